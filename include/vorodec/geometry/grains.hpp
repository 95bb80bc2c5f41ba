#pragma once
// Grain-based specimens: grains (Voronoi cells, or polygons from a file) with a mineral each,
// subdivided into the rigid sub-blocks the solver uses. CGAL stays inside src/geometry.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::geometry {

enum class SubBlocks { voronoi, trigon };

// One grain: a simple counter-clockwise polygon and its mineral (index).
struct Grain {
  std::vector<Point> corners;
  std::int32_t mineral = 0;
};

struct GrainSettings {
  double grain_size = 0.0;      // m, diameter of the circle of the mean grain area
  double sub_block_size = 0.0;  // m, diameter of the circle of the mean sub-block area
  SubBlocks sub_blocks = SubBlocks::voronoi;
  int sub_block_lloyd_iterations = 3;  // relaxation of the Voronoi sub-blocks inside each grain
  std::vector<double> fractions;       // requested area fraction of each mineral (sum 1)
  std::vector<Grain> grains;           // given grains (a grain file); empty: Voronoi grains
};

// The outline, seed, grain Lloyd iterations and min_edge_length (applied to the sub-blocks)
// come from `settings`; with given grains the outline is their bounding box. Throws
// GeometryError for impossible input.
Tessellation tessellate_grains(const TessellationSettings& settings, const GrainSettings& grains);

// Minerals for grains of the given areas so that the mineral area fractions approach the
// requested ones: grains in a seeded random order, each to the mineral furthest below its target
// area. Every achieved fraction is within (minerals - 1) x largest grain area / total area.
std::vector<std::int32_t> assign_minerals(std::span<const double> grain_areas,
                                          std::span<const double> fractions, std::uint64_t seed);

}  // namespace vorodec::geometry
