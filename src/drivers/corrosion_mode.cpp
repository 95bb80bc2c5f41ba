#include "corrosion_mode.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "vorodec/io/json.hpp"
#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::run {

// A member added is either saved in CorrosionControl::serialize or comes from the model file;
// then update these sizes.
static_assert(sizeof(CorrosionControl) == 240, "CorrosionControl changed: see its serialize()");
static_assert(sizeof(CorrosionStageReport) == 104,
              "CorrosionStageReport changed: it is saved as bytes");

double CorrosionClock::next(double shortest) {
  if (dt_ == 0.0) {
    dt_ = shortest / n_c_;
  } else if (quiet_ >= static_cast<long>(n_c_)) {
    dt_ *= 2.0;
    quiet_ = 0;
  }
  return std::min(dt_, shortest);
}

void CorrosionClock::after(bool broke) {
  if (broke) {
    dt_ = 0.0;
    quiet_ = 0;
  } else {
    ++quiet_;
  }
}

CorrosionControl::CorrosionControl(const loading::Stage& stage, const CorrosionConfig& config,
                                   const model::Model& model, const solver::Solver& solver,
                                   std::span<const std::int32_t> block_grain)
    : stage_(stage), config_(config), clock_(corrosion_settings(stage).steps_per_failure) {
  const auto& contacts = model.contacts;
  const auto specimen = [&](std::int32_t b) {
    return static_cast<std::size_t>(b) < block_grain.size() &&
           model.blocks.group[static_cast<std::size_t>(b)] == model::Group::specimen;
  };
  // Joints by block pair, in pair order then contact id: the same for any contact order.
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<Bond>> joints;
  std::vector<Bond> inter;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const model::Contact& c = contacts[i];
    laws::BondView b;
    if (!c.bonded || c.state >= model::ContactState::tensile_failed || !specimen(c.a) ||
        !specimen(c.b) || !solver.bond(i, b) || b.broken ||
        (b.tension_force <= 0 && b.cohesion_force <= 0))
      continue;
    const Bond bond{c.id, b.kn, b.ks, b.tension_force, b.cohesion_force, b.tan_phi, 1.0};
    const bool inside =
        block_grain[static_cast<std::size_t>(c.a)] == block_grain[static_cast<std::size_t>(c.b)];
    if (inside && config.transgranular)
      joints[{std::min(c.a, c.b), std::max(c.a, c.b)}].push_back(bond);
    else if (!inside && config.intergranular)
      inter.push_back(bond);
  }
  for (auto& [key, list] : joints) {
    std::sort(list.begin(), list.end(), [](const Bond& x, const Bond& y) { return x.id < y.id; });
    joints_.push_back({static_cast<std::uint32_t>(bonds_.size()),
                       static_cast<std::uint32_t>(list.size()), 0.0, 0.0, 0});
    bonds_.insert(bonds_.end(), list.begin(), list.end());
  }
  std::sort(inter.begin(), inter.end(), [](const Bond& x, const Bond& y) { return x.id < y.id; });
  inter_begin_ = bonds_.size();
  bonds_.insert(bonds_.end(), inter.begin(), inter.end());
  // D0: the joint's length, the sum of its contacts' lengths.
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t i = 0; i < contacts.size(); ++i) index[contacts[i].id] = i;
  for (Joint& j : joints_) {
    for (std::uint32_t k = j.first; k < j.first + j.count; ++k)
      j.d0 += contacts[index.at(bonds_[k].id)].length;
    j.d = j.d0;
  }
}

