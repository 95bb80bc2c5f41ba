#pragma once
// LawGroupOf<Law>: the per-contact loop (geometry -> kinematics -> Law::evaluate -> force record)
// shared by every law. Included only by the law sources, so Law::evaluate is inlined.
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/contact_geometry.hpp"
#include "vorodec/model/deformable_contact.hpp"

namespace vorodec::laws {

template <class Law>
class LawGroupOf final : public LawGroup {
 public:
  LawGroupOf(const LawParams& params, std::uint64_t seed)
      : params_(Law::params_from(params)), seed_(seed) {}

  std::string_view name() const override { return Law::name; }
  std::size_t size() const override { return props_.size(); }
  double max_stiffness(std::size_t i) const override { return Law::max_stiffness(props_[i]); }
  double strain_energy(std::size_t i, double fn, double fs) const override {
    return energy(props_[i], state_[i], fn, fs);
  }
  bool viscous() const override { return is_viscous; }
  double relaxation_time() const override {
    double t = std::numeric_limits<double>::infinity();
    if constexpr (is_viscous)
      for (const auto& p : props_) t = std::min(t, Law::relaxation_time(p));
    return t;
  }
  std::size_t bytes_per_contact() const override {
    return sizeof(typename Law::Props) + sizeof(typename Law::State);
  }

  bool linear_springs(std::size_t i, LinearSprings& out) const override {
    if constexpr (requires { Law::linear_springs(props_[i], state_[i]); }) {
      out = Law::linear_springs(props_[i], state_[i]);
      return true;
    }
    return false;
  }
  double elastic_reach(std::size_t i, double fn, double fs, double dfn, double dfs) const override {
    if constexpr (requires { Law::elastic_reach(props_[i], state_[i], fn, fs, dfn, dfs); })
      return Law::elastic_reach(props_[i], state_[i], fn, fs, dfn, dfs);
    return 0.0;
  }

  bool degradable_bonds() const override {
    return requires(const typename Law::Props& p, const typename Law::State& st) {
      Law::bond(p, st);
    };
  }
  bool bond(std::size_t i, BondView& out) const override {
    if constexpr (requires { Law::bond(props_[i], state_[i]); }) {
      out = Law::bond(props_[i], state_[i]);
      return true;
    }
    return false;
  }
  void set_bond(std::size_t i, const BondView& b, double gap, double fn, double fs) override {
    if constexpr (requires { Law::set_bond(props_[i], state_[i], b, gap, fn, fs); })
      Law::set_bond(props_[i], state_[i], b, gap, fn, fs);
  }

  bool preload(std::size_t i, double gap, double fn, double fs) override {
    if constexpr (requires { Law::preload(props_[i], state_[i], gap, fn, fs); }) {
      Law::preload(props_[i], state_[i], gap, fn, fs);
      return true;
    }
    return false;
  }

  std::vector<double> properties(std::size_t i) const override {
    static_assert(sizeof(typename Law::Props) == Law::property_names.size() * sizeof(double));
    std::vector<double> v(Law::property_names.size());
    std::memcpy(v.data(), &props_[i], sizeof(typename Law::Props));
    return v;
  }
  std::span<const std::string_view> property_names() const override { return Law::property_names; }

  void save(checkpoint::OutArchive& ar) const override {
    ar(checkpoint::pod(props_), checkpoint::pod(state_));
  }
  void load(checkpoint::InArchive& ar) override {
    ar(checkpoint::pod(props_), checkpoint::pod(state_));
  }

  void rebuild(std::span<const std::int64_t> old_of_new,
               std::span<const NewContact> fresh) override {
    std::vector<typename Law::Props> props(old_of_new.size());
    std::vector<typename Law::State> state(old_of_new.size());
    for (std::size_t i = 0; i < old_of_new.size(); ++i) {
      if (old_of_new[i] >= 0) {
        props[i] = props_[static_cast<std::size_t>(old_of_new[i])];
        state[i] = state_[static_cast<std::size_t>(old_of_new[i])];
      } else {
        props[i] = Law::sample(params_, seed_, fresh[i]);
        if constexpr (requires { Law::initial_state(props[i], fresh[i]); })
          state[i] = Law::initial_state(props[i], fresh[i]);
        else
          state[i] = Law::initial_state(fresh[i]);
      }
    }
    props_.swap(props);
    state_.swap(state);
  }

  void step(StepContext& ctx, std::size_t begin, std::size_t end) override {
    if (end - begin >= prefetch_from)
      step_range<true>(ctx, begin, end);
    else
      step_range<false>(ctx, begin, end);
  }

