#pragma once
// A load path: confinement plus a list of stages, each with its control and end condition.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace vorodec::loading {

// platen_velocity: strain control. axial_stress: a servo holds target_stress (creep stages).
// stress_rate: a servo moves the target from the stage's start stress at stress_rate (Pa/s).
enum class Control { platen_velocity, axial_stress, stress_rate };

struct StageEnd {
  static constexpr double unset = std::numeric_limits<double>::quiet_NaN();
  double axial_strain = unset;        // ends when the axial strain reaches this (-)
  double post_peak_fraction = unset;  // ends when stress falls below this fraction of the peak
  double duration = unset;            // s, ends after this much time in the stage
  double stress = unset;              // Pa, axial-stress stages: ends when the target is held
  double axial_stress = unset;        // Pa, ends when the stress crosses this (either direction)
};

// Adaptive platen speed of a velocity stage, driven by the unbalanced-force ratio (Solver::
// unbalanced_force_ratio): every interval_steps the speed is multiplied by
// sqrt(target_ratio / ratio), bounded to [1/max_change, max_change], and kept in
// [min_velocity, max_velocity]. Below the target (near equilibrium) it speeds up, above it slows.
struct AdaptiveVelocity {
  bool enabled = false;
  double target_ratio = 0.0;  // -, the ratio the controller steers to
  double min_velocity = 0.0;  // m/s
  double max_velocity = 0.0;  // m/s
  long interval_steps = 500;  // steps between control updates (>= the fundamental period)
  double max_change = 1.25;   // -, largest factor of one update
};

// A creep stage (an axial_stress stage that holds sigma1 - sigma3): the mechanical step is the
// creep step, with density scaling sized to it (PFC's and UDEC's creep modes), and the run
// watches for creep failure.
struct CreepSettings {
  bool enabled = false;
  // -, the largest creep step as a fraction of the contacts' shortest relaxation time (Ck/Kk or
  // Cm/Km); time_step > 0 (s) gives it directly instead.
  double step_factor = 1e-3;
  double time_step = 0.0;
  // The step shrinks (x 0.7) while the unbalanced-force ratio is above target_ratio, and grows
  // back (x 1.2, up to the largest) while it is below a third of it; checked every interval_steps.
  double target_ratio = 1e-3;
  long interval_steps = 100;
};

// A corrosion stage (static fatigue, docs/theory.md §14.4): an axial-stress servo holds
// sigma1 = sigma3 + rs (sf - sigma3); at each equilibrium the stress-corrosion layers advance the
// corrosion clock by one step (app/corrosion_control).
struct CorrosionSettings {
  bool enabled = false;
  double driving_stress_ratio = 0.0;  // -, rs in (0, 1)
  double peak_stress = 0.0;           // Pa, sf: short-term peak axial stress at this confinement
  // n_c: the first corrosion step is the shortest estimated time to failure / n_c; after n_c
  // steps without a break the step doubles; a break starts again from an estimate ([Potyondy2007]).
  double steps_per_failure = 4.0;
  // Time to failure and degradation over a step with each bond's forces held: integrated exactly
  // (laws::held_time), or with the rate frozen at its start ([Potyondy2007]'s estimate,
  // frozen_rate).
  bool frozen_rate = false;
  double equilibrium_ratio = 1e-4;      // -, unbalanced-force ratio of an equilibrium
  long check_interval = 50;             // steps between equilibrium checks
  long max_equilibrium_steps = 100000;  // more without equilibrium: the specimen collapsed
  double max_time = std::numeric_limits<double>::infinity();  // s of corrosion time, then stop
};

// Which branch of a loading cycle a stage is (cycle measures pair them up).
enum class CyclePhase { none, loading, unloading };

struct Stage {
  std::string name;
  Control control = Control::platen_velocity;
  double platen_velocity = 0.0;  // m/s, top platen, positive = compressing (bottom platen fixed);
                                 // servo stages: the servo's speed cap
  double target_stress = 0.0;    // Pa, axial stress for Control::axial_stress (compression +)
  double stress_rate = 0.0;      // Pa/s for Control::stress_rate (negative = unloading)
  double ramp_time = 0.0;        // s, velocity ramps linearly from the previous stage's over this
  AdaptiveVelocity adaptive;     // velocity stages: platen_velocity is then the starting speed
  // First velocity stage only: begin with the implicit elastic start (app/implicit_start), a
  // jump to this fraction of the platen displacement at which the first contact leaves its
  // elastic regime.
  bool implicit_start = false;
  double implicit_start_fraction = 0.9;  // -, in (0, 1]
  int implicit_start_increments = 10;    // solves, each from the geometry the last one reached
  CreepSettings creep;
  CorrosionSettings corrosion;
  StageEnd end;
  int cycle = 0;  // 1, 2, ... for stages generated by a cyclic block; 0 otherwise
  CyclePhase phase = CyclePhase::none;
  // Stages of a cyclic block: index of the first stage after the block. A loading stage that passes
  // a peak below its end.axial_stress (the specimen can no longer reach its target) still unloads,
  // then the run resumes there.
  int block_end = -1;
};

// Variable-amplitude cyclic loading (the marble study): load under platen-velocity control to each
// upper limit, unload under stress-rate control to the lower limit.
struct CyclicBlock {
  std::string name = "cycle";
  std::vector<double> upper_stresses;  // Pa, one per cycle
  double lower_stress = 0.0;           // Pa
  double loading_velocity = 0.0;       // m/s
  double unloading_rate = 0.0;         // Pa/s, positive
  double ramp_time = 0.0;              // s, of each loading
  double servo_velocity_cap = 0.05;    // m/s, of the unloading servo
};

// Appends the 2 x n stages of a cyclic block.
void append_cycles(const CyclicBlock& block, std::vector<Stage>& stages);

struct LoadPath {
  double confining_stress = 0.0;  // Pa, traction on the lateral boundary (compression +)
  std::vector<Stage> stages;
};

}  // namespace vorodec::loading
