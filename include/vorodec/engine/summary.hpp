#pragma once
// What a run reports at its end (summary.json): the measures, how the load path ended and what
// its stages did.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vorodec/measure/cycles.hpp"
#include "vorodec/measure/failure_stages.hpp"

namespace vorodec::run {

struct RunSummary {
  // 0 finished, 3 stopped unstable, 4 step limit of the model file reached, kStoppedForResume
  int exit_code = 0;
  std::string status;
  double peak_stress = 0;  // Pa, the highest axial stress of the loading sense
  // The stress fell at least 1 % below peak_stress after it: a peak, not where the run stopped.
  bool peak_passed = false;
  double tensile_strength = 0;  // Pa: Brazilian (disc specimens) or direct tension (largest pull)
  double youngs_modulus = 0, poisson_ratio = 0;
  double initial_poisson_ratio = 0;  // fit over 10-30 % of peak (the linear range)
  measure::FailureStages failure_stages;
  std::vector<measure::CycleMeasures> cycles;
  long steps = 0;
  double wall_seconds = 0;
  std::size_t blocks = 0, contacts = 0, cracks_tensile = 0, cracks_shear = 0;
  std::size_t zones = 0;  // of deformable blocks
  // Pa, zone-area-weighted mean stress of the specimen at the end (compression positive).
  double zone_stress_xx = 0, zone_stress_yy = 0, zone_stress_xy = 0;
};

}  // namespace vorodec::run
