#include "shpb_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/engine/observer.hpp"

namespace vorodec::run {

// A member added to the driver is either state a checkpoint carries (save and load it in
// ShpbDriver::state) or comes again from the model file (say so there); then update the size.
// The quiet ends and the gauges' blocks come again from the model.
static_assert(sizeof(ShpbDriver) == 1080, "ShpbDriver changed: see state()");

using model::Group;

namespace {

// [shpb.incident_bar] or [shpb.transmitted_bar]; the transmitted bar takes `like`'s (the incident
// bar's) diameter, E and density unless it gives its own.
loading::BarProperties read_bar(io::TomlSection b, const loading::BarProperties* like,
                                std::vector<double>& gauges) {
  loading::BarProperties p;
  p.length = b.positive("length", laws::required);
  p.width = b.positive("diameter", like ? like->width : laws::required);
  p.youngs_modulus = b.positive("E", like ? like->youngs_modulus : laws::required);
  p.density = b.positive("density", like ? like->density : laws::required);
  const std::string free_end = "free";
  const std::string end = b.string("far_end", &free_end);
  if (end != "free" && end != "quiet")
    b.fail("far_end", "\"free\" or \"quiet\" (viscous, non-reflecting)");
  p.quiet_far_end = end == "quiet";
  gauges = b.numbers("gauges");
  for (const double x : gauges)
    if (!(x > 0 && x < p.length))
      b.fail("gauges", fmt::format("a gauge at {} m is outside its bar (0, {} m) from the face", x,
                                   p.length));
  b.finish();
  return p;
}

// bars = "blocks": the bars built from blocks of bar_block_length.
void read_block_bars(io::TomlSection& sec, loading::ShpbConfig& s) {
  s.bar_block_length = sec.positive("bar_block_length", 0.1 * s.incident.width);
  if (!s.incident.quiet_far_end)
    sec.sub("incident_bar")
        .fail("far_end",
              "with bars = \"blocks\" the striker's pulse enters through the incident "
              "bar's far end, which absorbs what returns: far_end = \"quiet\"");
  if (s.transmitted.length < 2.0 * s.bar_block_length)
    sec.fail("bar_block_length",
             fmt::format("{} m: each bar needs at least two blocks", s.bar_block_length));
}

// m/s, the striker speed from whichever of the three readings of the incident wave the file
// gives (docs/dynamics.md): a striker of the bar's impedance sends rho c0 v / 2, a particle
// velocity of v / 2.
double read_incident_wave(io::TomlSection& sec, const loading::BarProperties& bar) {
  static constexpr std::array<const char*, 3> keys = {"striker_velocity", "incident_stress",
                                                      "incident_particle_velocity"};
  const char* given = nullptr;
  for (const char* k : keys)
    if (sec.has(k)) {
      if (given)
        sec.fail(k, fmt::format("the incident wave is given twice: keep {} or {}", given, k));
      given = k;
    }
  if (!given)
    sec.fail("striker_velocity",
             "required (or incident_stress, Pa, or incident_particle_velocity, m/s)");
  const double value = sec.positive(given, laws::required);
  if (given == keys[0]) return value;
  return given == keys[1] ? 2.0 * value / bar.impedance() : 2.0 * value;
}

// [shpb] with [shpb.incident_bar] and [shpb.transmitted_bar].
loading::ShpbConfig read_shpb(io::TomlSection& sec) {
  loading::ShpbConfig s;
  s.incident = read_bar(sec.sub("incident_bar"), nullptr, s.incident_gauges);
  s.transmitted = read_bar(sec.sub("transmitted_bar"), &s.incident, s.transmitted_gauges);
  s.striker_length = sec.positive("striker_length", laws::required);
  s.striker_velocity = read_incident_wave(sec, s.incident);
  const double pulse = 2.0 * s.striker_length / s.incident.wave_speed();
  if (2.0 * s.striker_length >= s.incident.length)
    sec.fail("striker_length",
             fmt::format("the pulse (2 x striker_length = {} m) is longer than the incident bar "
                         "({} m): incident and reflected waves overlap everywhere on it",
                         2.0 * s.striker_length, s.incident.length));
  for (const double x : s.incident_gauges)
    if (x < s.striker_length)
      sec.fail("striker_length",
               fmt::format("the incident gauge at {} m is closer to the face than half the "
                           "pulse ({} m): its incident and reflected waves overlap",
                           x, s.striker_length));
  s.rise_time = sec.non_negative("rise_time", 0.0);
  if (2.0 * s.rise_time > pulse)
    sec.fail("rise_time", fmt::format("the rise and the fall ({} s each) take longer than the "
                                      "pulse (2 x striker_length / c0 = {} s)",
                                      s.rise_time, pulse));
  const std::string linear = "linear";
  const std::string shape = sec.string("rise_shape", &linear);
  if (shape != "linear" && shape != "cosine")
    sec.fail(
        "rise_shape",
        fmt::format("\"linear\" (a ramp) or \"cosine\" (a raised cosine) (got \"{}\")", shape));
  s.smooth_rise = shape == "cosine";
  const std::string exact = "exact";
  const std::string bars = sec.string("bars", &exact);
  if (bars != "exact" && bars != "blocks")
    sec.fail("bars", "\"exact\" (1D elastic bars) or \"blocks\" (bars built from blocks)");
  s.block_bars = bars == "blocks";
  if (s.block_bars)
    read_block_bars(sec, s);
  else if (sec.has("bar_block_length"))
    sec.fail("bar_block_length", "only with bars = \"blocks\"");
  s.duration = sec.positive("duration", 2.0 * pulse);
  s.record_interval = sec.positive("record_interval", pulse / 1000.0);
  s.equilibrium_tolerance = sec.positive("equilibrium_tolerance", 0.05);
  return s;
}

}  // namespace

// [shpb]: no confinement, no density scaling, no quiet boundary (the bars are the boundaries).
std::shared_ptr<const loading::ExtensionSettings> ShpbDriver::read_table(
    io::TomlSection& sec, io::TomlSection& top, const io::ModelConfig& cfg) {
  if (cfg.load_path.confining_stress > 0)
    top.fail("loading", "a [shpb] test has no confinement: leave out confining_stress");
  if (cfg.load_path.both_platens)
    top.fail("loading", "a [shpb] test is loaded by its bars: leave out platens");
  if (cfg.solver.time_step > 0)
    io::TomlSection(*top.table()["solver"].as_table(), "solver", top.file())
        .fail("time_step", "density scaling would change the inertia a [shpb] test measures");
  if (top.has("quiet_boundary"))
    top.fail("quiet_boundary", "a [shpb] test's bars are its boundaries: no quiet boundary");
  return std::make_shared<loading::ShpbConfig>(read_shpb(sec));
}

ShpbDriver::ShpbDriver(const DriverContext& c)
    : cfg_(*io::table_settings<loading::ShpbConfig>(c.cfg, keys.table)),
      model_(c.model),
      solver_(c.solver),
      boundary_(c.boundary),
      specimen_(c.specimen),
      limit_{c.step_limit, c.limit_from_option},
      history_steps_(c.cfg.output.history_steps),
      vtk_steps_(c.cfg.output.vtk_steps),
      // The striker hits the bar's far end so that the pulse's front reaches the face at 0.
      incident_(cfg_.incident,
                loading::striker_pulse(cfg_.incident, cfg_.striker_length, cfg_.striker_velocity,
                                       -cfg_.incident.length / cfg_.incident.wave_speed(),
                                       cfg_.rise_time, cfg_.smooth_rise)),
      transmitted_(cfg_.transmitted, nullptr),
      bars_{cfg_, {}, {}, c.boundary.width(), c.boundary.height()},
      state_(measure::measure_specimen(c.model, c.boundary, c.solver)) {
  if (c.boundary.top_platen() < 0 || c.boundary.bottom_platen() < 0)
    throw std::runtime_error("a pressure-bar test needs both platens");
  if (cfg_.block_bars) {
    set_up_block_bars();
    return;
  }
  bars_.incident = [this](double x, double t) { return incident_.stress(x, t); };
  bars_.transmitted = [this](double x, double t) { return transmitted_.stress(x, t); };
  solver_.set_face_control([this] { couple(); });
}

void ShpbDriver::set_up_block_bars() {
  shift_ = cfg_.incident.length / cfg_.incident.wave_speed();
  for (const double x : cfg_.incident_gauges)
    bars_.reach = std::max(bars_.reach, x / cfg_.incident.wave_speed());
  for (const double x : cfg_.transmitted_gauges)
    bars_.reach = std::max(bars_.reach, x / cfg_.transmitted.wave_speed());
  const auto& bl = model_.blocks;
  // Each bar's blocks from its face outwards: the platen, then by distance from the specimen.
  const auto column = [&](Group platen, Group bar) {
    std::vector<std::uint32_t> c;
    for (std::uint32_t b = 0; b < bl.size(); ++b)
      if (bl.group[b] == platen || bl.group[b] == bar) c.push_back(b);
    const double y = bl.y[c.front()];
    std::sort(c.begin(), c.end(), [&](std::uint32_t a, std::uint32_t b) {
      return std::abs(bl.y[a] - y) < std::abs(bl.y[b] - y);
    });
    return c;
  };
  const double h = cfg_.bar_block_length;
  // The striker's pulse enters through the incident bar's far end as a quiet boundary's input
  // (2 rho c0 v_in with v_in = sigma / rho c0): the wave a striker of the bar's material and
  // section sends, rise and fall included; the end absorbs what comes back.
  const loading::BarProperties& in = cfg_.incident;
  const auto pulse = loading::striker_pulse(in, cfg_.striker_length, cfg_.striker_velocity, 0.0,
                                            cfg_.rise_time, cfg_.smooth_rise);
  const double z_in = in.impedance();
  const auto bar = [&](Group platen, Group group, const std::vector<double>& xs, double sign,
                       const loading::BarProperties& p, std::optional<loading::QuietBoundary>& q,
                       bool struck) {
    const std::vector<std::uint32_t> c = column(platen, group);
    for (const double x : xs) {
      const auto j =
          std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(x / h)), 1, c.size() - 1);
      gauges_.push_back({x, c[j - 1], c[j], sign, p.youngs_modulus, {}});
    }
    if (!p.quiet_far_end && !struck) return;
    const std::uint32_t end = c.back();  // its edge farthest from the specimen
    std::uint32_t best = bl.corner_begin[end];
    double far = -1;
    for (std::uint32_t k = bl.corner_begin[end]; k < bl.corner_begin[end + 1]; ++k) {
      const double mid = sign * (bl.corner[k].y + bl.corner[bl.next_corner(end, k)].y);
      if (mid > far) {
        far = mid;
        best = k;
      }
    }
    // Dashpots rho c0 per area: the bar's own impedance.
    const std::vector<loading::BoundaryEdge> edge{{end, best}};
    q.emplace(struck ? std::vector<loading::BoundaryEdge>{} : edge,
              loading::QuietSettings{p.density, p.wave_speed(), 0.0});
    if (struck)
      q->set_input(edge, [pulse, z_in](double t) {
        return loading::InputVelocity{pulse(t) / z_in, 0.0};
      });
  };
  bar(Group::top_platen, Group::incident_bar, cfg_.incident_gauges, 1.0, cfg_.incident,
      incident_end_, true);
  bar(Group::bottom_platen, Group::transmitted_bar, cfg_.transmitted_gauges, -1.0, cfg_.transmitted,
      transmitted_end_, false);
  const auto recorded = [this](const loading::WaveHistory& face, bool incident) {
    return [this, &face, incident](double x, double t) {
      if (x == 0.0) return face.at(t);
      for (const BlockGauge& g : gauges_)
        if (g.x == x && (g.sign > 0) == incident) return g.stress.at(t);
      return std::nan("");
    };
  };
  bars_.incident = recorded(incident_face_, true);
  bars_.transmitted = recorded(transmitted_face_, false);
}

