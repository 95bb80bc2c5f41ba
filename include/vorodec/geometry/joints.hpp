#pragma once
// Jointed rock: a specimen's blocks cut by joint sets and by fractures from a file
// (docs/specimens.md#jointed-rock). Each joint trace splits the blocks it crosses from side to
// side; the part of a trace that ends inside a block is dropped, as UDEC's jset does, so the
// intact blocks' size sets how closely a non-persistent trace is followed.
#include <cstdint>
#include <span>
#include <vector>

#include "vorodec/geometry/tessellation.hpp"

namespace vorodec::geometry {

// One straight joint trace of set `set` (index into the model file's [[joint_set]] tables).
struct JointTrace {
  Point a, b;
  std::int32_t set = 0;
};

// A joint set by its statistics, over the specimen's outline.
struct JointSetGeometry {
  double dip_deg = 0;         // deg, trace direction counter-clockwise from the x axis
  double spacing = 0;         // m, normal distance between neighbouring joints (> 0)
  double trace = 0;           // m, trace length; 0: persistent (every joint crosses the outline)
  double gap = 0;             // m, rock bridge between traces along a joint
  Point origin;               // m, a point one joint passes through
  double dip_spread = 0;      // deg, standard deviation of each joint's dip
  double spacing_spread = 0;  // m, standard deviation of each spacing
};

// The traces of one set across the outline's bounding box (reproducible from `seed`).
std::vector<JointTrace> joint_set_traces(const JointSetGeometry& g, const Outline& outline,
                                         std::int32_t set, std::uint64_t seed);

// Cuts the blocks of `intact` by the traces, in order. Vertices within a fifth of the mean block
// edge of a trace first move onto it (outline vertices along the outline), so the joints stay
// straight and leave no slivers; nothing is collapsed afterwards. The result's joint_edges name
// every block pair whose shared edge lies on a trace with the two blocks on either side of it.
Tessellation cut_by_joints(const Tessellation& intact, std::span<const JointTrace> traces,
                           const TessellationSettings& settings);

}  // namespace vorodec::geometry
