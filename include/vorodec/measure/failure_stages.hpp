#pragma once
// Stages I-IV of a monotonic loading (elastic, stable crack growth, accelerating crack growth,
// post-peak) from the contact failure rate, as the marble study ([Yu2023], Fig. 6) reads them.
#include <span>

namespace vorodec::measure {

struct FailureStages {
  bool valid = false;
  double crack_initiation_stress = 0;  // Pa, end of stage I: the first failed contact
  double accelerating_stress = 0;      // Pa, start of stage III
  double peak_stress = 0;              // Pa, start of stage IV
};

// Stage III starts where the failure rate's growth per unit strain, over a window of 1/20 of the
// pre-peak rows after initiation, first exceeds twice its mean since initiation.
FailureStages failure_stages(std::span<const double> axial_strain,
                             std::span<const double> axial_stress,
                             std::span<const double> failure_rate);

}  // namespace vorodec::measure
