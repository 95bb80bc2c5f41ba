// A7: Weibull sampling of contact properties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "vorodec/model/weibull.hpp"

using vorodec::model::Distribution;

namespace {
// Kolmogorov-Smirnov statistic of samples against the Weibull CDF.
double ks_statistic(std::vector<double> x, double shape, double scale) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = 1.0 - std::exp(-std::pow(x[i] / scale, shape));
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  return d;
}
}  // namespace

TEST(Weibull, MeanKeyGivesScaleMeanOverGamma) {
  const auto d = Distribution::weibull_from_mean(3.0, 10.0);
  EXPECT_NEAR(d.weibull_scale, 10.0 / std::tgamma(1.0 + 1.0 / 3.0), 1e-12);
  EXPECT_NEAR(Distribution::weibull_from_scale(3.0, 10.0).mean(), 10.0 * 0.8929795, 1e-6);
}

TEST(Weibull, SamplesPassKolmogorovSmirnovAndMatchMean) {
  for (const double m : {1.0, 3.0, 10.0}) {
    const auto d = Distribution::weibull_from_mean(m, 24.24e6);
    const int n = 100000;
    std::vector<double> x(n);
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += x[static_cast<std::size_t>(i)] = d.sample(42, static_cast<std::uint64_t>(i), 3);
    EXPECT_NEAR(sum / n, 24.24e6, 0.01 * 24.24e6) << "shape " << m;
    // p > 0.01 <=> D < 1.628 / sqrt(n) (asymptotic KS critical value).
    EXPECT_LT(ks_statistic(x, m, d.weibull_scale), 1.628 / std::sqrt(n)) << "shape " << m;
  }
}

TEST(Weibull, SampleIsAPureFunctionOfSeedContactAndProperty) {
  const auto d = Distribution::weibull_from_mean(4.0, 1.0);
  EXPECT_EQ(d.sample(1, 77, 2), d.sample(1, 77, 2));
  EXPECT_NE(d.sample(1, 77, 2), d.sample(2, 77, 2));
  EXPECT_NE(d.sample(1, 77, 2), d.sample(1, 78, 2));
  EXPECT_NE(d.sample(1, 77, 2), d.sample(1, 77, 3));
  EXPECT_EQ(Distribution::constant(5.0).sample(1, 2, 3), 5.0);
}
