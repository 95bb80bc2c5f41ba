#pragma once
// Mass properties of a simple polygon (docs/theory.md §3.1; [Steger1996]), unit thickness.
#include <span>

#include "vorodec/geometry/point.hpp"

namespace vorodec::model {

struct MassProperties {
  double area = 0.0;          // m^2
  geometry::Point centroid;   // m
  double polar_moment = 0.0;  // m^4, polar second moment of area about the centroid
};

// Vertices counter-clockwise; computed relative to vertex 0 to keep round-off small.
MassProperties mass_properties(std::span<const geometry::Point> polygon);

}  // namespace vorodec::model
