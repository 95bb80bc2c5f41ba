// Stiff and extreme cases (also listed in verification/REPORT.md): each run finishes or stops
// with a clear message, never NaN, a crash or a hang.
#include <gtest/gtest.h>

#include "cases.hpp"

TEST(Stability, StiffAndExtremeCasesFinishOrStopCleanly) {
  const auto outcomes = vorodec::verification::stability_cases(VORODEC_SOURCE_DIR, VORODEC_BINARY);
  ASSERT_EQ(outcomes.size(), 8u);
  for (const auto& o : outcomes) {
    EXPECT_TRUE(o.acceptable()) << o.name << " (" << o.change << "): exit " << o.exit_code
                                << ", status '" << o.status << "', finite " << o.finite;
    if (o.exit_code == 3) {
      EXPECT_NE(o.status.find("unstable: "), std::string::npos) << o.name;
    }
  }
}
