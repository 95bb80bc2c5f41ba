#include "excavation_mode.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vorodec/io/json.hpp"
#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::run {

static_assert(sizeof(ExcavationReport) == 40, "ExcavationReport changed: it is saved as bytes");

namespace {

using geometry::Point;

double area2(const std::vector<Point>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return a;
}

bool in_polygon(const std::vector<Point>& poly, Point p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
        p.x < poly[j].x + (p.y - poly[j].y) * (poly[i].x - poly[j].x) / (poly[i].y - poly[j].y))
      in = !in;
  return in;
}

bool segments_cross(Point a, Point b, Point c, Point d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool overlap(const std::vector<Point>& p, const std::vector<Point>& q) {
  for (const Point v : p)
    if (in_polygon(q, v)) return true;
  for (const Point v : q)
    if (in_polygon(p, v)) return true;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j)
      if (segments_cross(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()])) return true;
  return false;
}

Point point_of(io::TomlSection& sec, const toml::node& n, std::string_view key) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
    sec.fail(key, "a point is [x, y] (m)");
  return {(*a)[0].value<double>().value(), (*a)[1].value<double>().value()};
}

}  // namespace

bool ExcavationSettings::inside(Point p) const {
  if (radius > 0) return dot(p - centre, p - centre) < radius * radius;
  return in_polygon(polygon, p);
}

std::vector<Point> ExcavationSettings::outline() const {
  if (radius <= 0) return polygon;
  std::vector<Point> p;
  for (int k = 0; k < 64; ++k) {
    const double t = 2 * std::numbers::pi * k / 64;
    p.push_back(centre + radius * Point{std::cos(t), std::sin(t)});
  }
  return p;
}

// control = "excavation": circle = { centre = [x, y], radius = r } or polygon = [[x, y], ...];
// the servo holds target_stress (the vertical in-situ stress) for end_time.
std::shared_ptr<const loading::ExtensionSettings> ExcavationMode::read_stage(
    io::TomlSection& sec, loading::Stage& st, const io::ModelConfig& cfg) {
  auto e = std::make_shared<ExcavationSettings>();
  st.control = loading::Control::axial_stress;
  st.target_stress = sec.positive("target_stress", laws::required);
  st.platen_velocity = sec.positive("platen_velocity", 0.05);
  st.end.duration = sec.positive("end_time", laws::required);  // s, after the blocks go
  const geometry::Point size =
      cfg.tessellation.outline.kind == geometry::OutlineKind::disc
          ? Point{cfg.tessellation.outline.diameter, cfg.tessellation.outline.diameter}
          : Point{cfg.tessellation.outline.width, cfg.tessellation.outline.height};
  const auto within = [&](Point p) { return p.x > 0 && p.x < size.x && p.y > 0 && p.y < size.y; };
  if (sec.has("circle") == sec.has("polygon"))
    sec.fail("circle", "give the opening as exactly one of 'circle' and 'polygon'");
  double extent = 0;
  if (sec.has("circle")) {
    const toml::node* n = sec.node("circle");
    if (!n->is_table()) sec.fail("circle", "must be { centre = [x, y], radius = r } (m)");
    io::TomlSection c(*n->as_table(), sec.key_path("circle"), sec.file());
    e->radius = c.positive("radius", laws::required);
    if (!c.has("centre")) c.fail("centre", "required: the opening's centre [x, y] (m)");
    e->centre = point_of(c, *c.node("centre"), "centre");
    c.finish();
    for (const Point p : e->outline())
      if (!within(p)) sec.fail("circle", "the opening must lie inside the specimen");
    extent = e->radius;
  } else {
    const toml::node* n = sec.node("polygon");
    const toml::array* a = n->as_array();
    if (!a || a->size() < 3) sec.fail("polygon", "must be [[x, y], ...] with at least 3 corners");
    for (const toml::node& p : *a) e->polygon.push_back(point_of(sec, p, "polygon"));
    if (area2(e->polygon) < 0) std::reverse(e->polygon.begin(), e->polygon.end());
    const std::size_t m = e->polygon.size();
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = i + 2; j < m; ++j)
        if (!(i == 0 && j == m - 1) && segments_cross(e->polygon[i], e->polygon[(i + 1) % m],
                                                      e->polygon[j], e->polygon[(j + 1) % m]))
          sec.fail("polygon", "the polygon crosses itself");
    for (const Point p : e->polygon)
      if (!within(p)) sec.fail("polygon", "the opening must lie inside the specimen");
    extent = std::sqrt(std::abs(area2(e->polygon)) / 2 / std::numbers::pi);
    for (const Point p : e->polygon) e->centre = e->centre + (1.0 / double(m)) * p;
  }
  e->fall_distance = sec.positive("fall_distance", 0.1 * extent);
  e->relaxation_time = sec.non_negative("relaxation_time", 0.0);
  if (e->relaxation_time > st.end.duration)
    sec.fail("relaxation_time", "must not exceed the stage's end_time");
  if (e->relaxation_time > 0 && cfg.deformable.enabled)
    sec.fail("relaxation_time",
             "a gradual release needs rigid blocks ([blocks] deformable = "
             "false): zoned lining blocks take loads at their gridpoints");
  for (const loading::Stage& earlier : cfg.load_path.stages)
    if (earlier.mode == keys.control &&
        overlap(excavation_settings(earlier).outline(), e->outline()))
      sec.fail(sec.has("circle") ? "circle" : "polygon",
               fmt::format("the opening overlaps stage '{}''s", earlier.name));
  return e;
}

