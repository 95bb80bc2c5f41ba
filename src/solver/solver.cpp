#include "vorodec/solver/solver.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::solver {

using model::Point;

namespace {
constexpr std::uint32_t b_side = 0x80000000u;
double sign(double v) {
  return (v > 0.0) - (v < 0.0);
}
}  // namespace

Solver::Solver(model::Model& model, std::vector<std::unique_ptr<laws::LawGroup>> laws,
               LawTable table, SolverSettings settings)
    : model_(model),
      laws_(std::move(laws)),
      detector_(settings.contact_tolerance, table),
      settings_(settings) {}

void Solver::initialise() {
  detect(true);
  initial_bonded_ = static_cast<std::size_t>(
      std::count_if(model_.contacts.begin(), model_.contacts.end(), [&](const model::Contact& c) {
        // Bonds to platens (direct tension) are load transfer, not rock: not counted.
        const auto& g = model_.blocks.group;
        return c.bonded != 0 && g[static_cast<std::size_t>(c.a)] == model::Group::specimen &&
               g[static_cast<std::size_t>(c.b)] == model::Group::specimen;
      }));
}

void Solver::remove_blocks(std::span<const std::uint32_t> blocks) {
  auto& bl = model_.blocks;
  auto& z = model_.zoning;
  for (const std::uint32_t b : blocks) {
    bl.group[b] = model::Group::excavated;
    bl.prescribed[b] = 1;
    bl.vx[b] = bl.vy[b] = bl.omega[b] = 0.0;
    if (!bl.deformable[b]) continue;
    for (std::size_t k = 0; k < z.blocks.size(); ++k)  // a zoned block's gridpoints held too
      if (z.blocks[k] == b)
        for (std::uint32_t g = z.gp_begin[k]; g < z.gp_end[k]; ++g) {
          z.prescribed[g] = 1;
          z.vx[g] = z.vy[g] = 0.0;
        }
  }
  detect(false);
}

void Solver::detect(bool bond_new) {
  detector_.detect(model_, laws_, bond_new);
  ++detections_;
  const auto& bl = model_.blocks;
  // A new contact's shear spring starts unstretched where the blocks now are (on the edge the
  // step's walk will take it to; the detected edge stays for the step to walk from).
  for (model::Contact& c : model_.contacts)
    if (c.shear_edge == model::Contact::no_shear_edge) {
      model::Contact walked = c;
      const model::ContactFrame f = model::contact_frame(bl, walked);
      c.shear = model::shear_coordinate(f);
      c.shear_ray = f.ray;
      c.shear_edge = walked.edge;
    }
  const std::size_t nb = bl.size(), nc = model_.contacts.size();
  law_begin_.assign(laws_.size() + 1, 0);
  std::vector<std::size_t> deformable(laws_.size(), 0);
  for (const auto& c : model_.contacts) {
    ++law_begin_[c.law + 1u];
    if (bl.deformable[static_cast<std::size_t>(c.a)] ||
        bl.deformable[static_cast<std::size_t>(c.b)])
      ++deformable[c.law];
  }
  for (std::size_t l = 0; l < laws_.size(); ++l) law_begin_[l + 1] += law_begin_[l];
  // The detector puts each law's deformable contacts after its rigid ones.
  deformable_begin_.resize(laws_.size());
  for (std::size_t l = 0; l < laws_.size(); ++l)
    deformable_begin_[l] = law_begin_[l + 1] - deformable[l];
  forces_.resize(nc);
  sums_.resize(nb);
  gather_begin_.assign(nb + 1, 0);
  for (const auto& c : model_.contacts) {
    ++gather_begin_[static_cast<std::size_t>(c.a) + 1];
    ++gather_begin_[static_cast<std::size_t>(c.b) + 1];
  }
  for (std::size_t b = 0; b < nb; ++b) gather_begin_[b + 1] += gather_begin_[b];
  gather_.resize(2 * nc);
  std::vector<std::uint32_t> fill(gather_begin_.begin(), gather_begin_.end() - 1);
  for (std::uint32_t i = 0; i < nc; ++i) {
    gather_[fill[static_cast<std::size_t>(model_.contacts[i].a)]++] = i;
    gather_[fill[static_cast<std::size_t>(model_.contacts[i].b)]++] = i | b_side;
  }
  partition();
  x_detect_ = bl.x;
  y_detect_ = bl.y;
  t_detect_ = bl.theta;
  last_detection_ = steps_;
  compute_time_step();
}

