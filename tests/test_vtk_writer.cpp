// Round trip of the ParaView writer: frames written by VtkSeriesWriter are read back with VTK's own
// reader. This test and src/io/vtk_writer.cpp are the only files that include VTK headers.
//
// Output goes to $VORODEC_VTK_TEST_DIR if set, else <gtest temp dir>/vorodec_vtk_writer, and is
// left in place so that tests/run_paraview_check.sh can open <dir>/series/blocks.pvd afterwards.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vorodec/io/vtk_writer.hpp"

namespace {

namespace fs = std::filesystem;
using vorodec::geometry::Point;
using vorodec::io::VtkFrame;
using vorodec::io::VtkGrid;
using vorodec::io::VtkSeriesWriter;

fs::path output_root() {
  if (const char* env = std::getenv("VORODEC_VTK_TEST_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  // One folder per process: ctest runs each test as its own process, several at a time.
  return fs::path(::testing::TempDir()) / ("vorodec_vtk_writer_" + std::to_string(getpid()));
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = output_root() / name;
  fs::remove_all(dir);
  return dir;
}

// Times that only survive the .pvd with 17 significant digits.
const std::vector<double> kTimes = {0.0, 1.0e-4 / 3.0, 2.0e-4 / 3.0 + 1.0e-19};

// Two unit squares side by side; the right one moves right by 0.01 m per frame. One contact on
// their common edge. Frame k holds min(k, 2) cracks: none, a tensile one, then also a shear one.
VtkFrame synthetic_frame(int k) {
  VtkFrame f;
  f.time = kTimes.at(static_cast<std::size_t>(k));
  const double dx = 0.01 * k;
  f.block_points = {{0, 0},      {1, 0},      {1, 1},      {0, 1},
                    {1 + dx, 0}, {2 + dx, 0}, {2 + dx, 1}, {1 + dx, 1}};
  f.block_offsets = {0, 4, 8};
  f.block_id = {7, 8};
  f.block_group = {0, 1};
  f.block_velocity = {{0.0, 0.0}, {0.01 / 3.333e-5, -0.5}};
  f.block_displacement = {{0.0, 0.0}, {dx, 0.0}};
  f.contact_point = {{1 + dx / 2, 0.5}};
  f.contact_a = {{0.5, 0.5}};
  f.contact_b = {{1.5 + dx, 0.5}};
  f.contact_normal_force = {-1.25e6 * k};
  f.contact_shear_force = {3.5e5};
  f.contact_state = {k == 0 ? 0 : 2};
  if (k >= 1) {
    f.crack_begin.push_back({1.0, 0.2});
    f.crack_end.push_back({1.0, 0.8});
    f.crack_type.push_back(1);
    f.crack_time.push_back(kTimes[1]);
  }
  if (k >= 2) {
    f.crack_begin.push_back({0.2, 1.0});
    f.crack_end.push_back({0.8, 0.6});
    f.crack_type.push_back(2);
    f.crack_time.push_back(kTimes[2]);
  }
  return f;
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& file) {
  if (!fs::exists(file)) throw std::runtime_error("missing " + file.string());
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0) throw std::runtime_error("cannot read " + file.string());
  vtkSmartPointer<vtkPolyData> pd = reader->GetOutput();
  return pd;
}

std::vector<vtkIdType> cell_point_ids(vtkPolyData* pd, vtkIdType cell) {
  vtkNew<vtkIdList> ids;
  pd->GetCellPoints(cell, ids);
  std::vector<vtkIdType> out;
  for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i) out.push_back(ids->GetId(i));
  return out;
}

void expect_point(vtkPolyData* pd, vtkIdType id, Point p) {
  double xyz[3];
  pd->GetPoint(id, xyz);
  EXPECT_EQ(xyz[0], p.x) << "point " << id;
  EXPECT_EQ(xyz[1], p.y) << "point " << id;
  EXPECT_EQ(xyz[2], 0.0) << "point " << id;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct PvdEntry {
  double time;
  std::string file;
};

std::vector<PvdEntry> parse_pvd(const fs::path& file) {
  const std::string text = read_text(file);
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos) << text;
  EXPECT_NE(text.find("</Collection>"), std::string::npos) << text;
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos) << text;
  // Attribute values of each <DataSet .../> entry (no std::regex: GCC 12 warns inside it).
  const auto attribute = [](const std::string& tag, const std::string& name) {
    const std::string key = name + "=\"";
    const auto b = tag.find(key) + key.size();
    return tag.substr(b, tag.find('"', b) - b);
  };
  std::vector<PvdEntry> out;
  for (auto pos = text.find("<DataSet"); pos != std::string::npos;
       pos = text.find("<DataSet", pos + 1)) {
    const std::string tag = text.substr(pos, text.find("/>", pos) - pos);
    if (attribute(tag, "part") != "0") continue;
    out.push_back({std::stod(attribute(tag, "timestep")), attribute(tag, "file")});
  }
  return out;
}

class VtkSeriesWriterTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fresh_dir("series");
    VtkSeriesWriter writer(dir_);
    for (int k = 0; k < 3; ++k) writer.write(synthetic_frame(k));
    frames_ = writer.frames();
  }
  static fs::path dir_;
  static std::size_t frames_;
};
fs::path VtkSeriesWriterTest::dir_;
std::size_t VtkSeriesWriterTest::frames_ = 0;

TEST_F(VtkSeriesWriterTest, CountsWrittenFrames) {
  EXPECT_EQ(frames_, 3u);
}

TEST_F(VtkSeriesWriterTest, WritesSixDigitNumberedFilesPerSeriesAndFrame) {
  for (const char* series : {"blocks", "contacts", "cracks"}) {
    for (const char* n : {"000000", "000001", "000002"}) {
      EXPECT_TRUE(fs::exists(dir_ / (std::string(series) + "_" + n + ".vtp"))) << series << n;
    }
    EXPECT_FALSE(fs::exists(dir_ / (std::string(series) + "_000003.vtp")));
  }
}

TEST_F(VtkSeriesWriterTest, BlocksRoundTripAsPolygonsWithExactCoordinates) {
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const VtkFrame f = synthetic_frame(k);
    auto pd = read_vtp(dir_ / ("blocks_00000" + std::to_string(k) + ".vtp"));
    ASSERT_EQ(pd->GetNumberOfCells(), 2);
    ASSERT_EQ(pd->GetNumberOfPolys(), 2);
    ASSERT_EQ(pd->GetNumberOfPoints(), 8);
    EXPECT_EQ(pd->GetPoints()->GetDataType(), VTK_DOUBLE);
    EXPECT_EQ(cell_point_ids(pd, 1), (std::vector<vtkIdType>{4, 5, 6, 7}));
    for (vtkIdType i = 0; i < 8; ++i) expect_point(pd, i, f.block_points[static_cast<size_t>(i)]);
  }
}

TEST_F(VtkSeriesWriterTest, BlockCellDataRoundTrips) {
  const VtkFrame f = synthetic_frame(2);
  auto pd = read_vtp(dir_ / "blocks_000002.vtp");
  vtkCellData* cd = pd->GetCellData();
  ASSERT_NE(cd->GetArray("id"), nullptr);
  ASSERT_NE(cd->GetArray("group"), nullptr);
  ASSERT_NE(cd->GetArray("velocity"), nullptr);
  ASSERT_NE(cd->GetArray("displacement"), nullptr);
  EXPECT_EQ(cd->GetArray("id")->GetTuple1(0), 7);
  EXPECT_EQ(cd->GetArray("id")->GetTuple1(1), 8);
  EXPECT_EQ(cd->GetArray("group")->GetTuple1(1), 1);
  ASSERT_EQ(cd->GetArray("velocity")->GetNumberOfComponents(), 3);
  const double* v = cd->GetArray("velocity")->GetTuple3(1);
  EXPECT_EQ(v[0], f.block_velocity[1].x);
  EXPECT_EQ(v[1], f.block_velocity[1].y);
  EXPECT_EQ(v[2], 0.0);
  const double* u = cd->GetArray("displacement")->GetTuple3(1);
  EXPECT_EQ(u[0], f.block_displacement[1].x);
  EXPECT_EQ(u[2], 0.0);
}

TEST_F(VtkSeriesWriterTest, ContactIsOnePolylineFromCentroidAThroughContactPointToCentroidB) {
  const VtkFrame f = synthetic_frame(2);
  auto pd = read_vtp(dir_ / "contacts_000002.vtp");
  ASSERT_EQ(pd->GetNumberOfCells(), 1);
  ASSERT_EQ(pd->GetNumberOfLines(), 1);
  ASSERT_EQ(cell_point_ids(pd, 0).size(), 3u);
  const auto ids = cell_point_ids(pd, 0);
  expect_point(pd, ids[0], f.contact_a[0]);
  expect_point(pd, ids[1], f.contact_point[0]);
  expect_point(pd, ids[2], f.contact_b[0]);
  vtkCellData* cd = pd->GetCellData();
  ASSERT_NE(cd->GetArray("normal_force"), nullptr);
  ASSERT_NE(cd->GetArray("shear_force"), nullptr);
  ASSERT_NE(cd->GetArray("state"), nullptr);
  EXPECT_EQ(cd->GetArray("normal_force")->GetTuple1(0), -2.5e6);
  EXPECT_EQ(cd->GetArray("shear_force")->GetTuple1(0), 3.5e5);
  EXPECT_EQ(cd->GetArray("state")->GetTuple1(0), 2);
  EXPECT_EQ(cd->GetArray("state")->GetDataType(), VTK_INT);
}