CorrosionControl::Next CorrosionControl::after_step(solver::Solver& solver, model::Model& model,
                                                    const measure::SpecimenState& s) {
  const CorrosionSettings& cs = corrosion_settings(stage_);
  ++report_.mechanical_steps;
  ++since_equilibrium_;
  if (since_equilibrium_ % cs.check_interval != 0) return Next::step;
  const double target = stage_.target_stress;
  const bool held = std::abs(s.axial_stress - target) <= 0.01 * target;
  if (!started_) {  // loading: the limit counts from when the target is first held
    if (held || held_at_ >= 0) held_at_ = std::max(held_at_, 0L) + cs.check_interval;
    loading_peak_ = std::max(loading_peak_, s.axial_stress);
    // Past its peak below the target: it cannot take the load at all.
    if (loading_peak_ > 0.5 * target && s.axial_stress < 0.9 * loading_peak_) {
      report_.failure_time = 0.0;
      return Next::collapsed;
    }
  }
  if (!held || solver.unbalanced_force_ratio() >= cs.equilibrium_ratio) {
    if ((started_ ? since_equilibrium_ : held_at_) < cs.max_equilibrium_steps) return Next::step;
    report_.failure_time = started_ ? report_.time : 0.0;
    return Next::collapsed;
  }
  report_.longest_relaxation =
      std::max(report_.longest_relaxation, started_ ? since_equilibrium_ : held_at_);
  since_equilibrium_ = 0;
  if (!started_) report_.first_strain = s.axial_strain;
  report_.last_strain = s.axial_strain;
  if (started_) clock_.after(broke_ || solver.cracks().size() > cracks_seen_);
  started_ = true;
  if (report_.time >= cs.max_time) return Next::time_up;
  const double before = report_.time;
  broke_ = corrode(solver, model);
  cracks_seen_ = solver.cracks().size();
  if (report_.time == before && !broke_) return Next::no_corrosion;
  return Next::corroded;
}

namespace {
laws::ContactEvent tensile_or_shear(bool tensile) {
  return tensile ? laws::ContactEvent::tensile_failure : laws::ContactEvent::shear_failure;
}
}  // namespace

// One corrosion step's working state: what each corroding item is now (its rate, its floor and its
// time to failure), and the shortest time to failure of them all.
struct CorrosionControl::Step {
  struct JointNow {
    std::vector<std::size_t> contacts;
    std::vector<laws::PairContact> pair;
    laws::PairSection p;
    laws::BondStrength strength;
    double rate = 0, d_min = 0;
    bool fails = false, tensile = true;
  };

  Step(const CorrosionConfig& config, const CorrosionSettings& settings, std::size_t joint_count,
       std::size_t contact_count, solver::Solver& s, model::Model& m)
      : cfg(config),
        beta1(cfg.rate.at(settings.driving_stress_ratio)),
        beta3(cfg.beta3_per_beta1 * beta1),
        frozen(settings.frozen_rate),
        solver(s),
        model(m),
        corners(m.blocks.corners()),
        now(joint_count),
        rate(contact_count, 0.0),
        floor(contact_count, 0.0),
        fails(contact_count, 0),
        tensile(contact_count, 1),
        stress(contact_count) {
    for (std::size_t i = 0; i < m.contacts.size(); ++i) index[m.contacts[i].id] = i;
  }

  // Whether contact `id` still holds its bond; then `i` is its index.
  bool live(std::uint64_t id, std::size_t& i) const {
    const auto it = index.find(id);
    if (it == index.end()) return false;
    i = it->second;
    laws::BondView b;
    return model.contacts[i].state < model::ContactState::tensile_failed && solver.bond(i, b) &&
           !b.broken;
  }
  // Each item's rate as its value falls with its forces held (laws::held_time).
  auto bond_rate(const JointNow& jn) const {
    return [&cfg = cfg, beta1 = beta1, &jn](double d) {
      laws::BondSection s = jn.p.section;
      s.d = d;
      return laws::length_rate(cfg.bonded, beta1, s, jn.strength);
    };
  }
  auto factor_rate(std::size_t q) const {
    return [&cfg = cfg, beta3 = beta3, &held = stress[q]](double lambda) {
      return laws::factor_rate(cfg.degradation, beta3,
                               laws::stress_level(held.first, held.second, lambda));
    };
  }

  const CorrosionConfig& cfg;
  const double beta1, beta3;
  const bool frozen;
  solver::Solver& solver;
  model::Model& model;
  std::unordered_map<std::uint64_t, std::size_t> index;  // contact id -> index
  const model::CornerView corners;
  std::vector<JointNow> now;  // by joint
  // By grain-boundary contact (bonds_[inter_begin_ + q]):
  std::vector<double> rate, floor;
  std::vector<std::uint8_t> fails, tensile;
  std::vector<std::pair<laws::ContactStress, laws::InitialStrength>> stress;
  double shortest = std::numeric_limits<double>::infinity();
  bool broke = false;
};

