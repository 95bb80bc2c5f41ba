#include "vorodec/outputs/ae_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "vorodec/io/atomic_file.hpp"
#include "vorodec/io/json.hpp"
#include "vorodec/io/vtk_writer.hpp"

namespace vorodec::run {

measure::AeSettings ae_settings(const io::ModelConfig& cfg, double mean_block_size,
                                double thickness) {
  measure::AeSettings s{cfg.output.ae_radius, cfg.output.ae_shear_wave_speed, thickness};
  if (s.radius <= 0.0) s.radius = 2.0 * mean_block_size;
  if (s.shear_wave_speed <= 0.0) {
    // A row of rigid blocks of size d on shear springs k per unit length: c = sqrt(k d / rho)
    // (the P wave's speed with the normal spring is verification case A9); a joints law without
    // a shear spring falls back on its normal one.
    const laws::NominalStiffness k =
        laws::find_law(cfg.joints.name)->nominal_stiffness(cfg.joints.params);
    const double stiffness = k.shear > 0.0 ? k.shear : k.normal;
    s.shear_wave_speed = stiffness > 0.0 && cfg.density > 0.0
                             ? std::sqrt(stiffness * mean_block_size / cfg.density)
                             : 1e3;
  }
  return s;
}

namespace {
const char* type_name(measure::AeType t) {
  return t == measure::AeType::tensile ? "tensile"
         : t == measure::AeType::shear ? "shear"
                                       : "mixed";
}
}  // namespace

void write_ae_events(std::span<const measure::AeEvent> events, const std::filesystem::path& out) {
  std::string csv = "time,duration,x,y,energy,magnitude,cracks,tensile_cracks,type\n";
  io::VtkPointSet set;
  std::vector<double> time, energy, magnitude, cracks, type;
  for (const measure::AeEvent& e : events) {
    csv += fmt::format("{:.9g},{:.6g},{:.9g},{:.9g},{:.6g},{:.6g},{},{},{}\n", e.time, e.duration,
                       e.x, e.y, e.energy, e.magnitude, e.cracks, e.tensile, type_name(e.type));
    set.points.push_back({e.x, e.y});
    time.push_back(e.time);
    energy.push_back(e.energy);
    magnitude.push_back(e.magnitude);
    cracks.push_back(static_cast<double>(e.cracks));
    type.push_back(static_cast<double>(e.type));
  }
  io::write_file_atomically(out / "ae_events.csv", csv);
  set.fields = {{"time", time},
                {"energy", energy},
                {"magnitude", magnitude},
                {"cracks", cracks},
                {"type", type}};  // 1 tensile, 2 shear, 3 mixed
  io::write_point_set(set, out / "ae_events.vtp");
}

io::Json ae_json(std::span<const measure::AeEvent> events, const measure::AeSettings& s) {
  const measure::BValue b = measure::b_value(events);
  double largest = -INFINITY;
  std::size_t tensile = 0, shear = 0;
  for (const measure::AeEvent& e : events) {
    largest = std::max(largest, e.magnitude);
    tensile += e.type == measure::AeType::tensile;
    shear += e.type == measure::AeType::shear;
  }
  return {{"events", events.size()},
          {"tensile_events", tensile},
          {"shear_events", shear},
          {"mixed_events", events.size() - tensile - shear},
          {"largest_magnitude", io::rounded(largest, 6)},
          {"b_value", io::rounded(b.b, 6)},
          {"b_value_error", io::rounded(b.error, 6)},
          {"completeness_magnitude", io::rounded(b.mc, 6)},
          {"events_above_completeness", b.events},
          {"radius_m", io::rounded(s.radius, 6)},
          {"shear_wave_speed_m_per_s", io::rounded(s.shear_wave_speed, 6)}};
}

}  // namespace vorodec::run
