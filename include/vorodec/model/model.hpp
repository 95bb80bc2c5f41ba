#pragma once
// The model as plain arrays: rigid blocks (struct of arrays) and point contacts (array of records).
#include <omp.h>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "vorodec/checkpoint/archive.hpp"
#include "vorodec/geometry/point.hpp"
#include "vorodec/model/zoning.hpp"

namespace vorodec::model {

using geometry::Point;

// Which body a block is: the specimen or one of the loading platens.
// Pressure-bar tests with bars built from blocks add the bars' blocks (the platens are then the
// bars' first blocks).
enum class Group : std::int32_t {
  specimen = 0,
  bottom_platen = 1,
  top_platen = 2,
  incident_bar = 3,
  transmitted_bar = 4,
  // Removed by an excavation stage: held still, in contact with nothing, not drawn.
  excavated = 5
};
inline constexpr std::size_t kGroups = 6;

// Constants of a corner's rounded arc and of the block edge that starts at the corner.
struct CornerShape {
  double radius;       // m, arc radius
  double inv_length;   // 1/m, of the edge
  double s0, s1;       // m, where the edge's straight part (between the end arcs' tangent points)
                       // begins and ends along it
  std::uint32_t next;  // index of the next corner of the same block
  std::uint32_t prev;  // and of the previous one (in the padding: the record stays 40 bytes)
};
static_assert(sizeof(CornerShape) == 40);

struct CornerWorld {
  Point corner;  // unrounded corner, world frame
  Point centre;  // arc centre, world frame
};

// Blocks [first, second) of the calling thread in a parallel region: from `parts` (one cut more
// than threads) when it has one part per thread, else an equal share. The solver passes its
// contact parts' blocks, so that a thread moves and refreshes the blocks its contacts read.
inline std::pair<std::int64_t, std::int64_t> block_part(std::span<const std::size_t> parts,
                                                        std::int64_t n) {
  const int k = omp_get_num_threads(), t = omp_get_thread_num();
  if (parts.size() == static_cast<std::size_t>(k) + 1)
    return {static_cast<std::int64_t>(parts[static_cast<std::size_t>(t)]),
            static_cast<std::int64_t>(parts[static_cast<std::size_t>(t) + 1])};
  return {n * t / k, n * (t + 1) / k};
}

// The corner records that contact geometry reads, as plain pointers: a loop that stores a
// contact's one-byte state (which may alias anything) would otherwise reload them from the vectors.
struct CornerView {
  const CornerWorld* world;
  const CornerShape* shape;
};

struct BlockKinematics {
  double x, y, vx, vy, omega;
};

struct Blocks {
  std::vector<double> x, y, theta;    // centroid (m) and rotation (rad)
  std::vector<double> x0, y0;         // initial centroid (m)
  std::vector<double> vx, vy, omega;  // m/s, rad/s, at the half step
  // Inertial mass and polar moment (kg, kg m^2 per m); density scaling may raise them.
  std::vector<double> mass, inertia;
  std::vector<double> gravity_mass;    // true mass for body forces (kg per m)
  std::vector<double> true_inertia;    // true polar moment of inertia (kg m^2 per m)
  std::vector<double> fx, fy, moment;  // applied boundary loads of the current step (N, N m)
  std::vector<Group> group;
  std::vector<std::uint8_t> prescribed;  // 1: velocity set by the load path, not integrated
  // 1: zoned (Model::zoning); its corners follow boundary gridpoints, its centroid their mean.
  std::vector<std::uint8_t> deformable;
  // Shape, in the block's own frame (relative to the centroid at theta = 0), corners
  // counter-clockwise.
  std::vector<std::uint32_t> corner_begin;  // size blocks + 1
  std::vector<Point> corner;                // unrounded corner
  std::vector<Point> round_centre;          // centre of the rounded corner's arc
  std::vector<CornerShape> shape;           // per corner: arc and edge constants
  // Refreshed once per step by refresh_world(): cosine and sine of theta, world positions of
  // corners and arc centres, and the kinematics the contact loop reads (packed: one cache line
  // per block instead of five arrays).
  std::vector<double> cos_t, sin_t;
  std::vector<CornerWorld> world;
  std::vector<BlockKinematics> kin;

