// R4: a jointed rock mass started under its in-situ stress (docs/theory.md §6.7) must carry that
// stress: the forces through horizontal and vertical cuts, summed from the contacts that straddle
// them, against the field, after the model has held it for 1,000 steps.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>

#include "cases.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::verification {

namespace {

// N per m: the force on the blocks whose centroids lie on the `above` side of a cut from the
// blocks on the other side (the contacts that straddle it).
model::Point cut_force(model::Model& m, const std::function<bool(std::size_t)>& above) {
  model::Point f{0, 0};
  const auto& bl = m.blocks;
  for (model::Contact c : m.contacts) {
    const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
    if (bl.group[a] != model::Group::specimen || bl.group[b] != model::Group::specimen) continue;
    if (above(a) == above(b)) continue;
    const model::ContactFrame fr = model::contact_frame(bl.corners(), c);
    const model::Point on_a = c.fn * fr.n + (fr.gain * c.fs) * model::Point{-fr.n.y, fr.n.x};
    f = above(a) ? f + on_a : f - on_a;
  }
  return f;
}

}  // namespace

std::vector<CaseResult> r4_in_situ_start(const std::string& source_dir) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path file =
      std::filesystem::path(source_dir) / "models" / "tunnel_jointed.toml";
  const io::ModelConfig cfg = run::read_model_file(file);
  run::PreparedModel p = run::prepare_model(cfg, run::make_specimen(cfg));
  model::Model& m = *p.model;
  const loading::SpecimenBoundary boundary(m);
  const loading::InSituStress field = loading::resolved(*cfg.in_situ, m);
  const int steps = 1000;
  for (int k = 0; k < steps; ++k) {  // the platens held, the field's traction on the sides
    boundary.apply_stress(m, field);
    p.solver->step();
  }
  model::refresh_world(m);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double W = boundary.width(), H = boundary.height(), top = field.datum_y;
  const auto& bl = m.blocks;
  double yy_error = 0, yy_expected = 0, yy_measured = 0;
  for (const double depth : {2.0, 4.0, 6.0, 8.0}) {
    const double y = top - depth;
    const double measured = cut_force(m, [&](std::size_t b) { return bl.y[b] > y; }).y / W;
    const double expected = field.at(y).yy;
    if (std::abs(measured - expected) / expected >= yy_error) {
      yy_error = std::abs(measured - expected) / expected;
      yy_expected = expected;
      yy_measured = measured;
    }
  }
  // A vertical cut carries the horizontal stress averaged over the height.
  const double xx_expected = field.at(top - 0.5 * H).xx;
  double xx_error = 0, xx_measured = 0;
  for (const double x : {2.5, 5.0, 7.5}) {
    const double measured = -cut_force(m, [&](std::size_t b) { return bl.x[b] < x; }).x / H;
    if (std::abs(measured - xx_expected) / xx_expected >= xx_error) {
      xx_error = std::abs(measured - xx_expected) / xx_expected;
      xx_measured = measured;
    }
  }
  double moved = 0;
  for (std::size_t b = 0; b < bl.size(); ++b)
    moved = std::max(moved, std::hypot(bl.x[b] - bl.x0[b], bl.y[b] - bl.y0[b]));
  const std::string settings = fmt::format(
      "models/tunnel_jointed.toml ([in_situ] 5 / 10 MPa at the top, rho g with depth, gravity), "
      "{} steps with the platens held; unbalanced-force ratio then {:.2g}, largest block "
      "displacement {:.2g} m",
      steps, p.solver->unbalanced_force_ratio(), moved);
  CaseResult yy{"R4",
                "in-situ start: sigma_yy through horizontal cuts at 2, 4, 6, 8 m depth (worst)",
                "the field: 10 MPa + 26.5 kPa/m x depth",
                yy_expected,
                yy_measured,
                yy_error,
                0.01,
                settings,
                seconds};
  CaseResult xx{"R4",
                "in-situ start: sigma_xx through vertical cuts at x = 2.5, 5, 7.5 m (worst)",
                "the field's mean over the height: 5 MPa + 13.2 kPa/m x depth",
                xx_expected,
                xx_measured,
                xx_error,
                0.01,
                settings,
                seconds};
  return {yy, xx};
}

}  // namespace vorodec::verification
