// Deformable blocks: zoning, zone forces, lumped masses, contact with a rigid platen, and the
// verification cases A13 (patch test, column).
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <numeric>

#include "case_assertions.hpp"
#include "cases.hpp"
#include "run_support.hpp"
#include "scenes.hpp"
#include "vorodec/model/polygon.hpp"
#include "vorodec/model/zoning.hpp"

using namespace vorodec;
using namespace vorodec::verification;
namespace fs = std::filesystem;

namespace {
const model::ElasticMaterial rock{30e9, 0.25};
}  // namespace

TEST(Deformable, JointBetweenZonedBlocksHasItsNormalStiffness) {
  // Zones from the block's size down to 31 rounding lengths, and a rounding length 25 times
  // finer than the zones.
  for (const auto& [h, d] :
       {std::pair{0.05, 2e-4}, std::pair{0.00625, 2e-4}, std::pair{0.025, 1e-3}})
    EXPECT_TRUE(passes(deformable_joint(h, d)));
}

TEST(Deformable, A13PatchTestGivesExactUniformStress) {
  EXPECT_TRUE(passes(a13_patch_test()));
}

TEST(Deformable, ColumnMatchesElasticSolution) {
  for (const auto& r : deformable_column(0.02)) EXPECT_TRUE(passes(r)) << r.settings;
}

TEST(Deformable, ZoneForcesAreMinusHalfTheEdgeTractions) {
  // One well-shaped triangle: a single zone. docs/theory.md §4.3: F^a = -A sigma . grad N_a
  // = -(1/2) sum over the two edges meeting at a of (sigma . n_e) L_e.
  model::Model m;
  m.rounding_length = 1e-4;
  model::add_deformable_block(m, {{0, 0}, {0.01, 0.001}, {0.004, 0.009}}, 2600, rock, 1.0,
                              model::Group::specimen);
  auto& z = m.zoning;
  ASSERT_EQ(z.zones.size(), 1u);
  // A pure strain (symmetric gradient, no rotation): sigma is then also the nominal stress.
  const double exx = 2e-4, eyy = -1e-4, exy = 0.7e-4;
  for (std::size_t g = 0; g < 3; ++g) {
    z.x[g] += exx * z.x0[g] + exy * z.y0[g];
    z.y[g] += exy * z.x0[g] + eyy * z.y0[g];
  }
  std::vector<double> fx, fy;
  model::zone_forces(z, fx, fy);
  const model::ZoneStress s = z.stress(0);
  const auto& gp = z.zones[0].gp;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t a = gp[k], b = gp[(k + 1) % 3], c = gp[(k + 2) % 3];
    // Outward normal times length of a counter-clockwise edge p -> q: (dy, -dx).
    const auto traction = [&](std::size_t p, std::size_t q) {
      const double nx = z.y0[q] - z.y0[p], ny = -(z.x0[q] - z.x0[p]);
      return std::pair{s.xx * nx + s.xy * ny, s.xy * nx + s.yy * ny};
    };
    const auto [t1x, t1y] = traction(a, b);
    const auto [t2x, t2y] = traction(c, a);
    const double scale = std::abs(s.xx) * 0.01;
    EXPECT_NEAR(fx[a], -0.5 * (t1x + t2x), 1e-12 * scale);
    EXPECT_NEAR(fy[a], -0.5 * (t1y + t2y), 1e-12 * scale);
  }
  EXPECT_NEAR(fx[0] + fx[1] + fx[2], 0.0, 1e-12 * std::abs(fx[0]));
  // The stress is D eps of the linear displacement field (plane strain).
  const double l = rock.lambda(), G = rock.shear_modulus();
  const std::array<double, 3> e = z.strain(0);
  EXPECT_NEAR(s.xx, (l + 2 * G) * e[0] + l * e[1], 1e-9 * std::abs(s.xx));
  EXPECT_NEAR(s.zz, rock.poisson_ratio * (s.xx + s.yy), 1e-9 * std::abs(s.xx));
}

