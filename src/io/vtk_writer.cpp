// ParaView output. The only translation unit that includes VTK headers.
#include "vorodec/io/vtk_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkType.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace vorodec::io {
namespace {

constexpr std::array<const char*, 3> kSeries = {"blocks", "contacts", "cracks"};
constexpr const char* kGridSeries = "damage";
constexpr const char* kZoneSeries = "zones";

std::string frame_file(const char* series, std::size_t frame) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06zu.%s", series, frame,
                std::string(series) == kGridSeries ? "vti" : "vtp");
  return buf;
}

void require_size(std::size_t actual, std::size_t expected, const char* what) {
  if (actual != expected) {
    throw std::invalid_argument("VtkSeriesWriter: VtkFrame::" + std::string(what) + " has " +
                                std::to_string(actual) + " entries, expected " +
                                std::to_string(expected));
  }
}

std::size_t block_count(const VtkFrame& f) {
  if (f.block_offsets.empty()) {
    require_size(f.block_points.size(), 0, "block_points (no block_offsets)");
    return 0;
  }
  if (f.block_offsets.front() != 0) {
    throw std::invalid_argument("VtkSeriesWriter: VtkFrame::block_offsets must start at 0");
  }
  for (std::size_t i = 1; i < f.block_offsets.size(); ++i) {
    if (f.block_offsets[i] < f.block_offsets[i - 1] + 3) {
      throw std::invalid_argument("VtkSeriesWriter: block " + std::to_string(i - 1) +
                                  " has fewer than 3 corners or decreasing block_offsets");
    }
  }
  require_size(f.block_points.size(), f.block_offsets.back(), "block_points");
  return f.block_offsets.size() - 1;
}

void validate(const VtkFrame& f) {
  const std::size_t nb = block_count(f);
  require_size(f.block_id.size(), nb, "block_id");
  require_size(f.block_group.size(), nb, "block_group");
  require_size(f.block_velocity.size(), nb, "block_velocity");
  require_size(f.block_displacement.size(), nb, "block_displacement");
  if (!f.block_failed_fraction.empty())
    require_size(f.block_failed_fraction.size(), nb, "block_failed_fraction");
  if (!f.block_grain.empty()) require_size(f.block_grain.size(), nb, "block_grain");
  if (!f.block_mineral.empty()) require_size(f.block_mineral.size(), nb, "block_mineral");
  if (!f.block_hidden.empty()) require_size(f.block_hidden.size(), nb, "block_hidden");
  const std::size_t nc = f.contact_point.size();
  require_size(f.contact_a.size(), nc, "contact_a");
  require_size(f.contact_b.size(), nc, "contact_b");
  require_size(f.contact_normal_force.size(), nc, "contact_normal_force");
  require_size(f.contact_shear_force.size(), nc, "contact_shear_force");
  require_size(f.contact_state.size(), nc, "contact_state");
  const std::size_t nk = f.crack_begin.size();
  require_size(f.crack_end.size(), nk, "crack_end");
  require_size(f.crack_type.size(), nk, "crack_type");
  require_size(f.crack_time.size(), nk, "crack_time");
  if (!f.crack_class.empty()) require_size(f.crack_class.size(), nk, "crack_class");
  const VtkGrid& g = f.grid;
  if (g.nx > 0 && !(g.cell > 0.0))
    throw std::invalid_argument("VtkSeriesWriter: VtkFrame::grid.cell must be positive");
  for (const auto& field : g.fields)
    require_size(field.values.size(), g.nx * g.ny, ("grid field " + field.name).c_str());
  const std::size_t nz = f.zone_block.size();
  require_size(f.zone_points.size(), 3 * nz, "zone_points");
  require_size(f.zone_stress.size(), nz, "zone_stress");
  require_size(f.zone_strain.size(), nz, "zone_strain");
}

vtkNew<vtkPoints> make_points(std::size_t n) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(n));
  return pts;
}

void set_point(vtkPoints* pts, std::size_t i, geometry::Point p) {
  pts->SetPoint(static_cast<vtkIdType>(i), p.x, p.y, 0.0);
}

vtkNew<vtkIntArray> int_array(const char* name, const std::vector<std::int32_t>& v) {
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(1);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), v[i]);
  return a;
}

