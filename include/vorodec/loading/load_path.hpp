#pragma once
// A load path: confinement plus a list of stages, each with its control and end condition.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace vorodec::loading {

enum class Control { platen_velocity, axial_stress };

struct StageEnd {
  static constexpr double unset = std::numeric_limits<double>::quiet_NaN();
  double axial_strain = unset;        // ends when the axial strain reaches this (-)
  double post_peak_fraction = unset;  // ends when stress falls below this fraction of the peak
  double duration = unset;            // s, ends after this much time in the stage
  double stress = unset;              // Pa, axial-stress stages: ends when the target is held
};

struct Stage {
  std::string name;
  Control control = Control::platen_velocity;
  double platen_velocity = 0.0;  // m/s, top platen, positive = compressing (bottom platen fixed)
  double target_stress = 0.0;    // Pa, axial stress for Control::axial_stress (compression +)
  double ramp_time = 0.0;        // s, velocity ramps linearly from the previous stage's over this
  StageEnd end;
};

struct LoadPath {
  double confining_stress = 0.0;  // Pa, traction on the lateral boundary (compression +)
  std::vector<Stage> stages;
};

}  // namespace vorodec::loading
