// Polygon mass properties of a rectangle (A1's random polygons are a verification case).
#include <gtest/gtest.h>

#include <cmath>

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
