// Deformable blocks: zoning, zone forces, masses, contacts with rigid blocks, verification cases.
#include <gtest/gtest.h>

#include "cases.hpp"

using namespace vorodec::verification;

namespace {
::testing::AssertionResult passes(const CaseResult& r) {
  if (r.pass()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << r.id << " " << r.name << ": expected " << r.expected << ", measured " << r.measured
         << ", error " << r.error << " > tolerance " << r.tolerance << " (" << r.reference << ")";
}
}  // namespace

TEST(Deformable, A13PatchTestGivesExactUniformStress) {
  EXPECT_TRUE(passes(a13_patch_test()));
}

TEST(Deformable, ColumnMatchesElasticSolution) {
  for (const auto& r : deformable_column(0.02)) {
    EXPECT_TRUE(passes(r));
    std::printf("%s: %g (%s)\n", r.name.c_str(), r.error, r.settings.c_str());
  }
}
