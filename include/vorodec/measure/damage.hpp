#pragma once
// Damage measures of the rock-mechanics literature, read from the model state and the solver's
// crack events (not from images): contact failure rate D_Mi, damage density D_Ma, crack intensity
// P21 and its rose of 10-degree bins ("Mesomechanical characteristics of rock failure under
// variable amplitude cyclic loading by DEM", Rock Mech. Rock Eng., Eqs. 2-4), the failed fraction
// of each block's initial contacts, and P21 and D_Ma on a regular grid. Pure functions; no I/O.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::measure {

using geometry::Point;

inline constexpr std::size_t kRoseBins = 18;  // 10-degree bins of crack line orientation, 0-180
using Rose = std::array<double, kRoseBins>;

// Orientation of a crack's line (the joint, perpendicular to the contact normal), in degrees from
// the x axis, in [0, 180).
double crack_orientation_deg(const laws::CrackEvent& e);

// Index of the 10-degree bin holding an orientation in [0, 180).
std::size_t rose_bin(double orientation_deg);

// The initial state the measures compare against, taken once after the initial contact detection
// (failed contacts that separate are deleted later, so their identity must be remembered).
inline constexpr std::uint32_t kNoBond = 0xffffffffu;

struct DamageBaseline {
  struct Bond {            // one initial bonded contact
    std::uint64_t id;      // Contact::id, stable while the contact exists
    std::int32_t a, b;     // blocks
    std::uint32_t corner;  // corner of a
    std::uint32_t edge;    // edge of b (its start corner) at the start
    double length;         // m
  };
  std::vector<Bond> bonds;                     // in id order
  std::vector<std::uint32_t> bond_of_id;       // by contact id, up to the largest bond id: index
                                               // into bonds, or kNoBond
  std::vector<std::uint32_t> bonds_per_block;  // initial bonded contacts of each block
  double specimen_area = 0.0;                  // m^2 (per m thickness), S_is
  Point lo, hi;                                // initial bounding box of the specimen blocks, m
  double mean_block_size = 0.0;                // m, sqrt(specimen area / specimen blocks)
};

DamageBaseline damage_baseline(const model::Model& m);

// One failed initial bond: where it is now and how far it has opened.
struct CrackOpening {
  Point point;      // m, current contact point
  double aperture;  // m, normal opening max(gap, 0)
  double length;    // m
};

// Every initial bond that has failed. A failed contact still in the contact list gives its own gap
// and length. One that redetection deleted (it opened beyond the contact tolerance) gets the gap
// its corner would have now against the same edge of the other block, by the solver's own contact
// geometry (model::contact_frame), and its initial length. Needs Blocks::refresh_world() current.
std::vector<CrackOpening> crack_openings(const model::Model& m, const DamageBaseline& base);

struct DamageState {
  std::size_t cracks = 0, cracks_tensile = 0, cracks_shear = 0;
  double failure_rate = 0.0;    // D_Mi = failed contacts / initial bonded contacts (Eq. 2)
  double crack_area = 0.0;      // m^2 (per m thickness), S_C = sum of aperture x length
  double damage_density = 0.0;  // D_Ma = S_C / (S_C + S_is) (Eq. 3)
  double p21 = 0.0, p21_tensile = 0.0, p21_shear = 0.0;  // 1/m, crack length / S_is (Eq. 4)
  Rose rose{}, rose_tensile{}, rose_shear{};             // 1/m, P21 per orientation bin
};

DamageState measure_damage(const model::Model& m, std::span<const laws::CrackEvent> cracks,
                           const DamageBaseline& base);

// Per block: the fraction of its initial bonded contacts that failed (0 for blocks without any).
std::vector<double> block_failed_fraction(std::span<const laws::CrackEvent> cracks,
                                          const DamageBaseline& base);

// Square cells of side `cell` from the specimen's initial bounding box's lower-left corner,
// covering the box; cell (i, j) is entry i + nx * j. Cracks are binned by their midpoint (the
// event's contact point for P21, the current contact point for the opening), clamped into the grid.
struct DamageGrid {
  Point origin;  // m
  double cell = 0.0;
  std::size_t nx = 0, ny = 0;
  std::vector<double> specimen_area;   // m^2, initial specimen area inside the cell
  std::vector<double> crack_length;    // m
  std::vector<double> crack_area;      // m^2, sum of aperture x length
  std::vector<double> p21;             // 1/m, crack length / specimen area of the cell
  std::vector<double> damage_density;  // crack area / (crack area + specimen area of the cell)
};

DamageGrid damage_grid(const model::Model& m, std::span<const laws::CrackEvent> cracks,
                       const DamageBaseline& base, double cell);

}  // namespace vorodec::measure