void CorrosionControl::break_contacts(Step& s, const std::vector<std::size_t>& list, bool tension,
                                      long& n) {
  for (const std::size_t i : list) {
    s.solver.break_bond(i, tensile_or_shear(tension), report_.time);
    ++n;
  }
  s.broke = true;
}

// A sub-block joint's section, strength, rate and time to failure; one whose contact has failed
// (or that is past its strength) fails whole.
void CorrosionControl::assess_joints(Step& s) {
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    Joint& joint = joints_[j];
    if (joint.done) continue;
    Step::JointNow& jn = s.now[j];
    bool whole = true;
    model::Point tangent{0, 0};
    for (std::uint32_t k = joint.first; k < joint.first + joint.count; ++k) {
      std::size_t i = 0;
      if (!s.live(bonds_[k].id, i)) {
        whole = false;
        continue;
      }
      model::Contact& c = s.model.contacts[i];
      const model::ContactFrame f = model::contact_frame(s.corners, c);
      if (jn.contacts.empty()) tangent = {-f.n.y, f.n.x};
      jn.contacts.push_back(i);
      jn.pair.push_back({c.fn, c.fs, dot(f.point, tangent), c.length});
    }
    if (!whole) {  // one end already failed: the section has failed
      joint.done = 1;
      if (!jn.contacts.empty()) break_contacts(s, jn.contacts, true, report_.broken_transgranular);
      continue;
    }
    const Bond& first = bonds_[joint.first];
    double tension = 0, cohesion = 0;
    for (std::uint32_t k = joint.first; k < joint.first + joint.count; ++k) {
      tension += bonds_[k].tension0;
      cohesion += bonds_[k].cohesion0;
    }
    jn.strength = {tension / joint.d0, cohesion / joint.d0, first.tan_phi};
    jn.p = laws::pair_section(jn.pair, joint.d);
    if (laws::bond_fails(jn.p.section, jn.strength)) {
      jn.fails = true;
      jn.tensile = laws::bond_tension(jn.p.section) >= jn.strength.tension;
      continue;
    }
    jn.rate = laws::length_rate(s.cfg.bonded, s.beta1, jn.p.section, jn.strength);
    if (jn.rate == 0) continue;
    jn.d_min = laws::min_bonded_length(s.cfg.bonded, jn.p.section, jn.strength, joint.d0);
    s.shortest =
        std::min(s.shortest, s.frozen ? laws::time_to(joint.d, jn.d_min, jn.rate)
                                      : laws::held_time(s.bond_rate(jn), joint.d, jn.d_min));
    ++report_.active_bonds;
  }
}

// A grain-boundary contact's stress level, rate, floor and time to failure.
void CorrosionControl::assess_contacts(Step& s) {
  for (std::size_t k = inter_begin_; k < bonds_.size(); ++k) {
    Bond& b = bonds_[k];
    const std::size_t q = k - inter_begin_;
    std::size_t i = 0;
    if (b.lambda <= 0 || !s.live(b.id, i)) continue;
    const model::Contact& c = s.model.contacts[i];
    const laws::ContactStress st{-c.fn / c.length, std::abs(c.fs) / c.length};
    const laws::InitialStrength p0{b.tension0 / c.length, b.cohesion0 / c.length, b.tan_phi};
    const double m = laws::stress_level(st, p0, b.lambda);
    if (m >= 1.0) {
      s.fails[q] = 1;
      s.tensile[q] = st.sigma > 0 && st.sigma >= b.lambda * p0.tension;
      continue;
    }
    s.rate[q] = laws::factor_rate(s.cfg.degradation, s.beta3, m);
    if (s.rate[q] == 0) continue;
    s.floor[q] = laws::min_strength_factor(s.cfg.degradation, st, p0);
    s.tensile[q] = st.sigma > 0 && st.sigma / p0.tension >= (st.tau + st.sigma * p0.tan_phi) /
                                                                std::max(p0.cohesion, 1e-300);
    s.stress[q] = {st, p0};
    ++report_.active_contacts;
    if (s.frozen) {
      s.shortest = std::min(s.shortest, laws::time_to(b.lambda, s.floor[q], s.rate[q]));
      continue;
    }
    // Most contacts are far from failing: a panel or two of their integral already passes the
    // shortest time, and the whole (160 rates) could not lower it. The same shortest, bit for bit.
    if (!laws::held_time_exceeds(s.factor_rate(q), b.lambda, s.floor[q], s.shortest))
      s.shortest = std::min(s.shortest, laws::held_time(s.factor_rate(q), b.lambda, s.floor[q]));
  }
}

