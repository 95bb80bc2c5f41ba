// Damage measures (measure/damage.hpp) on hand-built states with known answers: three unit squares
// in a row, their bonds found by the real contact detection, contacts failed and opened by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scenes.hpp"
#include "vorodec/measure/damage.hpp"

using namespace vorodec;
using laws::ContactEvent;
using laws::CrackEvent;
using model::ContactState;
using model::Group;

namespace {

constexpr double a = 0.01;  // m, square side

// Squares [0,a], [a,2a], [2a,3a] side by side: two shared edges, two bonded contacts on each.
struct Row {
  model::Model m;
  std::unique_ptr<solver::Solver> solver;  // only its initial contact detection is used
  Row() {
    m.rounding_length = 0.01 * a;
    for (int i = 0; i < 3; ++i)
      model::add_block(m, verification::square(i * a, 0, a), 2600, Group::specimen);
    solver = verification::make_solver(m, "linear_elastic",
                                       verification::params({{"jkn", 1e10}, {"jks", 5e9}}), {});
  }
  // The contacts between blocks p and q.
  std::vector<model::Contact*> between(int p, int q) {
    std::vector<model::Contact*> out;
    for (auto& c : m.contacts)
      if (std::min(c.a, c.b) == p && std::max(c.a, c.b) == q) out.push_back(&c);
    return out;
  }
};

// A crack of the given length whose joint line lies at `deg` degrees from the x axis.
CrackEvent crack(double deg, double length, ContactEvent type, double x = 0.5 * a,
                 double y = 0.5 * a, int block_a = 0, int block_b = 1) {
  const double r = deg * M_PI / 180.0;
  // Normal perpendicular to the line direction (cos r, sin r).
  return {0.0, x, y, std::sin(r), -std::cos(r), length, block_a, block_b, type, 0.0};
}

}  // namespace

TEST(Damage, BaselineHoldsEveryInitialBondAndTheSpecimenArea) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  EXPECT_EQ(base.bonds.size(), 4u);
  EXPECT_EQ(row.between(0, 1).size(), 2u);
  EXPECT_EQ(row.between(1, 2).size(), 2u);
  EXPECT_EQ(base.bonds_per_block, (std::vector<std::uint32_t>{2, 4, 2}));
  EXPECT_NEAR(base.specimen_area, 3 * a * a, 1e-18);
  EXPECT_NEAR(base.lo.x, 0.0, 1e-15);
  EXPECT_NEAR(base.hi.x, 3 * a, 1e-15);
  EXPECT_NEAR(base.hi.y, a, 1e-15);
  EXPECT_NEAR(base.mean_block_size, a, 1e-15);
}

TEST(Damage, CrackOrientationIsTheJointLineAngleInZeroTo180) {
  EXPECT_NEAR(measure::crack_orientation_deg(crack(0, 1, ContactEvent::tensile_failure)), 0.0,
              1e-12);
  EXPECT_NEAR(measure::crack_orientation_deg(crack(90, 1, ContactEvent::tensile_failure)), 90.0,
              1e-12);
  EXPECT_NEAR(measure::crack_orientation_deg(crack(135, 1, ContactEvent::tensile_failure)), 135.0,
              1e-12);
  // A normal and its opposite describe the same line.
  EXPECT_NEAR(measure::crack_orientation_deg(crack(-30, 1, ContactEvent::tensile_failure)), 150.0,
              1e-12);
  EXPECT_NEAR(measure::crack_orientation_deg(crack(210, 1, ContactEvent::tensile_failure)), 30.0,
              1e-12);
  EXPECT_EQ(measure::rose_bin(0.0), 0u);
  EXPECT_EQ(measure::rose_bin(9.999), 0u);
  EXPECT_EQ(measure::rose_bin(10.0), 1u);
  EXPECT_EQ(measure::rose_bin(95.0), 9u);
  EXPECT_EQ(measure::rose_bin(179.999), 17u);
}