void Solver::partition() {
  if (chunks_ != omp_get_max_threads() || balance_.ranges() != 2 * laws_.size()) {
    chunks_ = omp_get_max_threads();
    balance_.reset(2 * laws_.size(), chunks_);
  } else {
    balance_.rebalance();
  }
  cracks_per_chunk_.resize(static_cast<std::size_t>(chunks_));
  const std::size_t nb = model_.blocks.size(), nc = model_.contacts.size();
  constexpr int none = -1, several = -2;
  std::vector<int> part(nb, none);
  // Cuts range r, [begin, end), into parts and marks each block with the one part whose contacts
  // touch it, or `several`.
  const auto mark = [&](std::size_t r, std::size_t begin, std::size_t end) {
    const std::size_t* cuts = balance_.cut(r, begin, end);
    for (int t = 0; t < chunks_; ++t) {
      for (std::size_t i = cuts[t]; i < cuts[t + 1]; ++i) {
        for (const auto blk : {model_.contacts[i].a, model_.contacts[i].b}) {
          int& p = part[static_cast<std::size_t>(blk)];
          p = p == none || p == t ? t : several;
        }
      }
    }
  };
  for (std::size_t l = 0; l < laws_.size(); ++l) mark(2 * l, law_begin_[l], deformable_begin_[l]);
  // The platens' contacts keep their forces whatever the thread count: contact_force_from reads
  // them.
  for (std::size_t b = 0; b < nb; ++b)
    if (model_.blocks.group[b] == model::Group::top_platen ||
        model_.blocks.group[b] == model::Group::bottom_platen)
      part[b] = several;
  shared_sides_.resize(nc);
  for (std::size_t i = 0; i < nc; ++i) {
    const model::Contact& c = model_.contacts[i];
    shared_sides_[i] = static_cast<std::uint8_t>(
        (part[static_cast<std::size_t>(c.a)] == several ? laws::a_shared : 0) |
        (part[static_cast<std::size_t>(c.b)] == several ? laws::b_shared : 0));
  }
  // The per-block loops (world refresh, integration) cut where the largest rigid pass's parts
  // meet (its contacts are in order of block a), so that a thread moves the blocks its contacts
  // read: on this project's 2-core machines a cache line costs about 0.2 us to cross cores.
  std::size_t widest = 0;
  for (std::size_t l = 1; l < laws_.size(); ++l)
    if (deformable_begin_[l] - law_begin_[l] > deformable_begin_[widest] - law_begin_[widest])
      widest = l;
  block_cuts_.assign(static_cast<std::size_t>(chunks_) + 1, nb);
  block_cuts_[0] = 0;
  if (!laws_.empty() &&
      deformable_begin_[widest] - law_begin_[widest] >= laws::rigid_parallel_from) {
    const std::size_t* cuts = balance_.cuts(2 * widest);
    for (std::size_t t = 1; t < block_cuts_.size() - 1; ++t)
      block_cuts_[t] = std::max(
          block_cuts_[t - 1],
          cuts[t] < cuts[chunks_] ? static_cast<std::size_t>(model_.contacts[cuts[t]].a) : nb);
  } else {
    for (std::size_t t = 1; t < block_cuts_.size() - 1; ++t)
      block_cuts_[t] = nb * t / static_cast<std::size_t>(chunks_);
  }
  shared_blocks_.clear();
  for (std::size_t b = 0; b < nb; ++b)
    if (part[b] == several) shared_blocks_.push_back(static_cast<std::uint32_t>(b));
  // The same for the contacts with a deformable side (laws::a_serial, laws::b_serial), law by
  // law: the laws' passes run one after another.
  for (std::size_t l = 0; l < laws_.size(); ++l) {
    std::fill(part.begin(), part.end(), none);
    mark(2 * l + 1, deformable_begin_[l], law_begin_[l + 1]);
    for (std::size_t i = deformable_begin_[l]; i < law_begin_[l + 1]; ++i) {
      const model::Contact& c = model_.contacts[i];
      shared_sides_[i] |= static_cast<std::uint8_t>(
          (part[static_cast<std::size_t>(c.a)] == several ? laws::a_serial : 0) |
          (part[static_cast<std::size_t>(c.b)] == several ? laws::b_serial : 0));
    }
  }
}