  std::size_t size() const { return x.size(); }
  std::uint32_t next_corner(std::uint32_t, std::uint32_t c) const { return shape[c].next; }
  std::uint32_t prev_corner(std::uint32_t, std::uint32_t c) const { return shape[c].prev; }
  CornerView corners() const { return {world.data(), shape.data()}; }
  // `skip_deformable`: leave the deformable blocks' corners and kinematics, which
  // refresh_deformable sets from their gridpoints. `parts`: each thread's blocks (block_part).
  void refresh_world(bool skip_deformable = false, std::span<const std::size_t> parts = {});
  Point to_world(std::uint32_t block, Point local) const {
    const double c = cos_t[block], s = sin_t[block];
    return {x[block] + c * local.x - s * local.y, y[block] + s * local.x + c * local.y};
  }
};

enum class ContactState : std::uint8_t {
  intact = 0,
  slipping = 1,
  tensile_failed = 2,
  shear_failed = 3
};

// A rounded corner of block a against block b's edge starting at corner `edge` (or, past the edge's
// straight part, against that edge's end corner). The normal points from b to a.
struct Contact {
  std::int32_t a = 0, b = 0;
  std::uint32_t corner = 0;   // global corner index of a
  std::uint32_t edge = 0;     // global corner index where b's edge starts
  std::uint64_t id = 0;       // stable id: keys the random stream of sampled properties
  double length = 0.0;        // m, joint length this contact represents
  double gap = 0.0;           // m, current gap (negative = overlap)
  double fn = 0.0, fs = 0.0;  // N per m thickness, normal force positive in compression
  // m, the shear coordinate (model::shear_coordinate) at the last step, with the edge it was on
  // and its ContactFrame::ray ((1, 0) on the straight part): the step's shear increment is the
  // coordinate's exact change while the edge stays the same.
  double shear = 0.0;
  Point shear_ray{1.0, 0.0};
  std::uint16_t law = 0;  // index of the contact law group that owns it
  ContactState state = ContactState::intact;
  std::uint8_t bonded = 0;  // 1: part of the initial tessellation (cohesive until it fails)
  std::uint32_t shear_edge = no_shear_edge;
  static constexpr std::uint32_t no_shear_edge = 0xffffffffu;  // new: no coordinate yet
};

// Force of one contact on block a and its moments about both centroids; block b receives the
// opposite force. The moments are taken in the contact loop, which has both centroids at hand, so
// that gathering a block's forces is additions only.
struct ContactForce {
  double fx = 0, fy = 0;
  double ma = 0, mb = 0;  // N m per m, moment of (fx, fy) about a's and about b's centroid
};

// Sum of the contact forces on one block and their moment about its centroid; one record so that
// a contact adds into one cache line per block, not three.
struct BlockForceSum {
  double fx = 0, fy = 0, m = 0;
};

struct Model {
  Blocks blocks;
  std::vector<Contact> contacts;
  double rounding_length = 0.0;  // m, UDEC corner rounding d
  double thickness = 1.0;        // m, out of plane
  Zoning zoning;                 // gridpoints and zones of the deformable blocks
};

// Checkpoints: what a run changes (positions, velocities, scaled masses, loads, the world arrays,
// contacts, gridpoints and zone state). Shapes and zones come again from the model file.
void save_state(checkpoint::OutArchive& ar, const Model& m);
void load_state(checkpoint::InArchive& ar, Model& m);

// Blocks::refresh_world() and then the deformable blocks from their gridpoints.
inline void refresh_world(Model& m, std::span<const std::size_t> parts = {}) {
  m.blocks.refresh_world(!m.zoning.empty(), parts);
  if (!m.zoning.empty()) refresh_deformable(m);
}

}  // namespace vorodec::model