namespace {
// A zoned pentagon (about 40 zones) of the rock above.
model::Model zoned_pentagon() {
  model::Model m;
  m.rounding_length = 1e-4;
  const std::vector<model::Point> poly{
      {0, 0}, {0.02, 0}, {0.026, 0.012}, {0.01, 0.022}, {-0.004, 0.01}};
  model::add_deformable_block(m, poly, 2600, rock, 0.004, model::Group::specimen);
  return m;
}

// The pentagon's solver: stiff elastic contacts (it has none of its own) and local damping alpha.
auto pentagon_solver(model::Model& m, double alpha) {
  solver::SolverSettings s;
  s.local_damping = alpha;
  return make_solver(m, "linear_elastic", params({{"jkn", 1e13}, {"jks", 1e13}}), s);
}
}  // namespace

// Issue 26: the damping's work is booked at each step's mean velocity, which is what the kinetic
// energy at half steps loses to it (the balance closes to 5e-9 here); booked at the new
// velocity, a heavily damped vibration of a zoned block missed 4.7 % of its energy (measured).
TEST(Deformable, DampedVibrationKeepsItsEnergyBalance) {
  model::Model m = zoned_pentagon();
  auto solver = pentagon_solver(m, 0.8);
  auto& z = m.zoning;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {  // a stretching, shearing start
    z.vx[g] = 0.05 * (z.x[g] - 0.01) / 0.02;
    z.vy[g] = 0.03 * std::sin(200.0 * z.x[g]);
  }
  const double e0 = solver->kinetic_energy();
  for (int i = 0; i < 2000; ++i) solver->step();
  const double kept = solver->kinetic_energy() + model::zone_strain_energy(z);
  ASSERT_LT(kept, 0.5 * e0);  // the damping has taken most of it
  EXPECT_NEAR(kept + solver->energy().damping, e0, 1e-5 * e0);
}

// Issue 26: a deformable block turned rigidly keeps no stress, whatever the angle (1e-9 of the
// stress of a 1e-3 strain), and a strain turned with it turns its stress (objectivity).
TEST(Deformable, RigidRotationOfAnySizeLeavesTheZonesStressFree) {
  model::Model m = zoned_pentagon();
  auto& z = m.zoning;
  ASSERT_GT(z.zones.size(), 10u);
  const double scale = rock.youngs_modulus * 1e-3;
  std::vector<double> fx, fy;
  for (const double angle : {0.3, M_PI / 2, M_PI, 4.0}) {
    const double c = std::cos(angle), s = std::sin(angle);
    for (std::size_t g = 0; g < z.gridpoints(); ++g) {
      z.x[g] = 0.5 + c * z.x0[g] - s * z.y0[g];
      z.y[g] = -0.2 + s * z.x0[g] + c * z.y0[g];
    }
    model::zone_forces(z, fx, fy);
    for (std::size_t i = 0; i < z.zones.size(); ++i) {
      const model::ZoneStress t = z.stress(i);
      EXPECT_LT(std::abs(t.xx) + std::abs(t.yy) + std::abs(t.xy), 1e-9 * scale) << angle;
    }
  }
  // A uniaxial strain along x, then the block turned by 90 degrees: the stress is along y.
  std::vector<double> stretched_x(z.gridpoints());
  for (std::size_t g = 0; g < z.gridpoints(); ++g) stretched_x[g] = (1 + 1e-3) * z.x0[g];
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    z.x[g] = stretched_x[g];
    z.y[g] = z.y0[g];
  }
  model::zone_forces(z, fx, fy);
  const model::ZoneStress before = z.stress(0);
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    z.x[g] = -z.y0[g];
    z.y[g] = stretched_x[g];
  }
  model::zone_forces(z, fx, fy);
  EXPECT_NEAR(z.stress(0).yy, before.xx, 1e-9 * scale);
  EXPECT_NEAR(z.stress(0).xx, before.yy, 1e-9 * scale);
  EXPECT_NEAR(z.stress(0).xy, 0.0, 1e-9 * scale);
}