vtkNew<vtkDoubleArray> double_array(const char* name, const std::vector<double>& v) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(1);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), v[i]);
  return a;
}

// 3-component vector (z = 0) so ParaView offers magnitude and glyphs.
vtkNew<vtkDoubleArray> vector_array(const char* name, const std::vector<geometry::Point>& v) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double t[3] = {v[i].x, v[i].y, 0.0};
    a->SetTypedTuple(static_cast<vtkIdType>(i), t);
  }
  return a;
}

void add_time(vtkDataObject* pd, double time) {
  vtkNew<vtkDoubleArray> t;
  t->SetName("TimeValue");
  t->SetNumberOfTuples(1);
  t->SetValue(0, time);
  pd->GetFieldData()->AddArray(t);
}

// The entries of per-block `v` for the blocks drawn.
template <class T>
std::vector<T> drawn(const std::vector<T>& v, const std::vector<std::size_t>& kept) {
  std::vector<T> out;
  out.reserve(kept.size());
  for (const std::size_t b : kept) out.push_back(v[b]);
  return out;
}

vtkNew<vtkPolyData> blocks_polydata(const VtkFrame& f) {
  const std::size_t nb = f.block_id.size();
  std::vector<std::size_t> kept;
  for (std::size_t b = 0; b < nb; ++b)
    if (f.block_hidden.empty() || !f.block_hidden[b]) kept.push_back(b);
  auto pts = make_points(f.block_points.size());
  for (std::size_t i = 0; i < f.block_points.size(); ++i) set_point(pts, i, f.block_points[i]);
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(kept.size()),
                       static_cast<vtkIdType>(f.block_points.size()));
  std::vector<vtkIdType> ids;
  for (const std::size_t b : kept) {
    ids.clear();
    for (std::uint32_t k = f.block_offsets[b]; k < f.block_offsets[b + 1]; ++k) ids.push_back(k);
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  auto* cd = pd->GetCellData();
  cd->AddArray(int_array("id", drawn(f.block_id, kept)));
  cd->AddArray(int_array("group", drawn(f.block_group, kept)));
  cd->AddArray(vector_array("velocity", drawn(f.block_velocity, kept)));
  cd->AddArray(vector_array("displacement", drawn(f.block_displacement, kept)));
  if (!f.block_failed_fraction.empty())
    cd->AddArray(double_array("failed_fraction", drawn(f.block_failed_fraction, kept)));
  if (!f.block_grain.empty()) cd->AddArray(int_array("grain", drawn(f.block_grain, kept)));
  if (!f.block_mineral.empty()) cd->AddArray(int_array("mineral", drawn(f.block_mineral, kept)));
  add_time(pd, f.time);
  return pd;
}