  // Contacts with a deformable side (docs/theory.md §4.4): the corner side moves with its
  // gridpoint, the edge side with its two gridpoints interpolated at the contact point, and their
  // force goes to the same gridpoints with the same weights. The laws run in parallel parts, each
  // adding its forces to the blocks only it touches; what must be added in contact order to stay
  // the same bits for any thread count (the sides a_serial and b_serial mark, and dissipation) is
  // left in a list per part and added after, part by part.
  void step_deformable(StepContext& ctx, std::size_t begin, std::size_t end) override {
    const int chunks = ctx.chunks;
    deferred_.resize(static_cast<std::size_t>(chunks));
    spent_.resize(static_cast<std::size_t>(chunks));
#pragma omp parallel num_threads(chunks) if (end - begin >= deformable_parallel_from)
    for (int t = omp_get_thread_num(); t < chunks; t += omp_get_num_threads()) {
      const model::BodyView v = model::body_view(*ctx.blocks, *ctx.zoning);
      model::Contact* contacts = ctx.contacts;
      const Loop loop = loop_constants(ctx);
      auto& cracks = (*ctx.cracks_per_chunk)[static_cast<std::size_t>(t)];
      auto& later = deferred_[static_cast<std::size_t>(t)];
      later.clear();
      auto& spent = spent_[static_cast<std::size_t>(t)].records;
      spent.clear();
      const std::size_t lo = ctx.cuts[t], hi = ctx.cuts[t + 1];
      const bool timed = omp_get_num_threads() > 1;
      if (timed) ctx.clocks[t].start = omp_get_wtime();
      // The frames of a batch first, as in step_range: independent of one another, so the core
      // overlaps their square roots and divisions.
      model::ContactFrame frames[batch];
      for (std::size_t first = lo; first < hi;) {
        const std::size_t stop = std::min(hi, first + static_cast<std::size_t>(batch));
        for (std::size_t i = first; i < stop; ++i)
          frames[i - first] = model::contact_frame(v.corners, contacts[i]);
        for (std::size_t i = first; i < stop; ++i) {
          model::Contact& c = contacts[i];
          const model::ContactFrame& f = frames[i - first];
          const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
          DeformableOutcome o;
          o.pa = model::corner_point(v, a, c.corner);
          o.pb = model::edge_point(v, b, c.edge, f.point);
          o.point = f.point;
          const model::Point va = model::velocity_at(v, a, o.pa, f.point);
          const model::Point vb = model::velocity_at(v, b, o.pb, f.point);
          // Gridpoint corners: the increment from the gridpoints' velocities, force at the point.
          const double du_s = ((va.x - vb.x) * -f.n.y + (va.y - vb.y) * f.n.x) * loop.dt;
          o.force = update(loop, c, loop.props[i - begin], loop.state[i - begin], f, du_s, 1.0,
                           cracks, spent);
          o.contact = i;
          o.sides = 0;
          if (!add_side(ctx, o, a, o.pa, 1.0, false, false)) o.sides |= a_serial;
          if (!add_side(ctx, o, b, o.pb, -1.0, true, false)) o.sides |= b_serial;
          if (o.sides != 0) later.push_back(o);
        }
        first = stop;
      }
      if (timed) ctx.clocks[t].end = omp_get_wtime();
    }
    for (const auto& later : deferred_) {
      for (const DeformableOutcome& o : later) {
        const model::Contact& c = ctx.contacts[o.contact];
        if (o.sides & a_serial)
          add_side(ctx, o, static_cast<std::size_t>(c.a), o.pa, 1.0, false, true);
        if (o.sides & b_serial)
          add_side(ctx, o, static_cast<std::size_t>(c.b), o.pb, -1.0, true, true);
      }
    }
    add_spent(ctx.totals);
  }

 private:
  // A viscous law's evaluate also returns its dashpots' work of the step.
  static constexpr bool is_viscous = requires {
    Law::viscous;
  };
  static double energy(const typename Law::Props& p, [[maybe_unused]] const typename Law::State& st,
                       double fn, double fs) {
    if constexpr (is_viscous)
      return Law::strain_energy(p, st, fn, fs);
    else
      return Law::strain_energy(p, fn, fs);
  }

  // From this many contacts the corner records outgrow the L2 cache and prefetching pays (1e4
  // blocks: -14 % per step); below it, it only adds instructions (+8 % in the default model).
  static constexpr std::size_t prefetch_from = 16384, prefetch_ahead = 8;
  // Below prefetch_from, contacts whose frames are computed ahead of their laws.
  static constexpr std::ptrdiff_t batch = 32;

