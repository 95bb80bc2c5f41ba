#pragma once
// Zoning of one convex block into constant-strain triangles (CGAL 2D constrained Delaunay mesher;
// CGAL stays inside src/geometry/zone_mesher.cpp).
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "vorodec/geometry/point.hpp"

namespace vorodec::geometry {

struct ZoneMesh {
  std::vector<Point> points;                        // gridpoints, m
  std::vector<std::array<std::uint32_t, 3>> zones;  // counter-clockwise triangles
  std::vector<std::uint32_t> boundary;  // boundary gridpoints counter-clockwise, starting at the
                                        // polygon's first corner
};

// Triangles no longer than `zone_size` on any edge (CGAL Delaunay_mesh_size_criteria_2, minimum
// angle about 20.7 degrees). `polygon` is counter-clockwise.
ZoneMesh mesh_polygon(std::span<const Point> polygon, double zone_size);

// The longest edge of a triangle whose centroid is p may be at most zone_size(p), m.
using ZoneSize = std::function<double(Point)>;
// Graded zoning: the same mesher with the bound taken where each triangle lies.
ZoneMesh mesh_polygon(std::span<const Point> polygon, const ZoneSize& zone_size);

}  // namespace vorodec::geometry
