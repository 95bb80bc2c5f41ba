#pragma once
// A verification case as a GoogleTest assertion: on failure it says what was measured and why.
#include <gtest/gtest.h>

#include "cases.hpp"

namespace vorodec::verification {

inline ::testing::AssertionResult passes(const CaseResult& r) {
  if (r.pass()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << r.id << " " << r.name << ": expected " << r.expected << ", measured " << r.measured
         << ", error " << r.error << " > tolerance " << r.tolerance << " (" << r.reference << ")";
}

}  // namespace vorodec::verification
