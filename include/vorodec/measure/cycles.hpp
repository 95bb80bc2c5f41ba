#pragma once
// Per-cycle measures of a cyclic load path from its history rows (the marble study, [Yu2023]):
// secant modulus, generalized Poisson's ratio, input / recovered / dissipated energy, residual
// strain.
#include <span>
#include <vector>

#include "vorodec/loading/load_path.hpp"

namespace vorodec::measure {

// One history row: specimen strains and stress, and the index of the stage it belongs to.
struct HistoryPoint {
  double axial_strain = 0, axial_stress = 0, lateral_strain = 0;
  int stage = 0;
};

struct CycleMeasures {
  int cycle = 0;
  double upper_target = 0;      // Pa, the cycle's upper limit
  double upper_reached = 0;     // Pa, highest stress of its loading
  bool stalled = false;         // loading peaked below its target
  double secant_modulus = 0;    // Pa, (stress rise) / (strain rise) over the loading
  double poisson_ratio = 0;     // generalized: -(lateral strain rise) / (axial strain rise)
  double input_work = 0;        // J/m^3, area under the loading curve (W_tol)
  double recovered_work = 0;    // J/m^3, area under the unloading curve (W_e)
  double dissipated_work = 0;   // J/m^3, W_dis = W_tol - W_e
  double dissipated_total = 0;  // J/m^3, sum of W_dis up to this cycle
  double residual_strain = 0;   // axial strain at the end of the unloading
};

// stalled[s]: stage s ended because it could not reach its target.
std::vector<CycleMeasures> cycle_measures(std::span<const HistoryPoint> rows,
                                          std::span<const loading::Stage> stages,
                                          const std::vector<bool>& stalled);

// Area under a stress-strain path by the trapezoid rule (J/m^3).
double work_along(std::span<const HistoryPoint> rows);

}  // namespace vorodec::measure