// One 3-point polyline per contact: centroid A -> contact point -> centroid B.
vtkNew<vtkPolyData> contacts_polydata(const VtkFrame& f) {
  const std::size_t nc = f.contact_point.size();
  auto pts = make_points(3 * nc);
  vtkNew<vtkCellArray> lines;
  lines->AllocateExact(static_cast<vtkIdType>(nc), static_cast<vtkIdType>(3 * nc));
  for (std::size_t c = 0; c < nc; ++c) {
    set_point(pts, 3 * c + 0, f.contact_a[c]);
    set_point(pts, 3 * c + 1, f.contact_point[c]);
    set_point(pts, 3 * c + 2, f.contact_b[c]);
    const auto base = static_cast<vtkIdType>(3 * c);
    const vtkIdType ids[3] = {base, base + 1, base + 2};
    lines->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetLines(lines);
  auto* cd = pd->GetCellData();
  cd->AddArray(double_array("normal_force", f.contact_normal_force));
  cd->AddArray(double_array("shear_force", f.contact_shear_force));
  cd->AddArray(int_array("state", f.contact_state));
  add_time(pd, f.time);
  return pd;
}

vtkNew<vtkPolyData> cracks_polydata(const VtkFrame& f) {
  const std::size_t nk = f.crack_begin.size();
  auto pts = make_points(2 * nk);
  vtkNew<vtkCellArray> lines;
  lines->AllocateExact(static_cast<vtkIdType>(nk), static_cast<vtkIdType>(2 * nk));
  for (std::size_t k = 0; k < nk; ++k) {
    set_point(pts, 2 * k + 0, f.crack_begin[k]);
    set_point(pts, 2 * k + 1, f.crack_end[k]);
    const auto base = static_cast<vtkIdType>(2 * k);
    const vtkIdType ids[2] = {base, base + 1};
    lines->InsertNextCell(2, ids);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetLines(lines);
  auto* cd = pd->GetCellData();
  cd->AddArray(int_array("type", f.crack_type));
  cd->AddArray(double_array("time", f.crack_time));
  if (!f.crack_class.empty()) cd->AddArray(int_array("class", f.crack_class));
  add_time(pd, f.time);
  return pd;
}

// An array of n 9-component (3 x 3) tensors, filled by the caller.
vtkNew<vtkDoubleArray> tensor_array(const char* name, std::size_t n) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(9);
  a->SetNumberOfTuples(static_cast<vtkIdType>(n));
  return a;
}

// Constant-strain triangles with their stress, principal stresses and strain.
vtkNew<vtkPolyData> zones_polydata(const VtkFrame& f) {
  const std::size_t nz = f.zone_block.size();
  auto pts = make_points(3 * nz);
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(nz), static_cast<vtkIdType>(3 * nz));
  auto stress = tensor_array("stress", nz), strain = tensor_array("strain", nz);
  std::vector<double> s1(nz), s2(nz), angle(nz);
  for (std::size_t z = 0; z < nz; ++z) {
    for (std::size_t k = 0; k < 3; ++k) set_point(pts, 3 * z + k, f.zone_points[3 * z + k]);
    const auto base = static_cast<vtkIdType>(3 * z);
    const vtkIdType ids[3] = {base, base + 1, base + 2};
    polys->InsertNextCell(3, ids);
    const auto& s = f.zone_stress[z];
    const auto& e = f.zone_strain[z];
    const double st[9] = {s[0], s[2], 0, s[2], s[1], 0, 0, 0, s[3]};
    const double et[9] = {e[0], e[2], 0, e[2], e[1], 0, 0, 0, 0};
    stress->SetTypedTuple(static_cast<vtkIdType>(z), st);
    strain->SetTypedTuple(static_cast<vtkIdType>(z), et);
    const double c = 0.5 * (s[0] + s[1]), r = std::hypot(0.5 * (s[0] - s[1]), s[2]);
    s1[z] = c + r;  // in-plane principal stresses, tension positive
    s2[z] = c - r;
    angle[z] = 0.5 * std::atan2(2 * s[2], s[0] - s[1]) * 180.0 / std::numbers::pi;
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  auto* cd = pd->GetCellData();
  cd->AddArray(int_array("block", f.zone_block));
  cd->AddArray(stress);
  cd->AddArray(double_array("principal_stress_max", s1));
  cd->AddArray(double_array("principal_stress_min", s2));
  cd->AddArray(double_array("principal_angle_deg", angle));
  cd->AddArray(strain);
  add_time(pd, f.time);
  return pd;
}

// A 2D image of nx x ny cells (nx + 1 by ny + 1 points) in the z = 0 plane.
vtkNew<vtkImageData> grid_image(const VtkFrame& f) {
  const VtkGrid& g = f.grid;
  vtkNew<vtkImageData> img;
  img->SetOrigin(g.origin.x, g.origin.y, 0.0);
  img->SetSpacing(g.cell, g.cell, g.cell);
  img->SetDimensions(static_cast<int>(g.nx + 1), static_cast<int>(g.ny + 1), 1);
  for (const auto& field : g.fields)
    img->GetCellData()->AddArray(double_array(field.name.c_str(), field.values));
  add_time(img, f.time);
  return img;
}

// Appended raw binary, zlib-compressed, 64-bit headers: the same for every series.
template <class Writer>
void write_xml(vtkDataObject* data, const std::filesystem::path& file) {
  // Written under a temporary name and renamed: a killed run leaves only whole frames.
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  vtkNew<Writer> w;
  w->SetFileName(tmp.string().c_str());
  w->SetInputData(data);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  w->SetCompressorTypeToZLib();
  w->SetHeaderTypeToUInt64();
  if (w->Write() != 1 || w->GetErrorCode() != 0) {
    throw std::runtime_error("VtkSeriesWriter: cannot write " + file.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("VtkSeriesWriter: cannot write " + file.string());
}

}  // namespace

void write_point_set(const VtkPointSet& set, const std::filesystem::path& file) {
  const std::size_t n = set.points.size();
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> pts = make_points(n);
  vtkNew<vtkCellArray> verts;
  for (std::size_t i = 0; i < n; ++i) {
    set_point(pts, i, set.points[i]);
    const vtkIdType id = static_cast<vtkIdType>(i);
    verts->InsertNextCell(1, &id);
  }
  pd->SetPoints(pts);
  pd->SetVerts(verts);
  for (const VtkPointSet::Field& f : set.fields) {
    require_size(f.values.size(), n, f.name.c_str());
    pd->GetPointData()->AddArray(double_array(f.name.c_str(), f.values));
  }
  write_xml<vtkXMLPolyDataWriter>(pd, file);
}

VtkSeriesWriter::VtkSeriesWriter(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_)) {
    throw std::runtime_error("VtkSeriesWriter: cannot create output directory '" + dir_.string() +
                             "'" + (ec ? ": " + ec.message() : std::string(": not a directory")));
  }
}