void ShpbDriver::couple() {
  auto& bl = model_.blocks;
  const auto top = static_cast<std::size_t>(boundary_.top_platen());
  const auto bottom = static_cast<std::size_t>(boundary_.bottom_platen());
  const double t = solver_.time(), mid = t + 0.5 * solver_.dt();
  // The specimen pushes the top platen up and the bottom one down (N per m): compression +.
  const double s_in = solver_.contact_force(top).y / cfg_.incident.width;
  const double s_tr = -solver_.contact_force(bottom).y / cfg_.transmitted.width;
  incident_.record_face(t, s_in);
  transmitted_.record_face(t, s_tr);
  bars_.recorded_until = t;
  // The step's velocity is the half step's: the face stress extrapolated there.
  const double h_in = coupled_ ? 1.5 * s_in - 0.5 * last_incident_ : s_in;
  const double h_tr = coupled_ ? 1.5 * s_tr - 0.5 * last_transmitted_ : s_tr;
  bl.vx[top] = bl.vx[bottom] = bl.omega[top] = bl.omega[bottom] = 0.0;
  bl.vy[top] = -incident_.face_velocity(mid, h_in);
  bl.vy[bottom] = transmitted_.face_velocity(mid, h_tr);
  last_incident_ = s_in;
  last_transmitted_ = s_tr;
  coupled_ = true;
}

