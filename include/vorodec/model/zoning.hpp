#pragma once
// Deformable blocks (docs/theory.md §4): each is zoned into constant-strain triangles whose corners
// are gridpoints with lumped mass. Stress is linear elasticity (plane strain) in each zone's own
// frame (co-rotational, total): F = I + grad u over the initial zone, F = R U (polar
// decomposition), Biot strain U - I, stress T = D (U - I), turned to the world as R T R^T. A
// rigid rotation of any size is stress-free, a uniform strain gives exactly uniform stress (patch
// test), the zone forces derive from the strain energy (no drift), and for small rotations this is
// small-strain elasticity.
#include <array>
#include <cstdint>
#include <vector>

#include "vorodec/geometry/point.hpp"
#include "vorodec/geometry/zone_mesh.hpp"

namespace vorodec::model {

using geometry::Point;

// Isotropic linear elasticity, plane strain.
struct ElasticMaterial {
  double youngs_modulus = 0;  // Pa
  double poisson_ratio = 0;
  double lambda() const {
    return youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }
  double shear_modulus() const { return youngs_modulus / (2 * (1 + poisson_ratio)); }
};

// One constant-strain triangle: gridpoints counter-clockwise, initial area and shape derivatives
// dN_k/dx = bx[k], dN_k/dy = by[k], and its elastic constants.
struct Zone {
  std::array<std::uint32_t, 3> gp;
  double area;                   // m^2, initial
  std::array<double, 3> bx, by;  // 1/m
  double lambda, shear;          // Pa
};

// Tension positive (docs/theory.md §1.2); zz is the out-of-plane stress of plane strain.
struct ZoneStress {
  double xx = 0, yy = 0, xy = 0, zz = 0;
};

// The zones' constants again in struct-of-arrays order, and the kernel's scratch, so that
// zone_forces runs over several zones per instruction.
struct ZoneArrays {
  std::array<std::vector<std::uint32_t>, 3> gp;
  std::array<std::vector<double>, 3> bx, by;
  std::vector<double> area, lambda, shear;
  // m, per gridpoint: the displacement of the last force pass, from which every zone's stress and
  // strain follow (Zoning::stress, Zoning::strain): state, not scratch.
  std::vector<double> ux, uy;
  // Pa, per zone: the in-situ stress it started with (tension positive, the zone's initial frame),
  // added to its elastic stress; empty: none (docs/theory.md §6.7).
  std::vector<double> s0xx, s0yy, s0xy;
};

// The boundary gridpoints of the deformable blocks as corners, all blocks in one list (block
// order), so that their world corners, edges and rounded arcs are refreshed several per
// instruction: the corner index and its gridpoint, where each block's corners begin in the list
// (and the list's end; a block's corners are in its order, so a corner's neighbours in the list
// are its block's previous and next corners but at the block's ends), and the refresh's scratch.
struct CornerArrays {
  std::vector<std::uint32_t> corner, gp;
  std::vector<std::uint32_t> block_begin;
  std::vector<double> px, py;  // m, corner
  std::vector<double> tx, ty;  // -, unit direction of the edge from the corner
  std::vector<double> inv;     // 1/m, of the edge's length
  std::vector<double> cx, cy;  // m, arc centre
  std::vector<double> radius;  // m
};

struct Zoning {
  // Gridpoints (struct of arrays).
  std::vector<double> x, y, x0, y0, vx, vy;
  std::vector<double> mass;              // kg per m, inertial (density scaling may raise it)
  std::vector<double> gravity_mass;      // kg per m, true lumped mass
  std::vector<double> fx, fy;            // N per m, applied boundary loads of the current step
  std::vector<double> cfx, cfy;          // N per m, contact force sums of the current step
  std::vector<std::uint32_t> block;      // owning block
  std::vector<std::uint8_t> prescribed;  // 1: velocity set from outside, not integrated
  // Zones; their stress and strain are functions of the displacements in `arrays` (ux, uy).
  std::vector<Zone> zones;
  ZoneArrays arrays;
  std::vector<std::uint32_t> zone_block;  // owning block; a block's zones are consecutive
  // Per block corner (Blocks::corner index): its gridpoint, or -1 on a rigid block.
  std::vector<std::int32_t> corner_gp;
  CornerArrays corners;
  // Deformable blocks, the range of their gridpoints and where their zones begin.
  std::vector<std::uint32_t> blocks, gp_begin, gp_end, zone_begin;

  std::size_t gridpoints() const { return x.size(); }
  // Pa, the zone's stress in the world frame at the last force pass (R T R^T), computed when
  // asked: the force pass needs only the zone's own frame.
  ZoneStress stress(std::size_t zone) const;
  // The zone's strain in the world frame at the last force pass, R (U - I) R^T: exx, eyy and the
  // engineering shear strain gamma_xy.
  std::array<double, 3> strain(std::size_t zone) const;
  bool empty() const { return zones.empty(); }
};

struct Model;
enum class Group : std::int32_t;

// Appends a deformable block zoned from a counter-clockwise polygon: its boundary gridpoints
// become the block's corners, so contact detection and geometry treat it like any block.
void add_deformable_block(Model& model, const std::vector<Point>& polygon, double density,
                          const ElasticMaterial& material, double zone_size, Group group);
// The same with a zone size that varies over the block (m at each point; graded zoning).
void add_deformable_block(Model& model, const std::vector<Point>& polygon, double density,
                          const ElasticMaterial& material, const geometry::ZoneSize& zone_size,
                          Group group);

// World corners, rounded-corner arcs and centroids of the deformable blocks from their gridpoints.
void refresh_deformable(Model& model);

// The gridpoint displacements (arrays.ux, arrays.uy) and from them the zone forces, gathered per
// gridpoint into (out_fx, out_fy) (N per m).
void zone_forces(Zoning& z, std::vector<double>& out_fx, std::vector<double>& out_fy);

// N/m per gridpoint, the Gershgorin row bound of the zone stiffness (docs/theory.md §9.2).
std::vector<double> zone_stiffness_bound(const Zoning& z);

// J per m, elastic strain energy held in the zones.
double zone_strain_energy(const Zoning& z);

// Area-weighted mean zone stress over the deformable blocks of one group (tension positive).
ZoneStress mean_stress(const Model& model, Group group);

}  // namespace vorodec::model