// Bonds already past their strength (after the last equilibrium) break now, at no cost of time.
void CorrosionControl::break_failed(Step& s) {
  for (std::size_t j = 0; j < joints_.size(); ++j)
    if (s.now[j].fails) {
      joints_[j].done = 1;
      break_contacts(s, s.now[j].contacts, s.now[j].tensile, report_.broken_transgranular);
    }
  for (std::size_t k = inter_begin_; k < bonds_.size(); ++k) {
    const std::size_t q = k - inter_begin_;
    std::size_t i = 0;
    if (s.fails[q] && s.live(bonds_[k].id, i)) {
      bonds_[k].lambda = 0;
      break_contacts(s, {i}, s.tensile[q], report_.broken_intergranular);
    }
  }
}

// The corrosion step (s), never past the stage's duration; the clocks move on by it.
double CorrosionControl::advance_clock(double shortest, solver::Solver& solver) {
  const double dt =
      std::min(clock_.next(shortest), corrosion_settings(stage_).max_time - report_.time);
  report_.time += dt;
  report_.min_step = report_.corrosion_steps ? std::min(report_.min_step, dt) : dt;
  report_.max_step = std::max(report_.max_step, dt);
  ++report_.corrosion_steps;
  solver.set_crack_clock(report_.time);
  return dt;
}

// Each joint's bonded length falls over dt: its contacts' springs, strengths and forces shrink
// with it, or the joint fails at its floor.
void CorrosionControl::shorten_joints(Step& s, double dt) {
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    Step::JointNow& jn = s.now[j];
    Joint& joint = joints_[j];
    if (joint.done || jn.rate == 0) continue;
    const double d = s.frozen ? joint.d - jn.rate * dt
                              : laws::held_value_after(s.bond_rate(jn), joint.d, jn.d_min, dt);
    if (d <= jn.d_min + 1e-9 * joint.d0) {
      joint.done = 1;
      const laws::BondSection& sec = jn.p.section;
      // Which limit set the floor: the tensile root (or xi_a) or the shear one.
      const bool shear =
          jn.strength.cohesion > 0 &&
          std::abs((std::abs(sec.fs) - sec.fn * jn.strength.tan_phi) / jn.strength.cohesion -
                   jn.d_min) <= 1e-12 * joint.d0;
      break_contacts(s, jn.contacts, !shear, report_.broken_transgranular);
      continue;
    }
    const double xi = d / joint.d, total = d / joint.d0;
    const std::vector<laws::PairContact> shrunk = laws::shrink_pair(jn.pair, jn.p, xi);
    for (std::size_t n = 0; n < jn.contacts.size(); ++n) {
      const Bond& b = bonds_[joint.first + n];
      s.solver.set_bond(
          jn.contacts[n],
          {total * b.kn0, total * b.ks0, total * b.tension0, total * b.cohesion0, b.tan_phi, false},
          shrunk[n].fn, shrunk[n].fs);
    }
    joint.d = d;
  }
}

