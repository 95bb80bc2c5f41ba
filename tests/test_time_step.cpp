// solver.fixed_time_step: used as given below the critical step, capped at it (with one warning)
// above it, and re-checked when contact detection finds new contacts.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scenes.hpp"

using namespace vorodec;
using model::Group;

namespace {
constexpr double rho = 2600, a = 0.01, jkn = 1e10;  // kg/m^3, m, Pa/m

// Two squares side by side, `gap` apart, joined by a linear elastic law.
std::unique_ptr<solver::Solver> pair(model::Model& m, double gap, double fixed) {
  m.rounding_length = 0.01 * a;
  model::add_block(m, verification::square(0, 0, a), rho, Group::specimen);
  model::add_block(m, verification::square(a + gap, 0, a), rho, Group::specimen);
  solver::SolverSettings s;
  s.local_damping = 0.0;
  s.fixed_time_step = fixed;
  return verification::make_solver(m, "linear_elastic",
                                   verification::params({{"jkn", jkn}, {"jks", jkn}}), s);
}
}  // namespace

TEST(FixedTimeStep, BelowTheCriticalStepIsUsedAsGiven) {
  model::Model m;
  testing::internal::CaptureStderr();
  auto solver = pair(m, 0.0, 1e-8);
  const std::string err = testing::internal::GetCapturedStderr();
  ASSERT_GT(solver->critical_time_step(), 1e-8);
  EXPECT_EQ(solver->dt(), 1e-8);
  EXPECT_EQ(err, "");
}

TEST(FixedTimeStep, AboveTheCriticalStepIsCappedWithOneWarning) {
  model::Model m;
  testing::internal::CaptureStderr();
  auto solver = pair(m, 0.0, 1.0);
  for (int i = 0; i < 500; ++i) solver->step();  // several detections: still one warning
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(solver->dt(), solver->critical_time_step());
  EXPECT_LT(solver->dt(), 1e-3);
  EXPECT_NE(err.find("solver.fixed_time_step = 1 s"), std::string::npos) << err;
  EXPECT_NE(err.find("critical time step"), std::string::npos) << err;
  EXPECT_EQ(err.find("warning"), err.rfind("warning")) << err;
}

TEST(FixedTimeStep, IsRecheckedWhenANewContactAppears) {
  model::Model m;
  testing::internal::CaptureStderr();
  auto solver = pair(m, 0.2 * a, 1e-4);  // apart: free flight, no critical step
  EXPECT_EQ(solver->dt(), 1e-4);
  m.blocks.vx[0] = 0.1;
  while (m.contacts.empty() && solver->steps() < 10000) solver->step();
  for (int i = 0; i < 20; ++i) solver->step();  // the detection that found it set the step
  const std::string err = testing::internal::GetCapturedStderr();
  ASSERT_FALSE(m.contacts.empty());
  EXPECT_LT(solver->dt(), 1e-4);
  EXPECT_EQ(solver->dt(), solver->critical_time_step());
  EXPECT_NE(err.find("fixed_time_step"), std::string::npos);
}
