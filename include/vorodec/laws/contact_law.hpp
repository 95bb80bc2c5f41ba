#pragma once
// The seam between the solver and contact laws. A law sees one contact's kinematics and its own
// state and returns forces and an event; the solver calls each law group once per step for its
// contiguous range of contacts, so there is no virtual call per contact.
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vorodec/model/model.hpp"
#include "vorodec/model/weibull.hpp"

namespace vorodec::laws {

struct ContactKinematics {
  double gap;     // m, current gap (u_n; negative = overlap)
  double du_n;    // m, normal displacement increment of this step (opening positive)
  double du_s;    // m, shear displacement increment of this step
  double length;  // m, contact length
  double dt;      // s
};

enum class ContactEvent : std::uint8_t { none, slip, tensile_failure, shear_failure };

struct LawResult {
  double fn;  // N, normal force, compression positive
  double fs;  // N, shear force along s = (-n_y, n_x)
  ContactEvent event;
  // The step followed the linear springs exactly (no slip, failure, cut-off or dilation), so it
  // dissipated nothing and the energy bookkeeping can be skipped.
  bool elastic;
};

// A crack: a contact that failed, recorded once at the intact -> failed transition.
struct CrackEvent {
  double time;        // s
  double x, y;        // m, contact point
  double nx, ny;      // contact normal
  double length;      // m
  std::int32_t a, b;  // blocks
  ContactEvent type;  // tensile_failure or shear_failure
  double energy;      // J per m, strain energy the failure released (the AE catalogue's source)
};

// Per-step outputs that are reduced over contacts.
struct ContactTotals {
  double dissipated_slip = 0.0;      // J per m, friction (and dilation) work of this step
  double dissipated_breakage = 0.0;  // J per m, spring energy released by failures this step
  double dissipated_viscous = 0.0;   // J per m, dashpot work (viscous laws) this step
};

// When a thread part of a contact pass started and ended (omp_get_wtime, s), on a cache line of
// its own; written only by a part that ran in a parallel region. The solver moves the cuts
// between parts towards equal finishing times (solver/part_balance.hpp).
struct alignas(64) PartClock {
  double start = 0.0, end = 0.0;
};

// Contacts [begin, end) cut into `chunks` contiguous equal parts: part t, [first, second).
inline std::pair<std::size_t, std::size_t> chunk_range(std::size_t begin, std::size_t end, int t,
                                                       int chunks) {
  const std::size_t n = end - begin, t0 = static_cast<std::size_t>(t);
  const auto k = static_cast<std::size_t>(chunks);
  return {begin + n * t0 / k, begin + n * (t0 + 1) / k};
}

// From this many rigid (deformable) contacts a law group's pass runs in parallel parts; below,
// one thread runs them all.
inline constexpr std::size_t rigid_parallel_from = 2048, deformable_parallel_from = 1024;

// Where a contact's force goes. Each law group's range is cut into `chunks` contiguous parts
// (StepContext::cuts), one per thread. A block that only contacts of one part touch is that part's
// own: its sums are added directly, in contact order. A block touched by several parts is shared:
// the contact writes its force record and the solver gathers the block's sum afterwards, also in
// contact order. Either way the sums are the same bits for any thread count.
inline constexpr std::uint8_t a_shared = 1, b_shared = 2;
// Contacts with a deformable side are cut into parts the same way; a side whose block several of
// those parts touch is added to its gridpoints or sum after the parts, in contact order.
inline constexpr std::uint8_t a_serial = 4, b_serial = 8;

struct StepContext {
  model::Blocks* blocks;
  model::Contact* contacts;          // whole contact array
  model::ContactForce* forces;       // whole force array (written where a block is shared)
  const std::uint8_t* shared_sides;  // per contact: a_shared | b_shared | a_serial | b_serial
  model::BlockForceSum* sums;        // per block contact sums, zero before the step
  int chunks;                        // parts per law group; cracks_per_chunk has this many lists
  // The range's parts: part t is [cuts[t], cuts[t + 1]), cuts[0] = begin, cuts[chunks] = end.
  // Any cut gives the same bits; the solver places them by measured time.
  const std::size_t* cuts;
  PartClock* clocks;  // one per part
  std::vector<std::vector<CrackEvent>>* cracks_per_chunk;
  double dt;    // s
  double time;  // s
  ContactTotals totals;
  model::Zoning* zoning;  // gridpoints of the deformable blocks (contact sums zero before the step)
};

// A contact's springs as the implicit elastic start (solver/implicit_start) sees them.
struct LinearSprings {
  double kn, ks;  // N/m
  // Carries no tension (an open or failed joint): it acts only while compressed.
  bool unilateral;
};

// A new contact: bonded ones belong to the initial tessellation, others are frictional only.
struct NewContact {
  std::uint64_t id;
  double length;
  bool bonded;
  // m, gap at which the normal spring is unloaded: 0, except for a contact that appears during
  // the run already overlapping, whose force starts at zero (as UDEC's incremental contacts do)
  // so that detection never creates strain energy (docs/theory.md §12).
  double spring_origin;
};

// A bonded contact's springs and strength as the stress-corrosion layers (stress_corrosion.hpp)
// read and degrade them.
struct BondView {
  double kn, ks;                         // N/m
  double tension_force, cohesion_force;  // N
  double tan_phi;
  bool broken;
};

class LawGroup {
 public:
  virtual ~LawGroup() = default;
  virtual std::string_view name() const = 0;
  // Advance contacts [begin, end) of the context's contact array; they all belong to this group.
  virtual void step(StepContext& ctx, std::size_t begin, std::size_t end) = 0;
  // The same for contacts [begin, end) that touch a deformable block.
  virtual void step_deformable(StepContext& ctx, std::size_t begin, std::size_t end) = 0;
  // The group's contacts were rebuilt: new local index i came from old local index old_of_new[i],
  // or is new (-1) and described by fresh[i].
  virtual void rebuild(std::span<const std::int64_t> old_of_new,
                       std::span<const NewContact> fresh) = 0;
  virtual std::size_t size() const = 0;
  // N/m, the larger of the normal and shear spring stiffness of local contact i (time step).
  virtual double max_stiffness(std::size_t i) const = 0;
  // s, the shortest relaxation time (dashpot / spring) of the group's contacts: the creep time
  // step's scale; infinity for a law without dashpots.
  virtual double relaxation_time() const = 0;
  // The law has dashpots: its evaluate reports their work (ContactTotals::dissipated_viscous).
  virtual bool viscous() const = 0;
  // J per m, elastic energy held in local contact i given its forces.
  virtual double strain_energy(std::size_t i, double fn, double fs) const = 0;
  // Bytes of law state and properties per contact (memory accounting).
  virtual std::size_t bytes_per_contact() const = 0;
  // The springs of local contact i in its current state; false if the law has no linear
  // elastic regime (the implicit elastic start then refuses to run).
  virtual bool linear_springs(std::size_t i, LinearSprings& out) const = 0;
  // Largest factor s >= 0 such that forces (fn + s dfn, fs + s dfs) stay elastic in local
  // contact i (no failure, slip or cut-off); infinity if they always do.
  virtual double elastic_reach(std::size_t i, double fn, double fs, double dfn,
                               double dfs) const = 0;
  // Sampled properties of local contact i, named by property_names() (for reports and files).
  virtual std::vector<double> properties(std::size_t i) const = 0;
  virtual std::span<const std::string_view> property_names() const = 0;
  // Stress corrosion: whether the law's contacts have bonds the layers can degrade, and local
  // contact i's bond (false: it has none).
  virtual bool degradable_bonds() const = 0;
  virtual bool bond(std::size_t i, BondView& out) const = 0;
  // Gives local contact i the springs and strength of `b` and, at its current gap, the forces
  // (fn, fs) N; or breaks it (tension and cohesion lost) with b.broken.
  virtual void set_bond(std::size_t i, const BondView& b, double gap, double fn, double fs) = 0;
  // In-situ stress: local contact i carries (fn, fs) N at its current gap; false if the law cannot
  // start loaded (its state has a history a force alone does not give).
  virtual bool preload(std::size_t i, double gap, double fn, double fs) = 0;
  // Checkpoints: the per-contact properties and state (the parameters come from the model file).
  virtual void save(checkpoint::OutArchive& ar) const = 0;
  virtual void load(checkpoint::InArchive& ar) = 0;
};

// What a law accepts from the model file: each key with its unit and valid range.
struct ParamSpec {
  std::string_view key;
  std::string_view unit;
  std::string_view doc;
  double min;  // the value (or a distribution's mean / scale) must be > min, or >= min if
               // min_inclusive
  bool min_inclusive;
  double max;            // and <= max
  double default_value;  // NaN: required unless optional
  bool distributable;    // may be Weibull distributed per contact
  bool optional;         // may be absent with no default (the law derives it)
};

using LawParams = std::map<std::string, model::Distribution, std::less<>>;

// Pa/m, a law's springs per unit contact length as a contact first takes load (their means): what
// platens, quiet boundaries and wave speeds are sized by. 0 where the law has no such spring.
struct NominalStiffness {
  double normal = 0, shear = 0;
};

// The mean of a law's parameter `key`, 0 if it has none.
inline double mean_of(const LawParams& p, std::string_view key) {
  const auto it = p.find(key);
  return it == p.end() ? 0.0 : it->second.mean();
}

struct LawInfo {
  std::string_view name;
  std::string_view doc;
  std::span<const ParamSpec> params;
  std::unique_ptr<LawGroup> (*make)(const LawParams& params, std::uint64_t seed);
  NominalStiffness (*nominal_stiffness)(const LawParams& params);
};

inline constexpr double required = std::numeric_limits<double>::quiet_NaN();

// All laws, one row each (src/laws/registry.cpp).
std::span<const LawInfo> law_registry();
const LawInfo* find_law(std::string_view name);

}  // namespace vorodec::laws
