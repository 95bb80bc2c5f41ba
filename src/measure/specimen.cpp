#include "vorodec/measure/specimen.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace vorodec::measure {

namespace {
double mean_dx(const model::Blocks& bl, const std::vector<std::uint32_t>& blocks) {
  if (blocks.empty()) return 0.0;
  double s = 0;
  for (std::uint32_t b : blocks) s += bl.x[b] - bl.x0[b];
  return s / static_cast<double>(blocks.size());
}

// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double den = n * sxx - sx * sx;
  return den != 0.0 ? (n * sxy - sx * sy) / den : 0.0;
}
}  // namespace

double platen_stress(double top_fy, double bottom_fy, const loading::SpecimenBoundary& boundary,
                     double thickness) {
  return (top_fy - bottom_fy) / (2.0 * boundary.width() * thickness);
}

SpecimenState measure_specimen(const model::Model& model, const loading::SpecimenBoundary& boundary,
                               const solver::Solver& solver) {
  const auto& bl = model.blocks;
  SpecimenState s;
  const int top = boundary.top_platen(), bot = boundary.bottom_platen();
  if (top >= 0 && bot >= 0) {
    const auto t = static_cast<std::size_t>(top), b = static_cast<std::size_t>(bot);
    s.axial_strain = ((bl.y[b] - bl.y0[b]) - (bl.y[t] - bl.y0[t])) / boundary.height();
    const auto force = [&](std::size_t p) {
      return boundary.platens_in_bars() ? solver.contact_force_from(p, model::Group::specimen).y
                                        : solver.contact_force(p).y;
    };
    s.axial_stress = platen_stress(force(t), force(b), boundary, model.thickness);
  }
  s.lateral_strain = -(mean_dx(bl, boundary.right_gauges()) - mean_dx(bl, boundary.left_gauges())) /
                     boundary.width();
  s.volumetric_strain = s.axial_strain + s.lateral_strain;
  return s;
}

ElasticConstants elastic_constants(std::span<const double> axial_strain,
                                   std::span<const double> axial_stress,
                                   std::span<const double> lateral_strain) {
  ElasticConstants e;
  if (axial_stress.empty()) return e;
  const auto peak_it = std::max_element(axial_stress.begin(), axial_stress.end());
  const double peak = *peak_it;
  const auto n_pre = static_cast<std::size_t>(peak_it - axial_stress.begin());
  // The pre-peak points between lo and hi times the peak: axial strain, stress, lateral strain.
  const auto band = [&](double lo, double hi) {
    std::array<std::vector<double>, 3> b;
    for (std::size_t i = 0; i < n_pre; ++i) {
      if (axial_stress[i] >= lo * peak && axial_stress[i] <= hi * peak) {
        b[0].push_back(axial_strain[i]);
        b[1].push_back(axial_stress[i]);
        b[2].push_back(lateral_strain[i]);
      }
    }
    return b;
  };
  const auto [ea, sa, el] = band(0.4, 0.6);
  if (ea.size() < 3 || peak <= 0) return e;
  e.youngs_modulus = slope(ea, sa);
  e.poisson_ratio = -slope(ea, el);
  if (const auto [ia, is, il] = band(0.1, 0.3); ia.size() >= 3)
    e.initial_poisson_ratio = -slope(ia, il);
  e.valid = e.youngs_modulus > 0;
  return e;
}

}  // namespace vorodec::measure