void ShpbDriver::record_block_bars() {
  const auto& bl = model_.blocks;
  const double t = face_time();
  for (BlockGauge& g : gauges_) {
    const double u_near = bl.y[g.near] - bl.y0[g.near], u_far = bl.y[g.far] - bl.y0[g.far];
    g.stress.add(t, g.youngs_modulus * g.sign * (u_near - u_far) / cfg_.bar_block_length);
  }
  // The contact forces are those of the step's start.
  const double t0 = t - solver_.dt();
  const auto top = static_cast<std::size_t>(boundary_.top_platen());
  const auto bottom = static_cast<std::size_t>(boundary_.bottom_platen());
  incident_face_.add(t0, solver_.contact_force_from(top, Group::specimen).y / cfg_.incident.width);
  transmitted_face_.add(
      t0, -solver_.contact_force_from(bottom, Group::specimen).y / cfg_.transmitted.width);
  bars_.recorded_until = t0;
}

RunView ShpbDriver::view() const {
  const double v = -model_.blocks.vy[static_cast<std::size_t>(boundary_.top_platen())];
  return {model_, solver_, specimen_, state_, v, 0, &bars_};
}

void ShpbDriver::advance(Observers& observers) {
  try {
    if (phase_ == Phase::start) {
      observers.sample(view(), {"impact:start", true, false});
      phase_ = Phase::stepping;
    } else if (phase_ == Phase::stepping) {
      step(observers);
    }
  } catch (const solver::InstabilityError& e) {
    mark_unstable(outcome_, e.what());
    good_.restore(model_);
    observers.sample(view(), {"unstable", false, true});
    phase_ = Phase::done;
  }
}