// A free deformable block spinning a turn and a quarter keeps its energy (kinetic + strain)
// within 0.1 %, and its zones carry only the centripetal stress (rho omega^2 R^2 scale) at every
// stage of the turn, not a stress of the angle turned.
TEST(Deformable, SpinningBlockKeepsItsEnergy) {
  model::Model m = zoned_pentagon();
  auto solver = pentagon_solver(m, 0.0);
  auto& z = m.zoning;
  const int turn = 20000;  // steps
  const double omega = 2 * M_PI / (turn * solver->dt());
  double cx = 0, cy = 0, mass = 0;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    cx += z.mass[g] * z.x[g];
    cy += z.mass[g] * z.y[g];
    mass += z.mass[g];
  }
  cx /= mass;
  cy /= mass;
  double radius = 0;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    z.vx[g] = -omega * (z.y[g] - cy);
    z.vy[g] = omega * (z.x[g] - cx);
    radius = std::max(radius, std::hypot(z.x[g] - cx, z.y[g] - cy));
  }
  const double e0 = solver->kinetic_energy();
  const double gx = z.x[0] - cx, gy = z.y[0] - cy;  // gridpoint 0 from the centre
  const double centripetal = 2600 * omega * omega * radius * radius;
  for (int i = 1; i <= turn + turn / 4; ++i) {
    solver->step();
    if (i % (turn / 8) != 0) continue;
    for (std::size_t k = 0; k < z.zones.size(); ++k) {
      const model::ZoneStress t = z.stress(k);
      ASSERT_LT(std::max({std::abs(t.xx), std::abs(t.yy), std::abs(t.xy)}), centripetal)
          << "step " << i;
    }
  }
  EXPECT_NEAR(solver->kinetic_energy() + model::zone_strain_energy(z), e0, 1e-3 * e0);
  // It has turned: gridpoint 0 is where a quarter turn takes it (the centre does not move).
  EXPECT_NEAR(z.x[0] - cx, -gy, 0.02 * radius);
  EXPECT_NEAR(z.y[0] - cy, gx, 0.02 * radius);
}

// Issue 26: boundary gridpoints along a straight edge (180 degree corners) take the 4d arc cap
// after any rigid turn, and their arc centre lies inside the block; round-off in the radius
// once put the centre on the edge, and detection then chose a neighbour edge by chance.
TEST(Deformable, StraightBoundaryGridpointsTakeTheCappedArc) {
  model::Model m = zoned_pentagon();
  auto& z = m.zoning;
  const auto& bl = m.blocks;
  const double d = m.rounding_length;
  std::size_t straight = 0;
  for (const double angle : {0.0, 0.37, 1.9, 3.3}) {
    const double c = std::cos(angle), s = std::sin(angle);
    for (std::size_t g = 0; g < z.gridpoints(); ++g) {
      z.x[g] = 0.013 + c * z.x0[g] - s * z.y0[g];
      z.y[g] = -0.07 + s * z.x0[g] + c * z.y0[g];
    }
    model::refresh_deformable(m);
    for (std::uint32_t k = bl.corner_begin[0]; k < bl.corner_begin[1]; ++k) {
      const auto g = static_cast<std::size_t>(z.corner_gp[k]);
      const auto prev =
          static_cast<std::size_t>(z.corner_gp[k == 0 ? bl.corner_begin[1] - 1 : k - 1]);
      const auto next = static_cast<std::size_t>(z.corner_gp[bl.shape[k].next]);
      const double turn = (z.x0[g] - z.x0[prev]) * (z.y0[next] - z.y0[g]) -
                          (z.y0[g] - z.y0[prev]) * (z.x0[next] - z.x0[g]);
      if (std::abs(turn) > 1e-12) continue;  // a polygon corner, not a straight gridpoint
      ++straight;
      EXPECT_EQ(bl.shape[k].radius, 4.0 * d) << "gridpoint " << g << ", angle " << angle;
      const model::Point off = bl.world[k].centre - bl.world[k].corner;
      EXPECT_NEAR(std::sqrt(dot(off, off)), 4.0 * d, 1e-9 * d);
    }
  }
  EXPECT_GT(straight, 8u);
}