  // Prefetches every cache line of the `bytes` bytes from `from`. At most 128 bytes span at most
  // three lines, and then the middle byte lies in the middle one. Integer arithmetic: the range
  // may run past the end of its array.
  template <std::size_t bytes>
  static void prefetch_bytes(const void* from) {
    static_assert(bytes > 0 && bytes <= 128);
    const auto p = reinterpret_cast<std::uintptr_t>(from);
    __builtin_prefetch(reinterpret_cast<const void*>(p));
    __builtin_prefetch(reinterpret_cast<const void*>(p + bytes / 2));
    __builtin_prefetch(reinterpret_cast<const void*>(p + bytes - 1));
  }

  template <bool from_memory>
  void step_range(StepContext& ctx, std::size_t begin, std::size_t end) {
    const int chunks = ctx.chunks;
    spent_.resize(static_cast<std::size_t>(chunks));
    // One part per thread; a thread the runtime did not grant (or a group too small to be worth
    // a parallel region) leaves its part to the others.
#pragma omp parallel num_threads(chunks) if (end - begin >= rigid_parallel_from)
    for (int t = omp_get_thread_num(); t < chunks; t += omp_get_num_threads()) {
      // Private to the thread: shared ones are read through the region's data block, again after
      // every one-byte store.
      const model::CornerView bl = ctx.blocks->corners();
      const model::BlockKinematics* kin = ctx.blocks->kin.data();
      model::Contact* contacts = ctx.contacts;
      model::ContactForce* forces = ctx.forces;
      const std::uint8_t* shared_sides = ctx.shared_sides;
      model::BlockForceSum* sums = ctx.sums;
      const Loop loop = loop_constants(ctx);
      auto& cracks = (*ctx.cracks_per_chunk)[static_cast<std::size_t>(t)];
      auto& spent = spent_[static_cast<std::size_t>(t)].records;
      spent.clear();
      const std::size_t lo = ctx.cuts[t], hi = ctx.cuts[t + 1];
      const bool timed = omp_get_num_threads() > 1;
      if (timed) ctx.clocks[t].start = omp_get_wtime();
      // Walked by pointers: an index would be one more register, spilled, in a loop short of them.
      typename Law::Props* props = loop.props + (lo - begin);
      typename Law::State* state = loop.state + (lo - begin);
      const std::uint8_t* shared_side = shared_sides + lo;
      model::Contact* const last = contacts + hi;
      // Law, force and sums of contact c, whose frame is f; then on to the next contact's data.
      const auto settle = [&](const model::ContactFrame& f, model::Contact& c)
          __attribute__((always_inline)) {
        const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
        const model::BlockKinematics& ka = kin[a];
        const model::BlockKinematics& kb = kin[b];
        // The exact change of the shear coordinate, so that the spring's energy is a function of
        // the positions; from the relative velocity at the arm only where its edge (the
        // coordinate's chart) changed since the last step.
        double du_s;
        if (c.shear_edge == c.edge) {
          // On an arc the coordinate follows the normal's turn since the last step (no atan2),
          // from the tangent point when the contact comes onto the arc from the straight part
          // (whose ray is (1, 0) exactly; so is the arc's at its tangent point, where both agree).
          const bool was_straight = c.shear_ray.x == 1.0 && c.shear_ray.y == 0.0;
          const double to = f.side == 0    ? f.shear
                            : was_straight ? f.shear + f.rho * model::turn({1.0, 0.0}, f.ray)
                                           : c.shear + f.rho * model::turn(c.shear_ray, f.ray);
          du_s = to - c.shear;
          c.shear = to;
        } else {
          const double vrx =
              (ka.vx - ka.omega * (f.arm.y - ka.y)) - (kb.vx - kb.omega * (f.arm.y - kb.y));
          const double vry =
              (ka.vy + ka.omega * (f.arm.x - ka.x)) - (kb.vy + kb.omega * (f.arm.x - kb.x));
          du_s = (vry * f.n.x - vrx * f.n.y) * loop.dt;
          c.shear = model::shear_coordinate(f);
        }
        c.shear_ray = f.ray;
        c.shear_edge = c.edge;
        const model::Point force = update(loop, c, *props, *state, f, du_s, f.gain, cracks, spent);
        const double fx = force.x, fy = force.y;
        const double ma = (f.arm.x - ka.x) * fy - (f.arm.y - ka.y) * fx;
        const double mb = (f.arm.x - kb.x) * fy - (f.arm.y - kb.y) * fx;
        const std::uint8_t shared = *shared_side;
        if (shared != 0) forces[&c - contacts] = {fx, fy, ma, mb};
        if (!(shared & a_shared)) {
          sums[a].fx += fx;
          sums[a].fy += fy;
          sums[a].m += ma;
        }
        if (!(shared & b_shared)) {
          sums[b].fx -= fx;
          sums[b].fy -= fy;
          sums[b].m -= mb;
        }
        ++props;
        ++state;
        ++shared_side;
      };
      if constexpr (from_memory) {
        for (model::Contact* cp = contacts + lo; cp != last; ++cp) {
          // The edge's records sit at the neighbour block's corners, not in contact order: fetch
          // them a few contacts ahead so their latency overlaps the work on this one.
          if (last - cp > std::ptrdiff_t{prefetch_ahead}) {
            const model::Contact& ahead = cp[prefetch_ahead];
            // The edge's end corner (and the corner after it, for the walk test) is the next
            // record in memory unless the edge closes its polygon: fetched with it, not after it.
            prefetch_bytes<2 * sizeof(model::CornerWorld) + sizeof(model::Point)>(
                &bl.world[ahead.edge]);
            prefetch_bytes<sizeof(model::CornerShape) + offsetof(model::CornerShape, next) +
                           sizeof(std::uint32_t)>(&bl.shape[ahead.edge]);
            __builtin_prefetch(&bl.world[ahead.corner]);
            __builtin_prefetch(&kin[static_cast<std::size_t>(ahead.b)]);
            __builtin_prefetch(&sums[static_cast<std::size_t>(ahead.b)], 1);
          }
          settle(model::contact_frame(bl, *cp), *cp);
        }
      } else {
        // From cache, the frames of a batch first: independent of one another, so the core
        // overlaps their square roots and divisions. (From memory this was slower: see
        // bench/README.md, seventh pass.)
        model::ContactFrame frames[batch];
        for (model::Contact* first = contacts + lo; first != last;) {
          model::Contact* const stop = last - first > batch ? first + batch : last;
          for (model::Contact* cp = first; cp != stop; ++cp)
            frames[cp - first] = model::contact_frame(bl, *cp);
          for (model::Contact* cp = first; cp != stop; ++cp) settle(frames[cp - first], *cp);
          first = stop;
        }
      }
      if (timed) ctx.clocks[t].end = omp_get_wtime();
    }
    add_spent(ctx.totals);
  }