void Solver::compute_time_step() {
  auto& bl = model_.blocks;
  const std::size_t nb = bl.size();
  std::vector<double> kt(nb, 0.0), kr(nb, 0.0);
  for (std::size_t l = 0; l < laws_.size(); ++l) {
    for (std::size_t i = law_begin_[l]; i < law_begin_[l + 1]; ++i) {
      model::Contact c = model_.contacts[i];
      const Point p = model::contact_frame(bl, c).arm;  // where the force acts
      const double k = laws_[l]->max_stiffness(i - law_begin_[l]);
      for (const auto blk : {static_cast<std::size_t>(c.a), static_cast<std::size_t>(c.b)}) {
        const double rx = p.x - bl.x[blk], ry = p.y - bl.y[blk];
        kt[blk] += k;
        kr[blk] += k * (rx * rx + ry * ry);
      }
    }
  }
  const double s = settings_.safety_factor;
  const double target = settings_.time_step;
  double dt = std::numeric_limits<double>::max();
  if (!model_.zoning.empty()) dt = gridpoint_time_step();
  for (std::size_t b = 0; b < nb; ++b) {
    if (bl.prescribed[b] || bl.deformable[b] || kt[b] == 0.0) continue;
    if (target > 0.0) {  // density scaling: the smallest inertia that makes `target` stable
      bl.mass[b] = std::max(bl.gravity_mass[b], kt[b] * target * target / (s * s));
      bl.inertia[b] = std::max(bl.true_inertia[b], kr[b] * target * target / (s * s));
    }
    dt = std::min({dt, std::sqrt(bl.mass[b] / kt[b]), std::sqrt(bl.inertia[b] / kr[b])});
  }
  // No contacts: free flight, no stability limit; 1e-6 s unless a fixed step is given.
  const bool free = dt == std::numeric_limits<double>::max();
  critical_dt_ = free ? std::numeric_limits<double>::infinity() : s * dt;
  dt_ = target > 0.0 ? target : free ? 1e-6 : critical_dt_;
  const double fixed = settings_.fixed_time_step;
  if (fixed > 0.0) {  // re-checked at every detection: new contacts can lower the critical step
    if (fixed > critical_dt_ && !fixed_step_warned_) {
      fmt::print(stderr,
                 "warning: solver.fixed_time_step = {:.4g} s is above the critical time step "
                 "{:.4g} s (safety_factor x min sqrt(m/k)) at step {}; using the critical step\n",
                 fixed, critical_dt_, steps_);
      fixed_step_warned_ = true;
    }
    dt_ = std::min(fixed, critical_dt_);
  }
}

void Solver::rescale_time_step(double dt) {
  const double before = dt_;
  settings_.time_step = dt;
  auto& bl = model_.blocks;
  if (dt == 0) {  // back to the true masses (density scaling only raises them)
    bl.mass = bl.gravity_mass;
    bl.inertia = bl.true_inertia;
  }
  compute_time_step();
  const double f = before / dt_;
  for (std::size_t b = 0; b < bl.size(); ++b) {
    if (bl.prescribed[b]) continue;
    bl.vx[b] *= f;
    bl.vy[b] *= f;
    bl.omega[b] *= f;
  }
}

