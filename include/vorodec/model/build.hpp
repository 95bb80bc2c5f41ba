#pragma once
// Turns a tessellation into rigid blocks (mass properties, rounded corners) plus loading platens.
#include <optional>
#include <span>
#include <vector>

#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::model {

// A pressure-bar test's bars as columns of rectangular blocks (the platens are their first
// blocks).
struct BlockBars {
  double width = 0, block_length = 0;  // m
  int incident_blocks = 0, transmitted_blocks = 0;
  double incident_density = 0, transmitted_density = 0;  // kg/m^3
};

struct BuildSettings {
  double density = 0.0;                        // kg/m^3
  double rounding_length = 0.0;                // m, UDEC corner rounding d
  bool platens = true;                         // rigid platens above and below the specimen
  std::span<const double> block_density = {};  // kg/m^3 per specimen block; empty: `density`
  std::optional<BlockBars> bars = {};          // instead of the platens
};

// Specimen blocks zoned into constant-strain triangles of this size and material.
struct DeformableBuild {
  double zone_size = 0.0;  // m, longest zone edge
  ElasticMaterial material;
  std::vector<ElasticMaterial> block_material = {};  // per specimen block; empty: `material`
};

Model build_model(const geometry::Tessellation& tess, const BuildSettings& settings,
                  const std::optional<DeformableBuild>& deformable = std::nullopt);

// Appends one rigid block with the given world-frame polygon (counter-clockwise).
void add_block(Model& model, std::span<const Point> polygon, double density, Group group);

}  // namespace vorodec::model
