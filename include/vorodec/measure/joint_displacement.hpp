#pragma once
// Joint displacement since a reference state: at each joint contact's current point, the two
// rigid blocks' relative displacement split into slip (along the joint) and opening (along its
// normal, separation positive), the largest of each per joint set (docs/loading.md#excavation).
#include <vector>

#include "vorodec/model/model.hpp"

namespace vorodec::measure {

// Where the blocks stood: centroids (m) and rotations (rad).
struct BlockPlacement {
  std::vector<double> x, y, theta;
};

BlockPlacement placement_of(const model::Blocks& bl);

// Contacts of law group first_law + k belong to joint set k (k < sets). Returns per set the
// largest slip and the largest opening (m), two numbers per set; zero where a set has no contact.
std::vector<double> joint_displacements(const model::Model& m, const BlockPlacement& at,
                                        int first_law, std::size_t sets);

}  // namespace vorodec::measure