double Solver::relaxation_time() const {
  double t = std::numeric_limits<double>::infinity();
  for (const auto& law : laws_) t = std::min(t, law->relaxation_time());
  return t;
}

bool Solver::viscous() const {
  return std::any_of(laws_.begin(), laws_.end(), [](const auto& l) { return l->viscous(); });
}

void Solver::step() {
  auto& bl = model_.blocks;
  const auto nb = static_cast<std::int64_t>(bl.size());
  model::refresh_world(model_, block_cuts_);
  if (steps_ % 10 == 0) {
    // Redetect once a block has moved half the tolerance since the last detection.
    double moved = 0.0;
    for (std::int64_t b = 0; b < nb; ++b) {
      const auto i = static_cast<std::size_t>(b);
      const double r = std::sqrt(bl.corner[bl.corner_begin[i]].x * bl.corner[bl.corner_begin[i]].x +
                                 bl.corner[bl.corner_begin[i]].y * bl.corner[bl.corner_begin[i]].y);
      moved = std::max(moved, std::abs(bl.x[i] - x_detect_[i]) + std::abs(bl.y[i] - y_detect_[i]) +
                                  2.0 * r * std::abs(bl.theta[i] - t_detect_[i]));
    }
    if (moved > 0.5 * detector_.tolerance() ||
        steps_ - last_detection_ >= settings_.max_detection_interval)
      detect(false);
  }
  contact_forces();
  if (face_control_) face_control_();
  integrate();
  if (!model_.zoning.empty()) integrate_gridpoints();
  time_ += dt_;
  ++steps_;
}

void Solver::contact_forces() {
  auto& bl = model_.blocks;
  if (chunks_ != omp_get_max_threads()) partition();  // the thread count changed
  std::fill(sums_.begin(), sums_.end(), model::BlockForceSum{});
  laws::StepContext ctx{&bl,
                        model_.contacts.data(),
                        forces_.data(),
                        shared_sides_.data(),
                        sums_.data(),
                        chunks_,
                        nullptr,
                        nullptr,
                        &cracks_per_chunk_,
                        dt_,
                        std::isnan(crack_clock_) ? time_ : crack_clock_,
                        {},
                        &model_.zoning};
  auto& z = model_.zoning;
  std::fill(z.cfx.begin(), z.cfx.end(), 0.0);
  std::fill(z.cfy.begin(), z.cfy.end(), 0.0);
  const auto take_cracks = [&] {
    for (auto& list : cracks_per_chunk_) {  // chunk order = contact order: deterministic
      cracks_.insert(cracks_.end(), list.begin(), list.end());
      list.clear();
    }
  };
  // Law l's rigid (pass 0) or deformable (pass 1) contacts, timed per part when parallel.
  const auto run = [&](std::size_t l, std::size_t pass) {
    const std::size_t r = 2 * l + pass;
    ctx.cuts = balance_.cuts(r);
    ctx.clocks = balance_.clocks(r);
    const bool timed = chunks_ > 1;
    if (timed) balance_.start(r);
    const double begin = timed ? omp_get_wtime() : 0.0;
    if (pass == 0)
      laws_[l]->step(ctx, law_begin_[l], deformable_begin_[l]);
    else
      laws_[l]->step_deformable(ctx, deformable_begin_[l], law_begin_[l + 1]);
    if (timed) balance_.record(r, begin);
    take_cracks();
  };
  for (std::size_t l = 0; l < laws_.size(); ++l) {
    run(l, 0);
    if (deformable_begin_[l] != law_begin_[l + 1]) run(l, 1);
  }
  energy_.slip += ctx.totals.dissipated_slip;
  energy_.breakage += ctx.totals.dissipated_breakage;
  energy_.viscous += ctx.totals.dissipated_viscous;
  gather_shared_forces();
}