void ExcavationMode::begin_stage(const StageContext& c) {
  const ExcavationSettings& e = excavation_settings(c.stage);
  auto& bl = model_.blocks;
  std::vector<std::uint32_t> removed;
  std::vector<std::uint8_t> gone(bl.size(), 0);
  for (std::uint32_t b = 0; b < bl.size(); ++b)
    if (bl.group[b] == model::Group::specimen && e.inside({bl.x[b], bl.y[b]})) {
      removed.push_back(b);
      gone[b] = 1;
    }
  // The lining: the blocks in contact with a removed one, before they go.
  std::vector<std::uint8_t> lines(bl.size(), 0);
  for (const model::Contact& k : model_.contacts) {
    const auto a = static_cast<std::size_t>(k.a), b = static_cast<std::size_t>(k.b);
    if (gone[a] && !gone[b] && bl.group[b] == model::Group::specimen) lines[b] = 1;
    if (gone[b] && !gone[a] && bl.group[a] == model::Group::specimen) lines[a] = 1;
  }
  // The removed blocks' last forces on the lining: each contact's force on its block a as the
  // last step applied it (fn n + gain fs s at the arm, from the world arrays of that step's
  // start), minus it on b.
  std::vector<std::array<double, 3>> load(e.relaxation_time > 0 ? bl.size() : 0);
  if (!load.empty())
    for (model::Contact k : model_.contacts) {
      const auto a = static_cast<std::size_t>(k.a), b = static_cast<std::size_t>(k.b);
      if (!(gone[b] && lines[a]) && !(gone[a] && lines[b])) continue;
      const model::ContactFrame f = model::contact_frame(bl, k);
      const Point force = k.fn * f.n + (f.gain * k.fs) * Point{-f.n.y, f.n.x};
      const std::size_t on = gone[b] ? a : b;
      const double sign = on == a ? 1.0 : -1.0;
      const Point arm = f.arm - Point{bl.kin[on].x, bl.kin[on].y};
      load[on] = {load[on][0] + sign * force.x, load[on][1] + sign * force.y,
                  load[on][2] + sign * cross(arm, force)};
    }
  solver_.remove_blocks(removed);
  lining_.clear();
  relaxation_load_.clear();
  for (std::uint32_t b = 0; b < bl.size(); ++b)
    if (lines[b]) {
      lining_.push_back(b);
      if (!load.empty()) relaxation_load_.push_back(load[b]);
    }
  start_time_ = solver_.time();
  relaxation_time_ = e.relaxation_time;
  apply_relaxation();
  at_ = measure::placement_of(bl);
  centre_ = e.centre;
  fall_distance_ = e.fall_distance;
  removed_total_ += static_cast<double>(removed.size());
  now_ = {};
  now_.removed = static_cast<double>(removed.size());
  now_.lining = static_cast<double>(lining_.size());
}

void ExcavationMode::measure() {
  const auto& bl = model_.blocks;
  double sum = 0, most = 0;
  for (const std::uint32_t b : lining_) {
    const Point r = Point{at_.x[b], at_.y[b]} - centre_;
    const double len = std::sqrt(dot(r, r));
    const double inward =
        len > 0 ? -dot(Point{bl.x[b] - at_.x[b], bl.y[b] - at_.y[b]}, r) / len : 0;
    sum += inward;
    most = std::max(most, inward);
  }
  now_.convergence = lining_.empty() ? 0 : sum / static_cast<double>(lining_.size());
  now_.max_convergence = most;
  double fallen = 0;
  for (std::size_t b = 0; b < bl.size(); ++b)
    if (bl.group[b] == model::Group::specimen &&
        std::hypot(bl.x[b] - at_.x[b], bl.y[b] - at_.y[b]) > fall_distance_)
      ++fallen;
  now_.fallen = fallen;
  joints_now_ = measure::joint_displacements(model_, at_, solver_.law_table().joint_set_law,
                                             cfg_.joint_sets.size());
}