void ShpbDriver::step(Observers& observers) {
  // Recorded bars run on until the waves of the test's end have reached the gauges.
  if (face_time() >= cfg_.duration + bars_.reach) return finish(observers, "impact:end");
  if (limit_.reached(solver_.steps(), outcome_)) return finish(observers, "impact:stopped");
  for (auto* end : {&incident_end_, &transmitted_end_})
    if (*end) {
      (*end)->clear_loads(model_);
      (*end)->apply(model_, solver_.time());
    }
  solver_.step();
  if (cfg_.block_bars) record_block_bars();
  state_ = measure::measure_specimen(model_, boundary_, solver_);
  good_.check(solver_, model_);
  track_extremes(outcome_, state_.axial_stress);
  const Due d = due(solver_.steps(), history_steps_, vtk_steps_);
  if (d.row || d.frame) observers.sample(view(), {"impact", d.row, d.frame});
}

void ShpbDriver::finish(Observers& observers, const std::string& label) {
  observers.sample(view(), {label, true, true});
  phase_ = Phase::done;
}

ProgressReport ShpbDriver::progress() const {
  ProgressReport r;
  r.stage_name = "impact";
  r.steps = solver_.steps();
  r.stress = state_.axial_stress;
  r.fraction = std::clamp(solver_.time() / (shift_ + cfg_.duration), 0.0, 1.0);
  return r;
}

template <class Archive>
void ShpbDriver::state(Archive& ar) {
  using checkpoint::pod;
  int phase = static_cast<int>(phase_);
  ar(phase, last_incident_, last_transmitted_, coupled_, checkpoint::bytes(state_), good_,
     bars_.recorded_until);
  std::vector<loading::WaveHistory*> records{
      &incident_.face_history(), &transmitted_.face_history(), &incident_face_, &transmitted_face_};
  for (BlockGauge& g : gauges_) records.push_back(&g.stress);
  for (loading::WaveHistory* h : records) ar(pod(h->times()), pod(h->values()));
  ar(outcome_.exit_code, outcome_.status, outcome_.peak, outcome_.trough);
  phase_ = static_cast<Phase>(phase);
}

void ShpbDriver::save(checkpoint::OutArchive& ar) const {
  const_cast<ShpbDriver*>(this)->state(ar);  // saving only reads
}

void ShpbDriver::load(checkpoint::InArchive& ar) {
  state(ar);
}

}  // namespace vorodec::run