TEST_F(VtkSeriesWriterTest, CracksRoundTripWithTypeAndTime) {
  const VtkFrame f = synthetic_frame(2);
  auto pd = read_vtp(dir_ / "cracks_000002.vtp");
  ASSERT_EQ(pd->GetNumberOfCells(), 2);
  ASSERT_EQ(pd->GetNumberOfLines(), 2);
  const auto ids = cell_point_ids(pd, 1);
  ASSERT_EQ(ids.size(), 2u);
  expect_point(pd, ids[0], f.crack_begin[1]);
  expect_point(pd, ids[1], f.crack_end[1]);
  vtkCellData* cd = pd->GetCellData();
  ASSERT_NE(cd->GetArray("type"), nullptr);
  ASSERT_NE(cd->GetArray("time"), nullptr);
  EXPECT_EQ(cd->GetArray("type")->GetTuple1(0), 1);
  EXPECT_EQ(cd->GetArray("type")->GetTuple1(1), 2);
  EXPECT_EQ(cd->GetArray("time")->GetTuple1(1), kTimes[2]);
}

TEST_F(VtkSeriesWriterTest, FrameWithoutCracksIsStillAReadableEmptyFile) {
  auto pd = read_vtp(dir_ / "cracks_000000.vtp");
  EXPECT_EQ(pd->GetNumberOfCells(), 0);
  EXPECT_EQ(pd->GetNumberOfPoints(), 0);
}

TEST_F(VtkSeriesWriterTest, CollectionsListEveryFrameWithFullPrecisionTimes) {
  for (const std::string series : {"blocks", "contacts", "cracks"}) {
    SCOPED_TRACE(series);
    const auto entries = parse_pvd(dir_ / (series + ".pvd"));
    ASSERT_EQ(entries.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(entries[k].time, kTimes[k]);  // exact: written with %.17g
      EXPECT_EQ(entries[k].file, series + "_00000" + std::to_string(k) + ".vtp");
      EXPECT_TRUE(fs::exists(dir_ / entries[k].file));
    }
  }
  EXPECT_FALSE(fs::exists(dir_ / "blocks.pvd.tmp"));
}

TEST(VtkSeriesWriter, CollectionIsRewrittenAfterEveryFrame) {
  const fs::path dir = fresh_dir("incremental");
  VtkSeriesWriter writer(dir);
  writer.write(synthetic_frame(0));
  EXPECT_EQ(parse_pvd(dir / "blocks.pvd").size(), 1u);
  writer.write(synthetic_frame(1));
  const auto entries = parse_pvd(dir / "cracks.pvd");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].time, kTimes[1]);
}

TEST(VtkSeriesWriter, FrameWithoutAnythingWritesValidFiles) {
  const fs::path dir = fresh_dir("empty");
  VtkSeriesWriter writer(dir);
  VtkFrame empty;
  empty.time = 1.5;
  writer.write(empty);
  for (const char* series : {"blocks", "contacts", "cracks"}) {
    auto pd = read_vtp(dir / (std::string(series) + "_000000.vtp"));
    EXPECT_EQ(pd->GetNumberOfCells(), 0) << series;
  }
  EXPECT_EQ(parse_pvd(dir / "contacts.pvd").at(0).time, 1.5);
}

TEST(VtkSeriesWriter, CreatesMissingNestedOutputDirectory) {
  const fs::path dir = fresh_dir("nested") / "a" / "b";
  VtkSeriesWriter writer(dir);
  EXPECT_TRUE(fs::is_directory(dir));
}

TEST(VtkSeriesWriter, ThrowsWhenOutputDirectoryCannotBeCreated) {
  const fs::path base = fresh_dir("blocked");
  fs::create_directories(base);
  std::ofstream(base / "file") << "not a directory";
  try {
    VtkSeriesWriter writer(base / "file" / "out");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create output directory"), std::string::npos)
        << e.what();
  }
}