// Each grain-boundary contact's strength factor falls over dt, or the contact fails at its floor.
void CorrosionControl::weaken_contacts(Step& s, double dt) {
  for (std::size_t k = inter_begin_; k < bonds_.size(); ++k) {
    const std::size_t q = k - inter_begin_;
    Bond& b = bonds_[k];
    std::size_t i = 0;
    if (s.rate[q] == 0 || !s.live(b.id, i)) continue;
    b.lambda = s.frozen ? b.lambda - s.rate[q] * dt
                        : laws::held_value_after(s.factor_rate(q), b.lambda, s.floor[q], dt);
    if (b.lambda <= s.floor[q] + 1e-9) {
      b.lambda = 0;
      break_contacts(s, {i}, s.tensile[q], report_.broken_intergranular);
      continue;
    }
    const model::Contact& c = s.model.contacts[i];
    s.solver.set_bond(
        i, {b.kn0, b.ks0, b.lambda * b.tension0, b.lambda * b.cohesion0, b.tan_phi, false}, c.fn,
        c.fs);
  }
}

bool CorrosionControl::corrode(solver::Solver& solver, model::Model& model) {
  Step s(config_, corrosion_settings(stage_), joints_.size(), bonds_.size() - inter_begin_, solver,
         model);
  report_.active_bonds = report_.active_contacts = 0;
  assess_joints(s);
  assess_contacts(s);
  break_failed(s);
  if (s.broke || !std::isfinite(s.shortest)) return s.broke;
  const double dt = advance_clock(s.shortest, solver);
  shorten_joints(s, dt);
  weaken_contacts(s, dt);
  return s.broke;
}

void CorrosionMode::begin_stage(const StageContext& c) {
  control_.emplace(c.stage, *config_, model_, solver_, specimen_.block_grain);
  solver_.set_crack_clock(0.0);
}

ModeVerdict CorrosionMode::after_step(const StageContext& c, const measure::SpecimenState& s) {
  switch (control_->after_step(solver_, model_, s)) {
    case CorrosionControl::Next::step:
      return {};
    case CorrosionControl::Next::corroded:
      return {":equilibrium", "", false, false};
    case CorrosionControl::Next::collapsed: {
      const double t = control_->report().failure_time;
      return {"",
              fmt::format("static-fatigue failure in stage '{}' after {:.4g} s ({:.4g} days) of "
                          "corrosion: no equilibrium within {} steps",
                          c.stage.name, t, t / 86400.0,
                          corrosion_settings(c.stage).max_equilibrium_steps),
              true, true};
    }
    case CorrosionControl::Next::no_corrosion:
      return {"",
              fmt::format("stage '{}': no bond corrodes at this stress (none above its "
                          "activation): no static-fatigue failure",
                          c.stage.name),
              true, false};
    case CorrosionControl::Next::time_up:
      return {"", "", true, false};
  }
  return {};
}

std::string CorrosionMode::unstable(const StageContext& c, const std::string& what) {
  // Static fatigue: the collapse went unstable.
  CorrosionStageReport r = control_->report();
  r.failure_time = r.time;
  reports_.emplace_back(c.index, r);
  control_.reset();
  solver_.set_crack_clock(std::numeric_limits<double>::quiet_NaN());
  return fmt::format(
      "static-fatigue failure in stage '{}' after {:.4g} s of corrosion, unstable: {}",
      c.stage.name, r.time, what);
}

void CorrosionMode::end_stage(const StageContext& c) {
  reports_.emplace_back(c.index, control_->report());
  control_.reset();
  solver_.set_crack_clock(std::numeric_limits<double>::quiet_NaN());
}

bool CorrosionMode::progress(const StageContext&, ProgressReport& r) const {
  if (!control_) return false;
  const CorrosionStageReport& c = control_->report();
  r.clock = fmt::format("corrosion {:.4g} s = {:.4g} days = {:.3g} years, step {}", c.time,
                        c.time / 86400.0, c.time / (365.25 * 86400.0), c.corrosion_steps);
  // When the specimen fails is what the stage finds out: no percentage.
  r.waiting = fmt::format("static fatigue: until collapse; {} tensile + shear cracks",
                          solver_.cracks().size());
  return true;
}