TEST(Damage, P21IsCrackLengthOverSpecimenAreaPerTenDegreeBinAndType) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  const std::vector<CrackEvent> cracks{
      crack(5, 1e-3, ContactEvent::tensile_failure), crack(15, 2e-3, ContactEvent::shear_failure),
      crack(92, 3e-3, ContactEvent::tensile_failure), crack(98, 4e-3, ContactEvent::shear_failure),
      crack(175, 5e-3, ContactEvent::tensile_failure)};
  const auto s = measure::measure_damage(row.m, cracks, base);
  const double area = 3 * a * a;
  EXPECT_EQ(s.cracks, 5u);
  EXPECT_EQ(s.cracks_tensile, 3u);
  EXPECT_EQ(s.cracks_shear, 2u);
  EXPECT_NEAR(s.p21, 15e-3 / area, 1e-12);
  EXPECT_NEAR(s.p21_tensile, 9e-3 / area, 1e-12);
  EXPECT_NEAR(s.p21_shear, 6e-3 / area, 1e-12);
  measure::Rose total{}, tensile{}, shear{};
  total[0] = tensile[0] = 1e-3 / area;
  total[1] = shear[1] = 2e-3 / area;
  total[9] = 7e-3 / area;
  tensile[9] = 3e-3 / area;
  shear[9] = 4e-3 / area;
  total[17] = tensile[17] = 5e-3 / area;
  for (std::size_t k = 0; k < measure::kRoseBins; ++k) {
    EXPECT_NEAR(s.rose[k], total[k], 1e-12) << k;
    EXPECT_NEAR(s.rose_tensile[k], tensile[k], 1e-12) << k;
    EXPECT_NEAR(s.rose_shear[k], shear[k], 1e-12) << k;
  }
}

TEST(Damage, FailureRateIsCracksOverInitialBonds) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  const std::vector<CrackEvent> cracks{crack(90, a / 2, ContactEvent::tensile_failure),
                                       crack(90, a / 2, ContactEvent::shear_failure),
                                       crack(90, a / 2, ContactEvent::shear_failure)};
  EXPECT_DOUBLE_EQ(measure::measure_damage(row.m, cracks, base).failure_rate, 3.0 / 4.0);
}

TEST(Damage, DamageDensityFromGapTimesLengthOfFailedContactsStillPresent) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  auto c01 = row.between(0, 1);
  auto c12 = row.between(1, 2);
  // Two failed contacts with known openings; a closed failed one and an opened intact one add
  // nothing.
  c01[0]->state = ContactState::tensile_failed;
  c01[0]->gap = 2e-6;
  c01[0]->length = 4e-3;
  c01[1]->state = ContactState::shear_failed;
  c01[1]->gap = 5e-6;
  c01[1]->length = 6e-3;
  c12[0]->state = ContactState::shear_failed;
  c12[0]->gap = -1e-6;
  c12[1]->gap = 9e-6;
  const double sc = 2e-6 * 4e-3 + 5e-6 * 6e-3;
  const auto s = measure::measure_damage(row.m, std::vector<CrackEvent>{}, base);
  EXPECT_NEAR(s.crack_area, sc, 1e-24);
  EXPECT_NEAR(s.damage_density, sc / (sc + 3 * a * a), 1e-15);
  EXPECT_EQ(measure::crack_openings(row.m, base).size(), 3u);
}

TEST(Damage, DeletedFailedContactOpensByTheCurrentGapOfItsCornerAgainstTheSameEdge) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  // Block 2 moves right by delta and its two failed contacts with block 1 are deleted.
  const double delta = 3e-5;
  row.m.blocks.x[2] += delta;
  row.m.blocks.refresh_world();
  std::erase_if(row.m.contacts, [](const model::Contact& c) { return std::max(c.a, c.b) == 2; });
  const auto openings = measure::crack_openings(row.m, base);
  ASSERT_EQ(openings.size(), 2u);
  for (const auto& o : openings) {
    EXPECT_NEAR(o.aperture, delta, 1e-15);
    EXPECT_NEAR(o.length, a / 2, 1e-15);
    EXPECT_NEAR(o.point.x, 2 * a + delta / 2, 1e-9);
  }
  const double sc = delta * a;
  const auto s = measure::measure_damage(row.m, std::vector<CrackEvent>{}, base);
  EXPECT_NEAR(s.crack_area, sc, 1e-15 * a);  // the apertures' round-off (coordinates ~3a) x a
  EXPECT_NEAR(s.damage_density, sc / (sc + 3 * a * a), 1e-15);
}