void Solver::displace(const std::vector<double>& dx, const std::vector<double>& dy,
                      const std::vector<double>& dtheta, double duration) {
  auto& bl = model_.blocks;
  const std::size_t nb = bl.size();
  double work = 0.0;
  for (std::size_t b = 0; b < nb; ++b) {
    if (bl.prescribed[b])  // minus the force the specimen exerts on it, before the jump
      work -= 0.5 * (sums_[b].fx * dx[b] + sums_[b].fy * dy[b] + sums_[b].m * dtheta[b]);
    else  // applied loads (confinement) are constant along the jump
      work += bl.fx[b] * dx[b] + bl.fy[b] * dy[b] + bl.moment[b] * dtheta[b];
    bl.x[b] += dx[b];
    bl.y[b] += dy[b];
    bl.theta[b] += dtheta[b];
    // The laws take this step's shear increment as velocity x dt.
    bl.vx[b] = dx[b] / dt_;
    bl.vy[b] = dy[b] / dt_;
    bl.omega[b] = dtheta[b] / dt_;
  }
  detect(false);  // refreshes the world arrays from the new positions
  contact_forces();
  for (std::size_t b = 0; b < nb; ++b) {
    if (bl.prescribed[b])  // and after it
      work -= 0.5 * (sums_[b].fx * dx[b] + sums_[b].fy * dy[b] + sums_[b].m * dtheta[b]);
    bl.vx[b] = bl.vy[b] = bl.omega[b] = 0.0;
  }
  energy_.boundary_work += work;
  time_ += duration;
}

void Solver::gather_shared_forces() {
  // Few blocks (where the thread parts meet, and the platens): not worth a parallel region.
  for (const std::uint32_t b : shared_blocks_) {
    double fx = 0, fy = 0, m = 0;
    for (std::uint32_t k = gather_begin_[b]; k < gather_begin_[b + 1]; ++k) {
      const std::uint32_t e = gather_[k];
      const model::ContactForce& f = forces_[e & ~b_side];
      const bool on_b = (e & b_side) != 0;  // selects, not branches: the side is unpredictable
      const double s = on_b ? -1.0 : 1.0;
      fx += s * f.fx;
      fy += s * f.fy;
      m += s * (on_b ? f.mb : f.ma);
    }
    sums_[b] = {fx, fy, m};
  }
}