TEST(Deformable, LumpedMassesSumToBlockMass) {
  model::Model m;
  m.rounding_length = 1e-4;
  const std::vector<model::Point> poly{
      {0, 0}, {0.02, 0}, {0.026, 0.012}, {0.01, 0.022}, {-0.004, 0.01}};
  model::add_deformable_block(m, poly, 2600, rock, 0.003, model::Group::specimen);
  const auto& z = m.zoning;
  ASSERT_GT(z.zones.size(), 20u);
  const double total = std::accumulate(z.gravity_mass.begin(), z.gravity_mass.end(), 0.0);
  const double block = 2600 * model::mass_properties(poly).area;
  EXPECT_NEAR(total, block, 1e-12 * block);
  EXPECT_NEAR(m.blocks.gravity_mass[0], block, 1e-12 * block);
  // Every zone respects the size criterion and has positive area.
  for (const auto& q : z.zones) {
    EXPECT_GT(q.area, 0.0);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto p = q.gp[k], r = q.gp[(k + 1) % 3];
      EXPECT_LE(std::hypot(z.x0[p] - z.x0[r], z.y0[p] - z.y0[r]), 0.003 * (1 + 1e-9));
    }
  }
}

TEST(Deformable, BlockRestingOnRigidPlatenCarriesItsWeight) {
  model::Model m;
  m.rounding_length = 1e-4;
  model::add_deformable_block(m, square(0, 0, 0.02), 2600, rock, 0.01, model::Group::specimen);
  model::add_block(m,
                   std::vector<model::Point>{{-0.01, -0.01}, {0.03, -0.01}, {0.03, 0}, {-0.01, 0}},
                   2600, model::Group::bottom_platen);
  solver::SolverSettings s;
  s.gravity = {0, -9.81};
  auto solver = make_solver(m, "linear_elastic", params({{"jkn", 1e13}, {"jks", 1e13}}), s);
  for (int i = 0; i < 3000; ++i) solver->step();
  const double weight = 2600 * 0.02 * 0.02 * 9.81;
  EXPECT_NEAR(-solver->contact_force(1).y, weight, 1e-6 * weight);
  EXPECT_NEAR(solver->contact_force(1).x, 0.0, 1e-6 * weight);
  // The zones carry it: mean sigma_yy = -weight / 2 / width (linear in depth, zero at the top).
  const model::ZoneStress mean = model::mean_stress(m, model::Group::specimen);
  EXPECT_NEAR(mean.yy, -0.5 * weight / 0.02, 0.01 * weight / 0.02);
}

TEST(Deformable, RunIsThreadInvariantAndWritesZones) {
  namespace t = vorodec::testing;
  const std::string model = std::string(VORODEC_SOURCE_DIR) + "/tests/models/deformable_small.toml";
  const auto one = t::out_dir("deformable_1"), two = t::out_dir("deformable_2");
  // The elastic part of the run (cracks start near 25 MPa): short enough for sanitizer builds.
  const std::string args = "run " + model + " --max-steps 1500 --out ";
  ASSERT_EQ(t::run_vorodec(args + one.string() + " --threads 1"), 0);
  ASSERT_EQ(t::run_vorodec(args + two.string() + " --threads 2 --no-vtk"), 0);
  EXPECT_EQ(t::slurp(one / "history.csv"), t::slurp(two / "history.csv"));
  // Before the first crack, the zones' mean axial stress is the platens' axial stress
  // (quasi-static loading).
  const auto rows = t::read_csv(one / "history.csv");
  int checked = 0;
  for (const auto& r : rows) {
    if (r[6] + r[7] > 0) break;  // cracks_tensile, cracks_shear
    if (r[3] < 5e6) continue;    // axial_stress, Pa
    EXPECT_NEAR(r[18], r[3], 0.02 * r[3]) << "zone_stress_yy at step " << r[0];
    ++checked;
  }
  EXPECT_GT(checked, 10);
  const std::string summary = t::slurp(one / "summary.json");
  EXPECT_GT(t::json_number(summary, "zones"), 500);
  ASSERT_TRUE(fs::exists(one / "vtk/zones.pvd"));
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  reader->SetFileName((one / "vtk/zones_000001.vtp").string().c_str());
  reader->Update();
  vtkPolyData* pd = reader->GetOutput();
  EXPECT_EQ(pd->GetNumberOfCells(), static_cast<vtkIdType>(t::json_number(summary, "zones")));
  vtkDataArray* stress = pd->GetCellData()->GetArray("stress");
  ASSERT_NE(stress, nullptr);
  EXPECT_EQ(stress->GetNumberOfComponents(), 9);
  for (const char* name : {"principal_stress_max", "principal_stress_min", "strain", "block"})
    EXPECT_NE(pd->GetCellData()->GetArray(name), nullptr) << name;
  fs::remove_all(t::base_dir());
}

