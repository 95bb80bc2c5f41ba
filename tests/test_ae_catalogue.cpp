#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "run_support.hpp"
#include "vorodec/measure/ae_catalogue.hpp"

namespace vorodec {
namespace {

using laws::ContactEvent;
using laws::CrackEvent;

CrackEvent crack(double t, double x, double y, double energy,
                 ContactEvent type = ContactEvent::tensile_failure) {
  return {t, x, y, 1.0, 0.0, 1e-3, 0, 1, type, energy};
}

// Radius 4 mm, shear waves at 2000 m/s: the window is 2 us.
const measure::AeSettings kSettings{4e-3, 2000.0, 1.0};

TEST(AeCatalogue, CracksWithinTheRadiusAndTheWaveWindowAreOneEvent) {
  const std::vector<CrackEvent> cracks{
      crack(0.0, 0.0, 0.0, 1.0),
      crack(1.5e-6, 3e-3, 0.0, 3.0, ContactEvent::shear_failure),  // near, within 2 us: joins
      crack(3.0e-6, 6e-3, 0.0, 1.0),   // 3 mm from the last crack, 1.5 us after it: joins
      crack(3.2e-6, 50e-3, 0.0, 2.0),  // far away: an event of its own
      crack(9.0e-6, 6e-3, 0.0, 1.0),   // near, but 6 us after the event's last crack: new
  };
  const auto events = measure::cluster_events(cracks, kSettings);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].cracks, 3u);
  EXPECT_EQ(events[0].type, measure::AeType::mixed);
  EXPECT_DOUBLE_EQ(events[0].energy, 5.0);
  EXPECT_DOUBLE_EQ(events[0].time, 0.0);
  EXPECT_DOUBLE_EQ(events[0].duration, 3.0e-6);
  EXPECT_NEAR(events[0].x, (3e-3 * 3.0 + 6e-3 * 1.0) / 5.0, 1e-15);  // energy-weighted
  EXPECT_EQ(events[1].cracks, 1u);
  EXPECT_EQ(events[1].type, measure::AeType::tensile);
  EXPECT_DOUBLE_EQ(events[1].x, 50e-3);
  EXPECT_EQ(events[2].cracks, 1u);
  EXPECT_DOUBLE_EQ(events[2].time, 9.0e-6);
}

TEST(AeCatalogue, MagnitudeFollowsTheGutenbergRichterEnergyRelation) {
  // log10 E = 1.5 M + 4.8: 1 kJ (1e3 J/m over 1 m) is magnitude -1.2.
  const auto events = measure::cluster_events(std::vector{crack(0, 0, 0, 1e3)}, kSettings);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NEAR(events[0].magnitude, -1.2, 1e-12);
  const auto thin =
      measure::cluster_events(std::vector{crack(0, 0, 0, 1e3)}, {4e-3, 2000.0, 0.001});
  EXPECT_NEAR(thin[0].magnitude, -1.2 - 2.0, 1e-12);  // a thousandth of the energy
}

// Magnitudes drawn from a Gutenberg-Richter law with b = 1 above -0.05, the lower edge of the
// 0.1 bin at 0 (a deterministic quantile sequence), one event each: the completeness magnitude
// is that bin, and Aki's estimate recovers b within twice its standard error.
TEST(AeCatalogue, AkisMaximumLikelihoodRecoversAPlantedBValue) {
  std::vector<CrackEvent> cracks;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n, m = -0.05 - std::log10(u) / 1.0;
    const double energy = std::pow(10.0, 1.5 * (m + 3.2));
    cracks.push_back(crack(i * 1.0, 0.0, 0.0, energy));  // 1 s apart: separate events
  }
  const auto events = measure::cluster_events(cracks, kSettings);
  ASSERT_EQ(events.size(), static_cast<std::size_t>(n));
  const measure::BValue b = measure::b_value(events);
  EXPECT_NEAR(b.mc, 0.0, 1e-12);  // the most populated 0.1 bin is the first
  EXPECT_NEAR(b.b, 1.0, 2.0 * b.error);
  EXPECT_NEAR(b.error, b.b / std::sqrt(static_cast<double>(b.events)), 1e-12);
}

TEST(AeCatalogue, TooFewEventsGiveNoBValue) {
  const auto events = measure::cluster_events(std::vector{crack(0, 0, 0, 1.0)}, kSettings);
  EXPECT_TRUE(std::isnan(measure::b_value(events).b));
}

// A run that cracks writes its events, and every crack of cracks.csv is in one of them.
TEST(AeCatalogue, ARunWritesEveryCrackIntoOneEvent) {
  namespace fs = std::filesystem;
  const fs::path out = testing::out_dir("ae_events");
  ASSERT_EQ(testing::run_vorodec("run " + std::string(VORODEC_SOURCE_DIR) +
                                 "/tests/models/e2e_small.toml --no-vtk --out " + out.string()),
            0);
  const auto cracks = testing::read_csv(out / "cracks.csv");
  const auto events = testing::read_csv(out / "ae_events.csv");
  ASSERT_GT(cracks.size(), 10u);
  ASSERT_FALSE(events.empty());
  double counted = 0, energy = 0;
  for (const auto& e : events) {
    counted += e[6];
    energy += e[4];
    EXPECT_LE(e[1], 1.0);  // durations are a few wave windows, not the run
  }
  EXPECT_EQ(counted, static_cast<double>(cracks.size()));
  EXPECT_GT(energy, 0.0);
  EXPECT_TRUE(fs::exists(out / "ae_events.vtp"));
}

}  // namespace
}  // namespace vorodec