namespace {
// What the block integration reads and writes, as plain pointers, passed by value: through the
// vectors (or a reference) every store could move the others, and the loop would not vectorise.
struct BlockArrays {
  double *x, *y, *theta, *vx, *vy, *omega;
  const double *fx_applied, *fy_applied, *m_applied, *mass, *inertia, *gravity_mass;
  const std::uint8_t *prescribed, *deformable;
  const model::BlockForceSum* sums;
  double *work_boundary, *work_body, *work_damping;  // J per m: each block's work this step
};

// Central difference with local damping (docs/theory.md §3.3, 8.1). Branch-free over prescribed
// blocks so that a rigid-only model's loop vectorises; `zoned` skips deformable blocks (they move
// with their gridpoints, integrate_gridpoints).
// Each block's work is stored and summed afterwards in block order: a reduction here would add
// in an order that depends on the thread count and the vector width (docs/theory.md section 18).
template <bool zoned>
void integrate_blocks(const BlockArrays a, std::int64_t nb, double alpha, double dt, Point g,
                      std::span<const std::size_t> parts) {
#pragma omp parallel
  {
    const auto [lo, hi] = model::block_part(parts, nb);
#pragma omp simd
    for (std::int64_t bi = lo; bi < hi; ++bi) {
      const auto b = static_cast<std::size_t>(bi);
      if constexpr (zoned) {
        if (a.deformable[b]) {
          a.work_boundary[b] = a.work_body[b] = a.work_damping[b] = 0.0;
          continue;
        }
      }
      const double u = a.vx[b], v = a.vy[b], w = a.omega[b];
      const model::BlockForceSum f = a.sums[b];
      const double fx = f.fx + a.fx_applied[b] + a.gravity_mass[b] * g.x;
      const double fy = f.fy + a.fy_applied[b] + a.gravity_mass[b] * g.y;
      const double mz = f.m + a.m_applied[b];
      const double dfx = -alpha * std::abs(fx) * sign(u);
      const double dfy = -alpha * std::abs(fy) * sign(v);
      const double dmz = -alpha * std::abs(mz) * sign(w);
      // 1 for a free block, 0 for a prescribed one: products, not selects, so that the loop
      // vectorises (a select of a division may not be if-converted); x 1 and + 0 are exact.
      const bool held = a.prescribed[b] != 0;
      const double free = held ? 0.0 : 1.0;
      // A held block's product must be 0, not 0 x inf: its mass never enters, so it may be
      // anything.
      const double m = held ? 1.0 : a.mass[b], inertia = held ? 1.0 : a.inertia[b];
      const double u1 = u + free * ((fx + dfx) / m * dt);
      const double v1 = v + free * ((fy + dfy) / m * dt);
      const double w1 = w + free * ((mz + dmz) / inertia * dt);
      // Work of a platen on the specimen: minus the contact force the specimen exerts on it.
      a.work_boundary[b] =
          free * ((a.fx_applied[b] * u1 + a.fy_applied[b] * v1 + a.m_applied[b] * w1) * dt) -
          (1.0 - free) * ((f.fx * u + f.fy * v + f.m * w) * dt);
      // The damping force's work at the step's mean velocity: the kinetic energy at half steps
      // changes by exactly (f + df) . (u + u1) / 2 dt, so the balance closes (with u1 alone it
      // missed up to 1 % of the boundary work after a deformable specimen's peak: measured).
      a.work_damping[b] = free * (-(dfx * (u + u1) + dfy * (v + v1) + dmz * (w + w1)) * 0.5 * dt);
      a.work_body[b] = free * (a.gravity_mass[b] * (g.x * u1 + g.y * v1) * dt);
      a.vx[b] = u1;
      a.vy[b] = v1;
      a.omega[b] = w1;
      a.x[b] += u1 * dt;
      a.y[b] += v1 * dt;
      a.theta[b] += w1 * dt;
    }
  }
}
}  // namespace

void Solver::integrate() {
  auto& bl = model_.blocks;
  const std::size_t n = bl.size();
  block_work_.resize(3 * n);
  double* work = block_work_.data();
  const BlockArrays arrays{bl.x.data(),
                           bl.y.data(),
                           bl.theta.data(),
                           bl.vx.data(),
                           bl.vy.data(),
                           bl.omega.data(),
                           bl.fx.data(),
                           bl.fy.data(),
                           bl.moment.data(),
                           bl.mass.data(),
                           bl.inertia.data(),
                           bl.gravity_mass.data(),
                           bl.prescribed.data(),
                           bl.deformable.data(),
                           sums_.data(),
                           work,
                           work + n,
                           work + 2 * n};
  const auto nb = static_cast<std::int64_t>(n);
  if (model_.zoning.empty())
    integrate_blocks<false>(arrays, nb, settings_.local_damping, dt_, settings_.gravity,
                            block_cuts_);
  else
    integrate_blocks<true>(arrays, nb, settings_.local_damping, dt_, settings_.gravity,
                           block_cuts_);
  double w_boundary = 0, w_body = 0, w_damp = 0;
  for (std::size_t b = 0; b < n; ++b) {
    w_boundary += work[b];
    w_body += work[n + b];
    w_damp += work[2 * n + b];
  }
  energy_.boundary_work += w_boundary;
  energy_.body_work += w_body;
  energy_.damping += w_damp;
}

