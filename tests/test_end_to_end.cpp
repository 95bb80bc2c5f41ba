// A small model through the real command: outputs exist and read back, runs are reproducible,
// and the stress-strain curve matches the committed reference (tests/reference/).
#include <gtest/gtest.h>
#include <omp.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_support.hpp"

namespace fs = std::filesystem;
using namespace vorodec::testing;

namespace {

const fs::path model = fs::path(VORODEC_SOURCE_DIR) / "tests/models/e2e_small.toml";

// Columns: 2 axial_strain, 3 axial_stress.
double peak_of(const std::vector<std::vector<double>>& rows) {
  double p = 0;
  for (const auto& r : rows) p = std::max(p, r[3]);
  return p;
}

class EndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_code_ =
        run_vorodec("run " + model.string() + " --threads 1 --out " + out_dir("one").string());
  }
  static int run_code_;
};
int EndToEnd::run_code_ = -1;

}  // namespace

TEST_F(EndToEnd, RunReachesPostPeakAndWritesEveryOutput) {
  ASSERT_EQ(run_code_, 0);
  const fs::path out = base_dir() / "one";
  for (const char* f : {"history.csv", "summary.json", "cracks.csv", "rose.csv", "vtk/blocks.pvd",
                        "vtk/contacts.pvd", "vtk/cracks.pvd", "vtk/damage.pvd"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto rows = read_csv(out / "history.csv");
  const double peak = peak_of(rows);
  EXPECT_GT(peak, 5e6);
  EXPECT_LT(rows.back()[3], 0.6 * peak);           // ended after the peak, by its end condition
  EXPECT_GT(rows.back()[6] + rows.back()[7], 10);  // cracks formed
  const std::string summary = slurp(out / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"finished\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"peak_passed\": true"), std::string::npos) << summary;
}

TEST(PeakStress, OfARunStoppedWhileTheStressRisesIsReportedAsTheHighestStressNotAPeak) {
  const fs::path out = out_dir("stopped_rising");
  const Outcome o =
      run_capture("run " + model.string() + " --threads 1 --no-vtk --max-steps 3000 --out " +
                  out.string());
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_NE(o.output.find("highest stress (no peak"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("peak stress"), std::string::npos) << o.output;
  const std::string summary = slurp(out / "summary.json");
  EXPECT_NE(summary.find("\"peak_passed\": false"), std::string::npos) << summary;
}

TEST_F(EndToEnd, VtkSeriesReadsBackThroughVtk) {
  ASSERT_EQ(run_code_, 0);
  const fs::path vtk = base_dir() / "one/vtk";
  vtkNew<vtkXMLPolyDataReader> blocks;
  blocks->SetFileName((vtk / "blocks_000000.vtp").string().c_str());
  blocks->Update();
  EXPECT_GT(blocks->GetOutput()->GetNumberOfCells(), 150);
  EXPECT_NE(blocks->GetOutput()->GetCellData()->GetArray("displacement"), nullptr);
  std::size_t frames = 0;
  for (const auto& e : fs::directory_iterator(vtk))
    frames += e.path().filename().string().rfind("cracks_", 0) == 0;
  ASSERT_GE(frames, 2u);
  char name[32];
  std::snprintf(name, sizeof name, "cracks_%06zu.vtp", frames - 1);
  vtkNew<vtkXMLPolyDataReader> cracks;
  cracks->SetFileName((vtk / name).string().c_str());
  cracks->Update();
  const auto rows = read_csv(vtk.parent_path() / "history.csv");
  EXPECT_EQ(cracks->GetOutput()->GetNumberOfCells(),
            static_cast<vtkIdType>(rows.back()[6] + rows.back()[7]));
  EXPECT_NE(cracks->GetOutput()->GetCellData()->GetArray("type"), nullptr);
}

TEST_F(EndToEnd, SameSeedGivesIdenticalResultsWithOneAndTwoThreads) {
  ASSERT_EQ(run_code_, 0);
  const fs::path two = out_dir("two");
  ASSERT_EQ(run_vorodec("run " + model.string() + " --threads 2 --no-vtk --out " + two.string()),
            0);
  const auto a = read_csv(base_dir() / "one/history.csv");
  const auto b = read_csv(two / "history.csv");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {  // every column (energies too), bit for bit
    ASSERT_EQ(a[i].size(), b[i].size());
    for (std::size_t c = 0; c < a[i].size(); ++c)
      ASSERT_EQ(a[i][c], b[i][c]) << "row " << i << " column " << c;
  }
}

TEST_F(EndToEnd, PreparedSpecimenReproducesTheRunBitForBit) {
  ASSERT_EQ(run_code_, 0);
  const fs::path built = out_dir("built");
  ASSERT_EQ(run_vorodec("build " + model.string() + " --out " + built.string()), 0);
  ASSERT_TRUE(fs::exists(built / "specimen.vsp"));
  std::string text = slurp(model);
  const auto from = text.find("[specimen]"), to = text.find("[blocks]");
  text.replace(from, to - from,
               "[specimen]\nfile = \"" + (built / "specimen.vsp").string() + "\"\n\n");
  const fs::path reload_model = built / "reload.toml";
  std::ofstream(reload_model) << text;
  const fs::path again = out_dir("again");
  ASSERT_EQ(
      run_vorodec("run " + reload_model.string() + " --threads 1 --no-vtk --out " + again.string()),
      0);
  const auto a = read_csv(base_dir() / "one/history.csv");
  const auto b = read_csv(again / "history.csv");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "row " << i;
}

// Columns of history.csv: 6, 7 cracks, 8 failure_rate, 9 damage_density, 10 p21; of cracks.csv:
// 4 length. The 0.02 x 0.04 m rectangle is tiled exactly by its blocks.
TEST_F(EndToEnd, DamageMeasuresAgreeWithTheCrackList) {
  ASSERT_EQ(run_code_, 0);
  const fs::path out = base_dir() / "one";
  const double area = 0.02 * 0.04;
  const double tol = 1e-9;  // the CSV files hold 10 significant digits
  const auto history = read_csv(out / "history.csv");
  const auto cracks = read_csv(out / "cracks.csv");
  double length = 0;
  for (const auto& c : cracks) length += c[4];
  const auto& last = history.back();
  ASSERT_EQ(last[6] + last[7], static_cast<double>(cracks.size()));
  EXPECT_NEAR(last[10], length / area, tol * length / area);
  EXPECT_GT(last[9], 0.0);  // post-peak: failed contacts have opened
  EXPECT_LT(last[9], 1.0);
  for (std::size_t i = 1; i < history.size(); ++i)
    ASSERT_GE(history[i][10], history[i - 1][10]) << "P21 never falls, row " << i;

  // rose.csv: time, axial_stress, p21, p21_tensile, p21_shear, 18 bins each of all, tensile, shear.
  const auto rose = read_csv(out / "rose.csv");
  ASSERT_GE(rose.size(), 2u);
  const auto& r = rose.back();
  ASSERT_EQ(r.size(), 5u + 3u * 18u);
  double bins = 0, tensile = 0, shear = 0;
  for (std::size_t k = 0; k < 18; ++k) {
    bins += r[5 + k];
    tensile += r[23 + k];
    shear += r[41 + k];
    EXPECT_NEAR(r[5 + k], r[23 + k] + r[41 + k], tol * r[2]) << "bin " << k;
  }
  EXPECT_NEAR(r[2], last[10], tol * r[2]);
  EXPECT_NEAR(bins, r[2], tol * r[2]);
  EXPECT_NEAR(tensile, r[3], tol * r[2]);
  EXPECT_NEAR(shear, r[4], tol * r[2]);

  // The last damage grid: cell P21 x cell specimen area sums to the crack length.
  std::size_t frames = 0;
  for (const auto& e : fs::directory_iterator(out / "vtk"))
    frames += e.path().extension() == ".vti";
  ASSERT_EQ(frames, rose.size());
  char name[32];
  std::snprintf(name, sizeof name, "damage_%06zu.vti", frames - 1);
  vtkNew<vtkXMLImageDataReader> grid;
  grid->SetFileName((out / "vtk" / name).string().c_str());
  grid->Update();
  vtkImageData* img = grid->GetOutput();
  vtkDataArray* p21 = img->GetCellData()->GetArray("p21");
  vtkDataArray* cell_area = img->GetCellData()->GetArray("specimen_area");
  ASSERT_NE(p21, nullptr);
  ASSERT_NE(cell_area, nullptr);
  ASSERT_NE(img->GetCellData()->GetArray("damage_density"), nullptr);
  double grid_length = 0, grid_area = 0;
  for (vtkIdType k = 0; k < img->GetNumberOfCells(); ++k) {
    grid_length += p21->GetTuple1(k) * cell_area->GetTuple1(k);
    grid_area += cell_area->GetTuple1(k);
  }
  EXPECT_NEAR(grid_area, area, 1e-12 * area);
  EXPECT_NEAR(grid_length, length, tol * length);
}

// Regression against tests/reference/e2e_small_history.csv (regenerate:
// tests/regenerate_reference.sh). All builds agree bit for bit (-ffp-contract=off), but a change
// that only reorders floating-point operations moves this dynamic, density-scaled curve by up to
// ~2e-4 of the peak before the first crack (measured when the corner data were repacked), and crack
// order is chaotic after it. So the pre-crack curve is held to 1e-3 of the peak and the peak to 3
// %: physics changes show, round-off does not.
TEST_F(EndToEnd, StressStrainMatchesCommittedReference) {
  ASSERT_EQ(run_code_, 0);
  const auto ref = read_csv(fs::path(VORODEC_SOURCE_DIR) / "tests/reference/e2e_small_history.csv");
  const auto now = read_csv(base_dir() / "one/history.csv");
  ASSERT_GT(ref.size(), 10u);
  const double ref_peak = peak_of(ref);
  std::size_t compared = 0;
  for (std::size_t i = 0; i < std::min(ref.size(), now.size()); ++i) {
    if (ref[i][6] + ref[i][7] > 0 || ref[i][3] > 0.5 * ref_peak) break;  // first crack: stop
    EXPECT_NEAR(now[i][3], ref[i][3], 1e-3 * ref_peak) << "row " << i;
    ++compared;
  }
  EXPECT_GT(compared, 5u);
  EXPECT_NEAR(peak_of(now) / ref_peak, 1.0, 0.03);
}

// Energy balance (docs/theory.md §12) through a dynamic stress drop. With friction 10 deg and no
// dilation blocks slide far after the peak; a corner that slid past another corner used to be
// taken for that corner's duplicate until it had sunk in, and when finally found its spring
// energy came from nowhere: 12.6 % of the boundary work in this run. Columns: 11 boundary work,
// 12-16 strain, kinetic, damping, friction, breakage energy.
TEST(EnergyBalance, HoldsThroughTheStressDropOfASlidingSpecimen) {
  const fs::path out = out_dir("sliding");
  ASSERT_EQ(run_vorodec("run " + model.string() + " --threads 1 --no-vtk --out " + out.string() +
                        " --set seed=12 --set joints.friction=10 --set joints.dilation=0"
                        " --set stage[0].end_post_peak_fraction=0.3"),
            0);
  const auto rows = read_csv(out / "history.csv");
  ASSERT_GT(rows.size(), 10u);
  const auto& last = rows.back();
  EXPECT_LT(last[3], 0.3 * peak_of(rows));  // through the stress drop
  const double work = last[11];
  const double stored = last[12] + last[13] + last[14] + last[15] + last[16];
  EXPECT_GT(work, 0.0);
  EXPECT_LT(std::abs(work - stored), 0.01 * work);
}