void CorrosionMode::column_values(std::vector<double>& row) const {
  // The clock of the current corrosion stage, or of the last one.
  const double clock = control_           ? control_->time()
                       : reports_.empty() ? 0.0
                                          : reports_.back().second.time;
  row.insert(row.end(), {clock, solver_.energy().corrosion});
}

// The corrosion clock, its steps and the failure time (null: no failure).
void CorrosionMode::summarise(io::Json& summary) const {
  if (reports_.empty()) return;
  io::Json rows = io::Json::array();
  for (const auto& [i, r] : reports_) {
    const loading::Stage& st = cfg_.load_path.stages[i];
    rows.push_back(
        {{"stage", st.name},
         {"driving_stress_ratio", io::rounded(corrosion_settings(st).driving_stress_ratio, 6)},
         {"target_stress_Pa", io::rounded(st.target_stress, 8)},
         {"corrosion_time_s", io::rounded(r.time, 10)},
         {"failure_time_s", io::rounded(r.failure_time, 10)},
         {"corrosion_steps", r.corrosion_steps},
         {"mechanical_steps", r.mechanical_steps},
         {"mechanical_steps_per_corrosion_step",
          io::rounded(
              r.corrosion_steps ? double(r.mechanical_steps) / double(r.corrosion_steps) : 0.0, 6)},
         {"longest_relaxation_steps", r.longest_relaxation},
         {"corrosion_step_s", {io::rounded(r.min_step, 6), io::rounded(r.max_step, 6)}},
         {"creep_strain", io::rounded(r.last_strain - r.first_strain, 6)},
         {"broken_transgranular", r.broken_transgranular},
         {"broken_intergranular", r.broken_intergranular},
         {"corroding_bonds", r.active_bonds},
         {"corroding_contacts", r.active_contacts}});
  }
  summary["corrosion_stages"] = std::move(rows);
}

void CorrosionMode::save(checkpoint::OutArchive& ar) const {
  save_mode_state(ar, control_, reports_);
}

void CorrosionMode::load(checkpoint::InArchive& ar, const loading::Stage& current) {
  load_mode_state(ar, control_, reports_, current, *config_);
}

// [corrosion]: the constants of the two layers (docs/theory.md §14; [Liu2020] Table 4 for LdB
// granite). A layer switched off keeps its keys (a batch case may switch it), required only when
// on.
std::shared_ptr<const loading::ExtensionSettings> CorrosionMode::read_table(
    io::TomlSection& sec, io::TomlSection& top, const io::ModelConfig& cfg) {
  if (!cfg.grains)
    top.fail("corrosion",
             "stress corrosion needs a grain-based specimen ([specimen] kind = "
             "\"grains\"): its layers act inside grains and on grain boundaries");
  auto c = std::make_shared<CorrosionConfig>();
  c->rate.beta_up = sec.positive("beta_up", laws::required);
  c->rate.beta_low = sec.positive("beta_low", laws::required);
  c->rate.r_mid = sec.positive("r_mid", laws::required);
  c->rate.k_v = sec.number("k_v", laws::required);
  if (c->rate.k_v >= 0)
    sec.fail("k_v", fmt::format("must be negative: the rate rises with the driving-stress ratio "
                                "(got {})",
                                c->rate.k_v));
  c->beta3_per_beta1 = sec.positive("beta3_per_beta1", 1.0);
  c->transgranular = sec.boolean("transgranular", true);
  c->intergranular = sec.boolean("intergranular", true);
  if (!c->transgranular && !c->intergranular)
    sec.fail("intergranular", "at least one of transgranular and intergranular must be on");
  const io::GrainConfig& g = *cfg.grains;
  const auto bonded_law = [&](const io::LawChoice& law, const char* key) {
    if (!laws::find_law(law.name)->make(law.params, 0)->degradable_bonds())
      sec.fail(key, fmt::format("corrodes bonds that a law lets it degrade; law '{}' has none (its "
                                "strength is not a bond the corrosion layers can weaken)",
                                law.name));
  };
  const auto needed = [](bool on) { return on ? laws::required : 1.0; };
  if (c->transgranular) {
    bonded_law(g.transgranular, "transgranular");
    for (const auto& in : g.inside)
      if (in) bonded_law(*in, "transgranular");
  }
  c->bonded.beta2 = sec.positive("beta2", needed(c->transgranular));
  c->bonded.activation_stress = sec.non_negative("activation_stress", needed(c->transgranular));
  c->bonded.xi_a = sec.positive("min_length_ratio", 0.01);
  if (c->bonded.xi_a >= 1) sec.fail("min_length_ratio", "must be < 1");
  if (c->intergranular) {
    bonded_law(g.intergranular, "intergranular");
    for (const auto& p : g.pairs) bonded_law(p.law, "intergranular");
  }
  c->degradation.beta4 = sec.positive("beta4", needed(c->intergranular));
  c->degradation.m_s = sec.non_negative("activation_level", needed(c->intergranular) * 0.5);
  if (c->degradation.m_s >= 1) sec.fail("activation_level", "must be < 1");
  c->degradation.lambda_a = sec.positive("min_strength_factor", 0.01);
  if (c->degradation.lambda_a >= 1) sec.fail("min_strength_factor", "must be < 1");
  return c;
}