model::Point Solver::contact_force_from(std::size_t b, model::Group g) const {
  model::Point f{0.0, 0.0};
  for (std::uint32_t k = gather_begin_[b]; k < gather_begin_[b + 1]; ++k) {
    const std::uint32_t e = gather_[k];
    const model::Contact& c = model_.contacts[e & ~b_side];
    const bool on_b = (e & b_side) != 0;
    if (model_.blocks.group[static_cast<std::size_t>(on_b ? c.a : c.b)] != g) continue;
    const model::ContactForce& cf = forces_[e & ~b_side];
    f.x += on_b ? -cf.fx : cf.fx;
    f.y += on_b ? -cf.fy : cf.fy;
  }
  return f;
}

double Solver::kinetic_energy() const {
  const auto& bl = model_.blocks;
  double e = 0.0;
  for (std::size_t b = 0; b < bl.size(); ++b)
    if (!bl.prescribed[b] && !bl.deformable[b])
      e += 0.5 * (bl.mass[b] * (bl.vx[b] * bl.vx[b] + bl.vy[b] * bl.vy[b]) +
                  bl.inertia[b] * bl.omega[b] * bl.omega[b]);
  const auto& z = model_.zoning;
  for (std::size_t g = 0; g < z.gridpoints(); ++g)
    if (!z.prescribed[g]) e += 0.5 * z.mass[g] * (z.vx[g] * z.vx[g] + z.vy[g] * z.vy[g]);
  return e;
}

double Solver::contact_strain_energy() const {
  double e = 0.0;
  for (std::size_t l = 0; l < laws_.size(); ++l)
    for (std::size_t i = law_begin_[l]; i < law_begin_[l + 1]; ++i)
      e += laws_[l]->strain_energy(i - law_begin_[l], model_.contacts[i].fn, model_.contacts[i].fs);
  return e;
}

double Solver::unbalanced_force_ratio() const {
  const auto& bl = model_.blocks;
  const Point g = settings_.gravity;
  double unbalanced = 0.0;
  std::size_t bodies = 0;
  for (std::size_t b = 0; b < bl.size() && b < sums_.size(); ++b) {
    if (bl.prescribed[b] || bl.deformable[b]) continue;
    unbalanced += std::hypot(sums_[b].fx + bl.fx[b] + bl.gravity_mass[b] * g.x,
                             sums_[b].fy + bl.fy[b] + bl.gravity_mass[b] * g.y);
    ++bodies;
  }
  const auto& z = model_.zoning;
  for (std::size_t i = 0; i < z.gridpoints() && i < zfx_.size(); ++i) {
    if (z.prescribed[i]) continue;
    unbalanced += std::hypot(zfx_[i] + z.cfx[i] + z.fx[i] + z.gravity_mass[i] * g.x,
                             zfy_[i] + z.cfy[i] + z.fy[i] + z.gravity_mass[i] * g.y);
    ++bodies;
  }
  double contact = 0.0;
  for (const auto& c : model_.contacts) contact += std::hypot(c.fn, c.fs);
  if (bodies == 0 || unbalanced == 0.0) return 0.0;
  if (contact == 0.0) return std::numeric_limits<double>::infinity();
  return (unbalanced / double(bodies)) / (contact / double(model_.contacts.size()));
}

double Solver::contact_stiffness_on(std::size_t b) const {
  double k = 0.0;
  for (std::uint32_t g = gather_begin_[b]; g < gather_begin_[b + 1]; ++g) {
    const std::size_t i = gather_[g] & ~b_side;
    const std::size_t l = model_.contacts[i].law;
    k += laws_[l]->max_stiffness(i - law_begin_[l]);
  }
  return k;
}

