// Stiff and extreme cases (also listed in verification/REPORT.md): each run finishes or stops
// with a clear message, never NaN, a crash or a hang.
#include <gtest/gtest.h>

#include <algorithm>

#include "cases.hpp"

using vorodec::verification::StabilityOutcome;

TEST(Stability, StiffAndExtremeCasesFinishOrStopCleanly) {
  const auto outcomes = vorodec::verification::stability_cases(VORODEC_SOURCE_DIR, VORODEC_BINARY);
  ASSERT_EQ(outcomes.size(), 13u);
  for (const auto& o : outcomes) {
    EXPECT_TRUE(o.acceptable()) << o.name << " (" << o.change << "): exit " << o.exit_code
                                << ", status '" << o.status << "', finite " << o.finite;
    if (o.exit_code == 3) {
      EXPECT_NE(o.status.find("unstable: "), std::string::npos) << o.name;
    }
  }
  // Stiff joints on deformable blocks run stably (issue 26: they once stopped on energy from
  // nothing), with and without density scaling.
  for (const auto& o : outcomes) {
    if (o.name.rfind("deformable, stiff joints", 0) == 0) {
      EXPECT_EQ(o.exit_code, 0) << o.name;
    }
  }
  const auto fixed = std::find_if(outcomes.begin(), outcomes.end(), [](const StabilityOutcome& o) {
    return o.name == "fixed step above critical";
  });
  ASSERT_NE(fixed, outcomes.end());
  EXPECT_GT(fixed->time_step, 0.0);
  EXPECT_LT(fixed->time_step, 1e-6);  // the requested 1e-6 s was capped at the critical step
}

// The 1e5-step version of the report's 1e6-step undamped case.
TEST(Stability, UndampedElasticAssemblyKeepsItsEnergy) {
  const auto e = vorodec::verification::undamped_energy(100000);
  EXPECT_EQ(e.steps, 100000);
  EXPECT_LT(e.shadow, vorodec::verification::undamped_energy_bound);
  EXPECT_GT(e.plain, e.shadow);  // the plain sum carries the half-step oscillation
}