TEST(VtkSeriesWriter, RejectsFrameWithInconsistentArraySizesAndWritesNothing) {
  const fs::path dir = fresh_dir("inconsistent");
  VtkSeriesWriter writer(dir);
  VtkFrame f = synthetic_frame(1);
  f.contact_state.clear();
  EXPECT_THROW(writer.write(f), std::invalid_argument);
  EXPECT_EQ(writer.frames(), 0u);
  EXPECT_FALSE(fs::exists(dir / "blocks_000000.vtp"));
  EXPECT_FALSE(fs::exists(dir / "blocks.pvd"));
}

// A frame with damage fields: each block's failed fraction and a 3 x 2 grid of 0.5 m cells.
VtkFrame damage_frame(int k) {
  VtkFrame f = synthetic_frame(k);
  f.block_failed_fraction = {0.25 * k, 0.5};
  f.grid = VtkGrid{{-0.5, 0.25}, 0.5, 3, 2, {}};
  f.grid.fields = {{"p21", {1, 2, 3, 4, 5, 6.5 + k}}, {"damage_density", {0, 0, 0.1, 0, 0, 0.2}}};
  return f;
}

TEST(VtkSeriesWriter, DamageGridIsAnImageDataSeriesWithCellFields) {
  const fs::path dir = fresh_dir("damage");
  VtkSeriesWriter writer(dir);
  for (int k = 0; k < 2; ++k) writer.write(damage_frame(k));
  const auto entries = parse_pvd(dir / "damage.pvd");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].time, kTimes[1]);
  EXPECT_EQ(entries[1].file, "damage_000001.vti");
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "damage_000001.vti").string().c_str());
  reader->Update();
  ASSERT_EQ(reader->GetErrorCode(), 0);
  vtkImageData* img = reader->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  EXPECT_EQ(dims[0], 4);
  EXPECT_EQ(dims[1], 3);
  EXPECT_EQ(dims[2], 1);
  EXPECT_EQ(img->GetNumberOfCells(), 6);
  double origin[3], spacing[3];
  img->GetOrigin(origin);
  img->GetSpacing(spacing);
  EXPECT_EQ(origin[0], -0.5);
  EXPECT_EQ(origin[1], 0.25);
  EXPECT_EQ(spacing[0], 0.5);
  EXPECT_EQ(spacing[1], 0.5);
  vtkDataArray* p21 = img->GetCellData()->GetArray("p21");
  ASSERT_NE(p21, nullptr);
  EXPECT_EQ(p21->GetTuple1(5), 7.5);
  // Cell (i, j) = (2, 0) is entry 2: the cell whose centre is (0.75, 0.5).
  double centre[3] = {0.75, 0.5, 0.0}, pcoords[3], weights[8];
  int sub = 0;
  EXPECT_EQ(img->FindCell(centre, nullptr, -1, 1e-9, sub, pcoords, weights), 2);
  ASSERT_NE(img->GetCellData()->GetArray("damage_density"), nullptr);
  EXPECT_EQ(img->GetCellData()->GetArray("damage_density")->GetTuple1(2), 0.1);
  auto blocks = read_vtp(dir / "blocks_000001.vtp");
  vtkDataArray* fraction = blocks->GetCellData()->GetArray("failed_fraction");
  ASSERT_NE(fraction, nullptr);
  EXPECT_EQ(fraction->GetTuple1(0), 0.25);
  EXPECT_EQ(fraction->GetTuple1(1), 0.5);
}

TEST(VtkSeriesWriter, SeriesWithoutGridWritesNoDamageFiles) {
  const fs::path dir = fresh_dir("no_grid");
  VtkSeriesWriter writer(dir);
  writer.write(synthetic_frame(0));
  EXPECT_FALSE(fs::exists(dir / "damage.pvd"));
  EXPECT_FALSE(fs::exists(dir / "damage_000000.vti"));
  EXPECT_EQ(read_vtp(dir / "blocks_000000.vtp")->GetCellData()->GetArray("failed_fraction"),
            nullptr);
}

TEST(VtkSeriesWriter, RejectsGridThatAppearsMidSeriesOrHasWrongFieldSize) {
  const fs::path dir = fresh_dir("grid_change");
  VtkSeriesWriter writer(dir);
  writer.write(synthetic_frame(0));
  EXPECT_THROW(writer.write(damage_frame(1)), std::invalid_argument);
  EXPECT_EQ(writer.frames(), 1u);
  VtkSeriesWriter other(fresh_dir("grid_size"));
  VtkFrame f = damage_frame(0);
  f.grid.fields[0].values.pop_back();
  EXPECT_THROW(other.write(f), std::invalid_argument);
}

}  // namespace