void Solver::check_stability() const {
  const auto& bl = model_.blocks;
  for (std::size_t b = 0; b < bl.size(); ++b) {
    if (!std::isfinite(bl.x[b] + bl.y[b] + bl.theta[b] + bl.vx[b] + bl.vy[b] + bl.omega[b]))
      throw InstabilityError(
          fmt::format("block {} has a non-finite position or velocity at step {} (t = {:.6g} s)", b,
                      steps_, time_));
  }
  const auto& z = model_.zoning;
  for (std::size_t g = 0; g < z.gridpoints(); ++g) {
    if (!std::isfinite(z.x[g] + z.y[g] + z.vx[g] + z.vy[g]))
      throw InstabilityError(
          fmt::format("gridpoint {} of block {} has a non-finite position or velocity at step {} "
                      "(t = {:.6g} s)",
                      g, z.block[g], steps_, time_));
  }
  const double limit = settings_.overlap_limit * model_.rounding_length;
  for (const auto& c : model_.contacts) {
    if (c.gap < -limit)
      throw InstabilityError(fmt::format(
          "contact overlap too great between blocks {} and {}: {:.3g} m > {:.3g} m ({} x the "
          "rounding "
          "length, contact.overlap_limit) at step {}"
          " (t = {:.6g} s; the contact is {:.3g} m long, {}, and carries {:.3g} N/m); loading too "
          "fast, time step too large or stiffness too low",
          c.a, c.b, -c.gap, limit, settings_.overlap_limit, steps_, time_, c.length,
          c.bonded && c.state <= model::ContactState::slipping ? "bonded" : "not bonded", c.fn));
  }
  const double supplied = energy_.boundary_work + energy_.body_work + energy_.initial;
  const double ke = kinetic_energy();
  if (steps_ > 100 && ke > 1.5 * std::abs(supplied) + 1e-9)
    throw InstabilityError(fmt::format(
        "kinetic energy {:.4g} J/m exceeds the work supplied {:.4g} J/m at step {} (t = {:.6g} s):"
        " the explicit integration is unstable; lower solver.safety_factor",
        ke, supplied, steps_, time_));
}

}  // namespace vorodec::solver

namespace vorodec::solver {

namespace {
std::pair<std::size_t, std::size_t> group_of(const std::vector<std::size_t>& begin,
                                             const model::Contact& c, std::size_t i) {
  return {c.law, i - begin[c.law]};
}
}  // namespace

bool Solver::bond(std::size_t i, laws::BondView& out) const {
  const auto [g, local] = group_of(law_begin_, model_.contacts[i], i);
  return laws_[g]->bond(local, out);
}

void Solver::set_bond(std::size_t i, const laws::BondView& b, double fn, double fs) {
  model::Contact& c = model_.contacts[i];
  const auto [g, local] = group_of(law_begin_, c, i);
  const double before = laws_[g]->strain_energy(local, c.fn, c.fs);
  laws_[g]->set_bond(local, b, c.gap, fn, fs);
  c.fn = fn;
  c.fs = fs;
  energy_.corrosion += before - laws_[g]->strain_energy(local, fn, fs);
}

bool Solver::preload(std::size_t i, double fn, double fs) {
  model::Contact& c = model_.contacts[i];
  const auto [g, local] = group_of(law_begin_, c, i);
  if (!laws_[g]->preload(local, c.gap, fn, fs)) return false;
  energy_.initial +=
      laws_[g]->strain_energy(local, fn, fs) - laws_[g]->strain_energy(local, c.fn, c.fs);
  c.fn = fn;
  c.fs = fs;
  return true;
}

void Solver::break_bond(std::size_t i, laws::ContactEvent type, double time) {
  model::Contact& c = model_.contacts[i];
  const auto [g, local] = group_of(law_begin_, c, i);
  laws::BondView b{};
  laws_[g]->bond(local, b);
  // What the broken joint will give up as it opens or slips: its strain energy at the break.
  const double released = laws_[g]->strain_energy(local, c.fn, c.fs);
  b.broken = true;
  laws_[g]->set_bond(local, b, c.gap, c.fn, c.fs);
  c.state = type == laws::ContactEvent::tensile_failure ? model::ContactState::tensile_failed
                                                        : model::ContactState::shear_failed;
  const model::ContactFrame f = model::contact_frame(model_.blocks.corners(), c);
  cracks_.push_back({time, f.point.x, f.point.y, f.n.x, f.n.y, c.length, c.a, c.b, type, released});
}

}  // namespace vorodec::solver
