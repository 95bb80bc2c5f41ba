// Weibull keys and the keyed random stream (A7's distribution test is a verification case).
#include <gtest/gtest.h>

#include <cmath>

#include "vorodec/model/weibull.hpp"

using vorodec::model::Distribution;

TEST(Weibull, MeanKeyGivesScaleMeanOverGamma) {
  const auto d = Distribution::weibull_from_mean(3.0, 10.0);
  EXPECT_NEAR(d.weibull_scale, 10.0 / std::tgamma(1.0 + 1.0 / 3.0), 1e-12);
  EXPECT_NEAR(Distribution::weibull_from_scale(3.0, 10.0).mean(), 10.0 * 0.8929795, 1e-6);
}

TEST(Weibull, SampleIsAPureFunctionOfSeedContactAndProperty) {
  const auto d = Distribution::weibull_from_mean(4.0, 1.0);
  EXPECT_EQ(d.sample(1, 77, 2), d.sample(1, 77, 2));
  EXPECT_NE(d.sample(1, 77, 2), d.sample(2, 77, 2));
  EXPECT_NE(d.sample(1, 77, 2), d.sample(1, 78, 2));
  EXPECT_NE(d.sample(1, 77, 2), d.sample(1, 77, 3));
  EXPECT_EQ(Distribution::constant(5.0).sample(1, 2, 3), 5.0);
}