// The lining's share of the removed blocks' forces, falling linearly to zero over the relaxation
// time (set, not added: nothing else loads an inner block).
void ExcavationMode::apply_relaxation() {
  if (relaxation_load_.empty()) return;
  auto& bl = model_.blocks;
  const double left =
      std::max(0.0, 1.0 - (solver_.time() - start_time_) / std::max(relaxation_time_, 1e-300));
  for (std::size_t i = 0; i < lining_.size(); ++i) {
    const std::uint32_t b = lining_[i];
    bl.fx[b] = left * relaxation_load_[i][0];
    bl.fy[b] = left * relaxation_load_[i][1];
    bl.moment[b] = left * relaxation_load_[i][2];
  }
  if (left == 0.0) relaxation_load_.clear();
}

ModeVerdict ExcavationMode::after_step(const StageContext&, const measure::SpecimenState&) {
  apply_relaxation();
  if (solver_.steps() % 100 == 0) measure();
  return {};
}

std::string ExcavationMode::unstable(const StageContext& c, const std::string&) {
  measure();
  reports_.emplace_back(c.index, now_);
  joint_reports_.insert(joint_reports_.end(), joints_now_.begin(), joints_now_.end());
  return "";
}

void ExcavationMode::end_stage(const StageContext& c) {
  measure();
  reports_.emplace_back(c.index, now_);
  joint_reports_.insert(joint_reports_.end(), joints_now_.begin(), joints_now_.end());
}

bool ExcavationMode::progress(const StageContext&, ProgressReport& r) const {
  r.clock = fmt::format("opening: {:.0f} blocks removed, convergence {:.3g} mm, {:.0f} fallen",
                        now_.removed, 1e3 * now_.convergence, now_.fallen);
  return false;
}

std::vector<std::string> ExcavationMode::column_names() const {
  std::vector<std::string> names{"excavated_blocks", "opening_convergence",
                                 "opening_max_convergence", "fallen_blocks"};
  for (const auto& set : cfg_.joint_sets) {
    names.push_back("joint_max_slip_" + set.name);
    names.push_back("joint_max_opening_" + set.name);
  }
  return names;
}

void ExcavationMode::column_values(std::vector<double>& row) const {
  row.insert(row.end(), {removed_total_, now_.convergence, now_.max_convergence, now_.fallen});
  for (std::size_t k = 0; k < cfg_.joint_sets.size(); ++k)
    row.insert(row.end(), {joints_now_[2 * k], joints_now_[2 * k + 1]});
}

void ExcavationMode::summarise(io::Json& summary) const {
  if (reports_.empty()) return;
  io::Json rows = io::Json::array();
  const std::size_t sets = cfg_.joint_sets.size();
  for (std::size_t n = 0; n < reports_.size(); ++n) {
    const auto& [i, r] = reports_[n];
    io::Json joints = io::Json::array();
    for (std::size_t k = 0; k < sets; ++k)
      joints.push_back({{"set", cfg_.joint_sets[k].name},
                        {"max_slip_m", io::rounded(joint_reports_[2 * (n * sets + k)], 6)},
                        {"max_opening_m", io::rounded(joint_reports_[2 * (n * sets + k) + 1], 6)}});
    rows.push_back({{"stage", cfg_.load_path.stages[i].name},
                    {"removed_blocks", r.removed},
                    {"lining_blocks", r.lining},
                    {"convergence_m", io::rounded(r.convergence, 6)},
                    {"max_convergence_m", io::rounded(r.max_convergence, 6)},
                    {"fallen_blocks", r.fallen},
                    {"joint_sets", std::move(joints)}});
  }
  summary["excavation_stages"] = std::move(rows);
}

void ExcavationMode::save(checkpoint::OutArchive& ar) const {
  ar(centre_.x, centre_.y, fall_distance_, removed_total_, checkpoint::bytes(now_),
     checkpoint::pod(lining_), checkpoint::pod(at_.x), checkpoint::pod(at_.y),
     checkpoint::pod(at_.theta), checkpoint::pod(relaxation_load_), start_time_, relaxation_time_,
     checkpoint::pod(joints_now_), checkpoint::pod(joint_reports_));
  save_stage_reports(ar, reports_);
}

void ExcavationMode::load(checkpoint::InArchive& ar, const loading::Stage&) {
  ar(centre_.x, centre_.y, fall_distance_, removed_total_, checkpoint::bytes(now_),
     checkpoint::pod(lining_), checkpoint::pod(at_.x), checkpoint::pod(at_.y),
     checkpoint::pod(at_.theta), checkpoint::pod(relaxation_load_), start_time_, relaxation_time_,
     checkpoint::pod(joints_now_), checkpoint::pod(joint_reports_));
  load_stage_reports(ar, reports_);
}

}  // namespace vorodec::run