  // What one contact dissipated in a step that was not elastic, J per m.
  struct Spent {
    double slip, breakage, dashpots;
  };
  // The parts' dissipation, summed in contact order (the parts in order, each in contact order):
  // per-part sums would add in an order set by the thread count.
  void add_spent(ContactTotals& totals) const {
    double slip = 0.0, breakage = 0.0, dashpots = 0.0;
    for (const auto& part : spent_) {
      for (const Spent& s : part.records) {
        slip += s.slip;
        breakage += s.breakage;
        dashpots += s.dashpots;
      }
    }
    totals.dissipated_slip += slip;
    totals.dissipated_breakage += breakage;
    totals.dissipated_viscous += dashpots;
  }

  // What every contact of a step reads, in locals: behind a pointer the compiler would reload
  // them after each one-byte store (c.state), which may alias anything.
  struct Loop {
    typename Law::Props* props;  // indexed by the group's local contact index
    typename Law::State* state;
    double dt, time;
  };
  Loop loop_constants(const StepContext& ctx) {
    return {props_.data(), state_.data(), ctx.dt, ctx.time};
  }

  // Law::evaluate for contact c with its properties and state and shear increment du_s of a
  // with respect to b, its bookkeeping (state, crack, dissipation in `spent` unless the step was
  // elastic), and the force on a: the shear force times `gain` (ContactFrame::gain) along s.
  [[gnu::always_inline]] inline model::Point update(const Loop& loop, model::Contact& c,
                                                    const typename Law::Props& props,
                                                    typename Law::State& state,
                                                    const model::ContactFrame& f, double du_s,
                                                    double gain, std::vector<CrackEvent>& cracks,
                                                    std::vector<Spent>& spent) {
    const model::Point s{-f.n.y, f.n.x};
    const double dt = loop.dt;
    const ContactKinematics k{f.gap, f.gap - c.gap, du_s, c.length, dt};
    double viscous_work = 0.0, energy_before = 0.0;
    if constexpr (is_viscous) energy_before = Law::strain_energy(props, state, c.fn, c.fs);
    const LawResult r = [&] {
      if constexpr (is_viscous)
        return Law::evaluate(k, props, state, viscous_work);
      else
        return Law::evaluate(k, props, state);
    }();
    // Energy a contact dissipates in one step: work done on it minus its strain-energy change
    // (zero by construction in an elastic step).
    double dissipated = 0.0;
    if (!r.elastic) {
      // Read here, not before evaluate: the law's state stores might alias them for the compiler,
      // which would then load and keep them (on the stack) for every contact.
      const double fn0 = c.fn, fs0 = c.fs;
      const double work = -0.5 * ((fn0 + r.fn) * k.du_n + (fs0 + r.fs) * k.du_s);
      // A viscous law's spring energy depends on its state, so it was taken before the step.
      const double e0 = is_viscous ? energy_before : energy(props, state, fn0, fs0);
      dissipated = work - (energy(props, state, r.fn, r.fs) - e0) - viscous_work;
    }
    c.gap = f.gap;
    c.fn = r.fn;
    c.fs = r.fs;
    const bool failed =
        r.event == ContactEvent::tensile_failure || r.event == ContactEvent::shear_failure;
    // Most steps are elastic and dissipate nothing: they leave no record.
    if (!r.elastic)
      spent.push_back(failed ? Spent{0.0, dissipated, viscous_work}
                             : Spent{dissipated, 0.0, viscous_work});
    if (failed) {
      c.state = r.event == ContactEvent::tensile_failure ? model::ContactState::tensile_failed
                                                         : model::ContactState::shear_failed;
      cracks.push_back(
          {loop.time, f.point.x, f.point.y, f.n.x, f.n.y, c.length, c.a, c.b, r.event, dissipated});
    } else {
      if (c.state <= model::ContactState::slipping)
        c.state = r.event == ContactEvent::slip ? model::ContactState::slipping
                                                : model::ContactState::intact;
    }
    const double fs = gain * r.fs;
    return {r.fn * f.n.x + fs * s.x, r.fn * f.n.y + fs * s.y};
  }