TEST(Damage, BlockFailedFractionCountsBothBlocksOfEachCrack) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  const std::vector<CrackEvent> cracks{
      crack(90, a / 2, ContactEvent::tensile_failure, a, 0.25 * a, 0, 1),
      crack(90, a / 2, ContactEvent::tensile_failure, a, 0.75 * a, 1, 0),
      crack(90, a / 2, ContactEvent::shear_failure, 2 * a, 0.25 * a, 1, 2)};
  EXPECT_EQ(measure::block_failed_fraction(cracks, base), (std::vector<double>{1.0, 0.75, 0.5}));
}

TEST(Damage, GridBinsCrackLengthAndOpeningByMidpointOverTheCellsSpecimenArea) {
  Row row;
  const auto base = measure::damage_baseline(row.m);
  auto c01 = row.between(0, 1);  // on x = a
  c01[0]->state = ContactState::tensile_failed;
  c01[0]->gap = 4e-6;
  const double sc = 4e-6 * c01[0]->length;
  const std::vector<CrackEvent> cracks{
      crack(90, 1e-3, ContactEvent::tensile_failure, 0.5 * a, 0.5 * a),
      crack(90, 2e-3, ContactEvent::tensile_failure, 1.5 * a, 0.2 * a),
      crack(90, 3e-3, ContactEvent::tensile_failure, 1.9 * a, 0.9 * a)};

  // Cells of side a: one per square.
  const auto g = measure::damage_grid(row.m, cracks, base, a);
  ASSERT_EQ(g.nx, 3u);
  ASSERT_EQ(g.ny, 1u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(g.specimen_area[k], a * a, 1e-18) << k;
  EXPECT_NEAR(g.p21[0], 1e-3 / (a * a), 1e-9);
  EXPECT_NEAR(g.p21[1], 5e-3 / (a * a), 1e-9);
  EXPECT_EQ(g.p21[2], 0.0);

  // Cells of side 2a: the second cell holds only the third square (clipped area).
  const auto h = measure::damage_grid(row.m, cracks, base, 2 * a);
  ASSERT_EQ(h.nx, 2u);
  ASSERT_EQ(h.ny, 1u);
  EXPECT_NEAR(h.specimen_area[0], 2 * a * a, 1e-18);
  EXPECT_NEAR(h.specimen_area[1], a * a, 1e-18);
  EXPECT_NEAR(h.p21[0], 6e-3 / (2 * a * a), 1e-9);
  EXPECT_EQ(h.crack_length[1], 0.0);
  EXPECT_NEAR(h.crack_area[0], sc, 1e-22);
  EXPECT_NEAR(h.damage_density[0], sc / (sc + 2 * a * a), 1e-15);
  EXPECT_EQ(h.damage_density[1], 0.0);

  // Cells of side 0.4a (not a divisor): the partial last column and top row hold the rest.
  const auto q = measure::damage_grid(row.m, cracks, base, 0.4 * a);
  EXPECT_EQ(q.nx, 8u);
  EXPECT_EQ(q.ny, 3u);
  double total = 0;
  for (double v : q.specimen_area) total += v;
  EXPECT_NEAR(total, 3 * a * a, 1e-18);
  EXPECT_NEAR(q.specimen_area[0], 0.16 * a * a, 1e-18);
  EXPECT_NEAR(q.specimen_area[7], 0.08 * a * a, 1e-18);      // last column: 0.2a x 0.4a
  EXPECT_NEAR(q.specimen_area[2 * 8], 0.08 * a * a, 1e-18);  // top row: 0.4a x 0.2a
}