VtkSeriesWriter::VtkSeriesWriter(std::filesystem::path dir, Written written)
    : VtkSeriesWriter(std::move(dir)) {
  times_ = std::move(written.times);
  grid_ = written.grid;
  zones_ = written.zones;
  write_collections();
}

void VtkSeriesWriter::write(const VtkFrame& frame) {
  validate(frame);
  const std::size_t n = times_.size();
  const bool grid = frame.grid.nx > 0;
  if (n == 0) grid_ = grid;
  if (grid != grid_) {
    throw std::invalid_argument(
        "VtkSeriesWriter: every frame of a series must have a damage grid, or none");
  }
  const bool zones = !frame.zone_block.empty();
  if (n == 0) zones_ = zones;
  if (zones != zones_)
    throw std::invalid_argument(
        "VtkSeriesWriter: every frame of a series must have zones, or none");
  write_xml<vtkXMLPolyDataWriter>(blocks_polydata(frame), dir_ / frame_file(kSeries[0], n));
  write_xml<vtkXMLPolyDataWriter>(contacts_polydata(frame), dir_ / frame_file(kSeries[1], n));
  write_xml<vtkXMLPolyDataWriter>(cracks_polydata(frame), dir_ / frame_file(kSeries[2], n));
  if (grid_) write_xml<vtkXMLImageDataWriter>(grid_image(frame), dir_ / frame_file(kGridSeries, n));
  if (zones_)
    write_xml<vtkXMLPolyDataWriter>(zones_polydata(frame), dir_ / frame_file(kZoneSeries, n));
  times_.push_back(frame.time);
  write_collections();
}

// VTK 9.1 has no PVD writer. Each collection goes to a temporary file renamed over the old one, so
// a reader never sees a half-written .pvd.
void VtkSeriesWriter::write_collections() const {
  std::vector<const char*> series_list(kSeries.begin(), kSeries.end());
  if (grid_) series_list.push_back(kGridSeries);
  if (zones_) series_list.push_back(kZoneSeries);
  for (const char* series : series_list) {
    const auto target = dir_ / (std::string(series) + ".pvd");
    auto tmp = target;
    tmp += ".tmp";
    {
      std::ofstream out(tmp, std::ios::trunc);
      out << "<?xml version=\"1.0\"?>\n"
             "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
             "  <Collection>\n";
      for (std::size_t i = 0; i < times_.size(); ++i) {
        char t[40];
        std::snprintf(t, sizeof t, "%.17g", times_[i]);
        out << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << frame_file(series, i)
            << "\"/>\n";
      }
      out << "  </Collection>\n</VTKFile>\n";
      out.flush();
      if (!out) throw std::runtime_error("VtkSeriesWriter: cannot write " + tmp.string());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, target, ec);
    if (ec) {
      throw std::runtime_error("VtkSeriesWriter: cannot replace " + target.string() + ": " +
                               ec.message());
    }
  }
}

}  // namespace vorodec::io
