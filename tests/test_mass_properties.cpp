// A1: polygon mass properties against exact formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "vorodec/model/polygon.hpp"

using vorodec::geometry::Point;
using vorodec::model::mass_properties;

TEST(MassProperties, RectangleFarFromOriginMatchesClosedForm) {
  const double w = 0.003, h = 0.002, x0 = 0.0456, y0 = -0.0789;
  const std::vector<Point> p{{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
  const auto m = mass_properties(p);
  EXPECT_NEAR(m.area, w * h, 1e-12 * w * h);
  EXPECT_NEAR(m.centroid.x, x0 + w / 2, 1e-12 * std::abs(x0));
  EXPECT_NEAR(m.centroid.y, y0 + h / 2, 1e-12 * std::abs(y0));
  const double j = w * h * (w * w + h * h) / 12.0;
  EXPECT_NEAR(m.polar_moment, j, 1e-12 * j);
}

// Random convex polygons: regular n-gons of random radius, rotation and position, whose exact
// area and polar moment are known: A = n r^2 sin(2 pi / n) / 2, J = A r^2 (2 + cos(2 pi / n)) / 6.
TEST(MassProperties, RandomRegularPolygonsMatchExactValuesTo1e12) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + static_cast<int>(u(rng) * 10);
    const double r = 1e-3 * (0.5 + u(rng)), phase = u(rng) * 6.28;
    const Point c{u(rng) * 0.1, u(rng) * 0.1};
    std::vector<Point> p;
    for (int i = 0; i < n; ++i) {
      const double a = phase + 2 * std::numbers::pi * i / n;
      p.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
    }
    const auto m = mass_properties(p);
    const double t = 2 * std::numbers::pi / n;
    const double area = 0.5 * n * r * r * std::sin(t);
    const double j = area * r * r * (2 + std::cos(t)) / 6.0;
    EXPECT_NEAR(m.area, area, 1e-12 * area);
    EXPECT_NEAR(m.centroid.x, c.x, 1e-12 * 0.1);
    EXPECT_NEAR(m.centroid.y, c.y, 1e-12 * 0.1);
    EXPECT_NEAR(m.polar_moment, j, 1e-11 * j);
  }
}
