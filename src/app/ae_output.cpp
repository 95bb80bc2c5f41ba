#include "ae_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "vorodec/io/atomic_file.hpp"
#include "vorodec/io/vtk_writer.hpp"

namespace vorodec::app {

measure::AeSettings ae_settings(const io::ModelConfig& cfg, double mean_block_size,
                                double thickness) {
  measure::AeSettings s{cfg.output.ae_radius, cfg.output.ae_shear_wave_speed, thickness};
  if (s.radius <= 0.0) s.radius = 2.0 * mean_block_size;
  if (s.shear_wave_speed <= 0.0) {
    // A row of rigid blocks of size d on springs jks per unit length: c = sqrt(jks d / rho)
    // (VERIFICATION A9 for the P wave); a joints law without jks falls back on jkn.
    const auto& p = cfg.joints.params;
    const auto k =
        p.find("jks") != p.end() && p.at("jks").mean() > 0.0 ? p.find("jks") : p.find("jkn");
    const double stiffness = k != p.end() ? k->second.mean() : 0.0;
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

std::string ae_json(std::span<const measure::AeEvent> events, const measure::AeSettings& s) {
  const measure::BValue b = measure::b_value(events);
  double largest = -INFINITY;
  std::size_t tensile = 0, shear = 0;
  for (const measure::AeEvent& e : events) {
    largest = std::max(largest, e.magnitude);
    tensile += e.type == measure::AeType::tensile;
    shear += e.type == measure::AeType::shear;
  }
  const auto number = [](double v) {
    return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("null");
  };
  return fmt::format(
      ",\n  \"acoustic_emission\": {{\"events\": {}, \"tensile_events\": {}, \"shear_events\": {}, "
      "\"mixed_events\": {}, \"largest_magnitude\": {}, \"b_value\": {}, \"b_value_error\": {}, "
      "\"completeness_magnitude\": {}, \"events_above_completeness\": {}, \"radius_m\": {:.6g}, "
      "\"shear_wave_speed_m_per_s\": {:.6g}}}",
      events.size(), tensile, shear, events.size() - tensile - shear, number(largest), number(b.b),
      number(b.error), number(b.mc), b.events, s.radius, s.shear_wave_speed);
}

}  // namespace vorodec::app
