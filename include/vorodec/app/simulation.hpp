#pragma once
// Wires a model file to a run: specimen -> model -> solver loop over the load path -> outputs.
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/measure/cycles.hpp"
#include "vorodec/measure/failure_stages.hpp"
#include "vorodec/model/model.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::app {

// The specimen of a model file: tessellated, or loaded from a prepared specimen file.
geometry::Tessellation make_specimen(const io::ModelConfig& cfg);

// A model ready to step: blocks, platens and initial contacts detected.
struct PreparedModel {
  std::unique_ptr<model::Model> model;
  std::unique_ptr<solver::Solver> solver;
};
PreparedModel prepare_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen);

struct RunOptions {
  std::filesystem::path out;  // results folder
  long max_steps = 0;         // > 0: stop after this many steps (short mode)
  bool write_vtk = true;
  bool progress = true;  // progress bar (terminal) or progress lines
  // > 0: at the first step from this one where the run can resume, write a checkpoint and stop
  // (exit code kStoppedForResume), as SIGINT or SIGTERM do.
  long stop_at_step = 0;
};

// Exit code of a run stopped with a checkpoint written (signal or --stop-at-step):
// `vorodec resume DIR` continues it.
inline constexpr int kStoppedForResume = 6;
// The checkpoint file in a results folder.
inline constexpr const char* kCheckpointFile = "checkpoint.vck";

// What the implicit elastic start of the first stage did (stage key implicit_start).
struct ImplicitStart {
  double reach = 0;  // m, platen displacement at the first contact's elastic limit (first solve)
  double displacement = 0;  // m, platen displacement of the jump
  double stress = 0;        // Pa, axial stress of the linear response after the jump
  double modulus = 0;       // Pa, Young's modulus of the linear response (plane-strain apparent)
  double time = 0;          // s, stage time at which the platen program reaches the displacement
  std::size_t dofs = 0, active_contacts = 0;
  int solves = 0;    // solve steps: the increments plus one per closing
  int closings = 0;  // steps cut short where an open contact closed
  int passes = 0;    // factorisations (a solve refactorises when it drops a pulled contact)
  double solve_seconds = 0;
  std::string limit;  // what ends the elastic regime, or which end condition capped the jump
  template <class Archive>
  void serialize(Archive& ar) {
    ar(reach, displacement, stress, modulus, time, dofs, active_contacts, solves, closings, passes,
       solve_seconds, limit);
  }
};

// What a creep stage did (summary.json).
struct CreepStageReport {
  double max_time_step = 0, min_time_step = 0;  // s, the creep step's range in the stage
  double max_energy_ratio = 0;                  // -, largest kinetic / contact strain energy
  long steps = 0;
  double failure_onset = std::numeric_limits<double>::quiet_NaN();  // s in the stage
  double collapse = std::numeric_limits<double>::quiet_NaN();       // s in the stage
};

// What a corrosion stage did (summary.json).
struct CorrosionStageReport {
  double time = 0;  // s, corrosion time reached
  // s, corrosion time of the last equilibrium before the specimen collapsed (NaN: it did not)
  double failure_time = std::numeric_limits<double>::quiet_NaN();
  double first_strain = 0, last_strain = 0;  // -, axial strain at the first and last equilibrium
  double min_step = 0, max_step = 0;         // s, the corrosion step's range
  long corrosion_steps = 0;
  long mechanical_steps = 0;  // solver steps in the stage (equilibria included)
  long broken_transgranular = 0, broken_intergranular = 0;  // bonds broken by corrosion
  long active_bonds = 0, active_contacts = 0;               // corroding at the last corrosion step
};

struct RunSummary {
  // 0 finished, 3 stopped unstable, 4 step limit of the model file reached, kStoppedForResume
  int exit_code = 0;
  std::string status;
  double peak_stress = 0;       // Pa
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
  std::optional<ImplicitStart> implicit_start;
  // Creep stages: (stage index, what it did), in stage order.
  std::vector<std::pair<std::size_t, CreepStageReport>> creep;
  std::vector<std::pair<std::size_t, CorrosionStageReport>> corrosion;
};

// Runs the load path. `overrides` are those cfg was read with (a checkpoint records them).
RunSummary run_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen,
                     const RunOptions& options, const std::vector<io::Override>& overrides = {});

// Continues the run whose checkpoint is in `dir`, with the options it was started with but for
// stop_at_step and progress. Throws checkpoint::CheckpointError (no, foreign, truncated or corrupt
// checkpoint) and io::ModelFileError (the model file changed since).
RunSummary resume_run(const std::filesystem::path& dir, long stop_at_step, bool progress);

// SIGINT and SIGTERM then stop a run at its next step with a checkpoint (kStoppedForResume); a
// second one ends it at once. Runs install this when their stepping starts.
void stop_on_signals();

// The initial contacts of a model with their sampled properties, as text (for `vorodec build`).
std::string describe_contacts(const io::ModelConfig& cfg, const geometry::Tessellation& specimen);

}  // namespace vorodec::app