  typename Law::Params params_;
  std::uint64_t seed_;
  std::vector<typename Law::Props> props_;
  std::vector<typename Law::State> state_;
  // One part's records, in contact order, on cache lines of its own: the parts' threads push to
  // their lists at the same time.
  struct alignas(64) PartSpent {
    std::vector<Spent> records;
  };
  std::vector<PartSpent> spent_;

  // A deformable contact's result: what its parallel pass leaves for the ordered one.
  struct DeformableOutcome {
    model::BodyPoint pa, pb;  // where the force goes on a and on b
    model::Point force, point;
    std::size_t contact;
    std::uint8_t sides;  // a_serial | b_serial: the sides still to add
  };
  std::vector<std::vector<DeformableOutcome>> deferred_;  // per part, in contact order

  // Adds o's force on one side (block blk at p; on a: sign 1, on b: -1) where it may be added
  // now: in the ordered pass (`in_order`) always, in the parallel one where its block is this
  // part's own. A shared rigid block takes the contact's force record instead, in either pass.
  // Returns false where the side is left for the ordered pass.
  static bool add_side(StepContext& ctx, const DeformableOutcome& o, std::size_t blk,
                       const model::BodyPoint& p, double sign, bool on_b, bool in_order) {
    const std::uint8_t shared = ctx.shared_sides[o.contact];
    if (p.g0 < 0 && (shared & (on_b ? b_shared : a_shared))) {
      const model::BlockKinematics& k = ctx.blocks->kin[blk];
      model::ContactForce& rec = ctx.forces[o.contact];
      rec.fx = o.force.x;
      rec.fy = o.force.y;
      (on_b ? rec.mb : rec.ma) = (o.point.x - k.x) * o.force.y - (o.point.y - k.y) * o.force.x;
      return true;
    }
    if (!in_order && (shared & (on_b ? b_serial : a_serial))) return false;
    if (p.g0 >= 0) {
      model::Zoning& z = *ctx.zoning;
      const auto g0 = static_cast<std::size_t>(p.g0);
      z.cfx[g0] += sign * (1.0 - p.w1) * o.force.x;
      z.cfy[g0] += sign * (1.0 - p.w1) * o.force.y;
      if (p.g1 >= 0) {
        const auto g1 = static_cast<std::size_t>(p.g1);
        z.cfx[g1] += sign * p.w1 * o.force.x;
        z.cfy[g1] += sign * p.w1 * o.force.y;
      }
      return true;
    }
    const model::BlockKinematics& k = ctx.blocks->kin[blk];
    const double m = (o.point.x - k.x) * o.force.y - (o.point.y - k.y) * o.force.x;
    ctx.sums[blk].fx += sign * o.force.x;
    ctx.sums[blk].fy += sign * o.force.y;
    ctx.sums[blk].m += sign * m;
    return true;
  }
};

}  // namespace vorodec::laws