TEST(Deformable, ParallelPartsGiveTheSameCracksAndStressesForAnyThreadCount) {
  namespace t = vorodec::testing;
  const std::string model = std::string(VORODEC_SOURCE_DIR) + "/tests/models/deformable_small.toml";
  const auto one = t::out_dir("deformable_parallel_1"), three = t::out_dir("deformable_parallel_3");
  // 302 blocks, 3,982 zones and 2,183 contacts: past every loop's threshold for thread parts
  // (contacts, zones, gridpoints, blocks); weak joints, so that cracks start within the run.
  const std::string args =
      "run " + model +
      " --max-steps 1500 --no-vtk --set specimen.block_count=300 --set blocks.zone_size=1e-3 "
      "--set joints.tension=2e6 --set joints.cohesion=4e6 --out ";
  ASSERT_EQ(t::run_vorodec(args + one.string() + " --threads 1"), 0);
  ASSERT_EQ(t::run_vorodec(args + three.string() + " --threads 3"), 0);
  const auto a = t::read_csv(one / "history.csv"), b = t::read_csv(three / "history.csv");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.back()[6] + a.back()[7], 50);  // cracks_tensile + cracks_shear
  // Every column (kinematics, stress, cracks, energies, the zones' mean stress), bit for bit.
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].size(), b[i].size());
    for (std::size_t c = 0; c < a[i].size(); ++c)
      ASSERT_EQ(a[i][c], b[i][c]) << "row " << i << " column " << c;
  }
  EXPECT_GT(t::json_number(t::slurp(one / "summary.json"), "initial_contacts"), 1024);
}

TEST(Deformable, CornerArcsMatchRigidBlockRounding) {
  // The trigonometry-free arcs of deformable blocks equal the rigid builder's at real corners;
  // at gridpoints along an edge the arc is tangent to the edge at the gridpoint.
  const std::vector<model::Point> poly{{0, 0}, {0.02, 0.002}, {0.024, 0.015}, {0.006, 0.02}};
  model::Model m;
  m.rounding_length = 5e-4;
  model::add_block(m, poly, 2600, model::Group::specimen);
  model::add_deformable_block(m, poly, 2600, rock, 0.004, model::Group::specimen);
  m.blocks.refresh_world();
  model::refresh_deformable(m);
  const auto& bl = m.blocks;
  std::size_t matched = 0;
  for (std::uint32_t c = bl.corner_begin[1]; c < bl.corner_begin[2]; ++c) {
    const model::Point p = bl.world[c].corner;
    for (std::uint32_t k = bl.corner_begin[0]; k < bl.corner_begin[1]; ++k) {
      const model::Point q = bl.world[k].corner;
      if (std::hypot(p.x - q.x, p.y - q.y) > 1e-12) continue;
      EXPECT_NEAR(bl.shape[c].radius, bl.shape[k].radius, 1e-12);
      EXPECT_NEAR(bl.world[c].centre.x, bl.world[k].centre.x, 1e-12);
      EXPECT_NEAR(bl.world[c].centre.y, bl.world[k].centre.y, 1e-12);
      ++matched;
    }
    // The arc touches the edge that leaves the corner: its centre lies R inside that edge.
    const model::Point e = bl.world[bl.shape[c].next].corner - p;
    const double inside = geometry::cross(e, bl.world[c].centre - p) / std::hypot(e.x, e.y);
    EXPECT_NEAR(inside, bl.shape[c].radius, 1e-12);
  }
  EXPECT_EQ(matched, poly.size());
  EXPECT_GT(bl.corner_begin[2] - bl.corner_begin[1], poly.size());
}