// control = "corrosion": the servo holds sigma1 = sigma3 + rs (sf - sigma3) while the layers of
// [corrosion] run, until collapse or the duration (it does not end when the target is held).
std::shared_ptr<const loading::ExtensionSettings> CorrosionMode::read_stage(
    io::TomlSection& sec, loading::Stage& st, const io::ModelConfig& cfg) {
  if (!cfg.tables.count(keys.table))
    sec.fail("control", "a corrosion stage needs a [corrosion] table (the layers' constants)");
  st.control = loading::Control::axial_stress;
  auto c = std::make_shared<CorrosionSettings>();
  c->driving_stress_ratio = sec.positive("driving_stress_ratio", laws::required);
  if (c->driving_stress_ratio >= 1)
    sec.fail("driving_stress_ratio",
             fmt::format("must be in (0, 1) (got {})", c->driving_stress_ratio));
  const double s3 = cfg.load_path.confining_stress;
  c->peak_stress = sec.positive("peak_stress", laws::required);
  if (c->peak_stress <= s3)
    sec.fail("peak_stress",
             fmt::format("must exceed the confining stress {} Pa (got {})", s3, c->peak_stress));
  st.target_stress = s3 + c->driving_stress_ratio * (c->peak_stress - s3);
  st.platen_velocity = sec.positive("platen_velocity", 0.05);  // servo's speed cap
  c->steps_per_failure = sec.number("steps_per_failure", c->steps_per_failure);
  if (!(c->steps_per_failure >= 1))
    sec.fail("steps_per_failure", fmt::format("n_c must be >= 1 (got {})", c->steps_per_failure));
  const std::string held = "held";
  const std::string ttf = sec.string("time_to_failure", &held);
  if (ttf != "held" && ttf != "frozen")
    sec.fail("time_to_failure",
             fmt::format("must be \"held\" (forces held, integrated) or "
                         "\"frozen\" (the rate frozen, [Potyondy2007]) (got \"{}\")",
                         ttf));
  c->frozen_rate = ttf == "frozen";
  c->equilibrium_ratio = sec.positive("equilibrium_ratio", c->equilibrium_ratio);
  c->check_interval = sec.integer("check_interval", c->check_interval, 1);
  c->max_equilibrium_steps = sec.integer("max_equilibrium_steps", c->max_equilibrium_steps, 1);
  int given = 0;
  for (const auto& [key, unit] : {std::pair{"duration", 1.0}, std::pair{"duration_days", 86400.0},
                                  std::pair{"duration_years", 365.25 * 86400.0}})
    if (sec.has(key)) {
      if (++given > 1)
        sec.fail(key, "give at most one of duration (s), duration_days and duration_years");
      c->max_time = unit * sec.positive(key, laws::required);
    }
  if (sec.has("end_time")) sec.fail("end_time", "a corrosion stage ends by failure or duration");
  if (cfg.deformable.enabled)
    sec.fail("control", "corrosion stages need rigid blocks ([blocks] deformable = false)");
  return c;
}

}  // namespace vorodec::run
