#pragma once
// The corrosion mode (stages with control = "corrosion", constants in [corrosion]). A corrosion
// stage's time advancement (docs/theory.md §14.4; [Potyondy2007]'s psc.fis, [Liu2020] Fig. 9). At
// each equilibrium under the held stress: every corroding bond's time to failure, forces held; one
// corrosion step for all; the degraded bonds. A specimen that finds no equilibrium within
// max_equilibrium_steps has collapsed: the corrosion time of its last equilibrium is its failure
// time.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "stage_mode.hpp"
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/input/toml_section.hpp"
#include "vorodec/laws/stress_corrosion.hpp"
#include "vorodec/measure/specimen.hpp"

namespace vorodec::run {

// [corrosion]: the stress-corrosion layers of a grain-based specimen (docs/theory.md §14;
// [Liu2020]).
struct CorrosionConfig final : loading::ExtensionSettings {
  laws::DrivingRate rate;        // beta1(rs): m/s for bonded lengths
  double beta3_per_beta1 = 1.0;  // 1/m: beta3 (1/s, strength factors) = this x beta1
  bool transgranular = true;     // bonded-length reduction inside grains
  bool intergranular = true;     // strength degradation on grain boundaries
  laws::BondedLength bonded;
  laws::StrengthDegradation degradation;
};

// A corrosion stage (static fatigue, docs/theory.md §14.4): an axial-stress servo holds
// sigma1 = sigma3 + rs (sf - sigma3); at each equilibrium the stress-corrosion layers advance the
// corrosion clock by one step.
struct CorrosionSettings final : loading::ExtensionSettings {
  double driving_stress_ratio = 0.0;  // -, rs in (0, 1)
  double peak_stress = 0.0;           // Pa, sf: short-term peak axial stress at this confinement
  // n_c: the first corrosion step is the shortest estimated time to failure / n_c; after n_c
  // steps without a break the step doubles; a break starts again from an estimate ([Potyondy2007]).
  double steps_per_failure = 4.0;
  // Time to failure and degradation over a step with each bond's forces held: integrated exactly
  // (laws::held_time), or with the rate frozen at its start ([Potyondy2007]'s estimate,
  // frozen_rate).
  bool frozen_rate = false;
  double equilibrium_ratio = 1e-4;  // -, unbalanced-force ratio of an equilibrium
  long check_interval = 10;         // steps between equilibrium checks (half of B3's end by one)
  // More without equilibrium: the specimen collapsed; every step past it is spent on a specimen
  // already failed. In B3 every relaxation past 5,000 steps came within 0.03 orders of magnitude
  // of the failure time (docs/time-dependent.md, "Collapse").
  long max_equilibrium_steps = 20000;
  double max_time = std::numeric_limits<double>::infinity();  // s of corrosion time, then stop
};

inline const CorrosionSettings& corrosion_settings(const loading::Stage& stage) {
  return static_cast<const CorrosionSettings&>(*stage.mode_settings);
}

// What a corrosion stage did (summary.json).
struct CorrosionStageReport {
  double time = 0;  // s, corrosion time reached
  // s, corrosion time of the last equilibrium before the specimen collapsed (NaN: it did not)
  double failure_time = std::numeric_limits<double>::quiet_NaN();
  double first_strain = 0, last_strain = 0;  // -, axial strain at the first and last equilibrium
  double min_step = 0, max_step = 0;         // s, the corrosion step's range
  long corrosion_steps = 0;
  long mechanical_steps = 0;  // solver steps in the stage (equilibria included)
  // The most solver steps to an equilibrium (after a corrosion step, or from when the target
  // was first held): how far below max_equilibrium_steps the relaxations stay until collapse.
  long longest_relaxation = 0;
  long broken_transgranular = 0, broken_intergranular = 0;  // bonds broken by corrosion
  long active_bonds = 0, active_contacts = 0;               // corroding at the last corrosion step
};

// The corrosion step ([Potyondy2007]): the shortest estimated time to failure / n_c at first,
// doubled after n_c steps without a break, estimated afresh after one; never past the next
// estimated failure, so the bond that fails first fails at its estimated time.
class CorrosionClock {
 public:
  explicit CorrosionClock(double n_c) : n_c_(n_c) {}
  double next(double shortest);  // s, the step, given the shortest time to failure (s)
  void after(bool broke);        // after the step and its equilibrium: did a bond break?
  template <class Archive>
  void serialize(Archive& ar) {
    ar(n_c_, dt_, quiet_);
  }

 private:
  double n_c_, dt_ = 0.0;
  long quiet_ = 0;
};

class CorrosionControl {
 public:
  enum class Next { step, corroded, collapsed, no_corrosion, time_up };
  // Starts the stage: the corroding bonds of the specimen as they are now.
  CorrosionControl(const loading::Stage& stage, const CorrosionConfig& config,
                   const model::Model& model, const solver::Solver& solver,
                   std::span<const std::int32_t> block_grain);
  // A control whose state a checkpoint then loads.
  CorrosionControl(const loading::Stage& stage, const CorrosionConfig& config)
      : stage_(stage), config_(config), clock_(corrosion_settings(stage).steps_per_failure) {}
  // After each solver step of the stage: at an equilibrium, one corrosion step (corroded).
  Next after_step(solver::Solver& solver, model::Model& model, const measure::SpecimenState& s);
  double time() const { return report_.time; }
  const CorrosionStageReport& report() const { return report_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(checkpoint::pod(bonds_), checkpoint::pod(joints_), inter_begin_, clock_, since_equilibrium_,
       held_at_, loading_peak_, cracks_seen_, broke_, started_, checkpoint::bytes(report_));
  }

 private:
  struct Bond {  // a corroding contact as the stage found it
    std::uint64_t id;
    double kn0, ks0, tension0, cohesion0;  // N/m, N/m, N, N
    double tan_phi;
    double lambda;  // grain boundaries: strength factor
  };
  struct Joint {  // a sub-block joint: bonds_[first, first + count)
    std::uint32_t first, count;
    double d0, d;  // m, bonded length at the start and now
    std::uint8_t done;
  };
  bool corrode(solver::Solver& solver, model::Model& model);  // one step; true if a bond broke
  // corrode()'s steps, in order, on the step's working state (corrosion_mode.cpp).
  struct Step;
  void assess_joints(Step& s);    // each joint's state now and its time to failure
  void assess_contacts(Step& s);  // each grain-boundary contact's
  void break_failed(Step& s);     // those already past their strength break
  double advance_clock(double shortest, solver::Solver& solver);  // s, the step taken
  void shorten_joints(Step& s, double dt);
  void weaken_contacts(Step& s, double dt);
  void break_contacts(Step& s, const std::vector<std::size_t>& list, bool tension, long& n);

  const loading::Stage& stage_;
  const CorrosionConfig& config_;
  std::vector<Bond> bonds_;  // joints' bonds first, grain-boundary contacts from inter_begin_
  std::vector<Joint> joints_;
  std::size_t inter_begin_ = 0;
  CorrosionClock clock_;
  long since_equilibrium_ = 0;  // solver steps since the last equilibrium
  long held_at_ = -1;           // loading: steps since the target was first held (-1: not yet)
  double loading_peak_ = 0;     // Pa, the highest stress while loading
  std::size_t cracks_seen_ = 0;
  bool broke_ = false;    // the last corrosion step broke a bond
  bool started_ = false;  // the first equilibrium (at the held stress) was reached
  CorrosionStageReport report_;
};

class CorrosionMode final : public StageMode {
 public:
  // The model-file keys: the [corrosion] table and a corrosion stage's (docs/model-file.md).
  static std::shared_ptr<const loading::ExtensionSettings> read_table(io::TomlSection& sec,
                                                                      io::TomlSection& top,
                                                                      const io::ModelConfig& cfg);
  static std::shared_ptr<const loading::ExtensionSettings> read_stage(io::TomlSection& sec,
                                                                      loading::Stage& st,
                                                                      const io::ModelConfig& cfg);
  static constexpr io::StageModeKeys keys{"corrosion", "corrosion", read_table, read_stage};

  explicit CorrosionMode(const DriverContext& c)
      : cfg_(c.cfg),
        config_(static_cast<const CorrosionConfig*>(
            c.cfg.tables.count(keys.table) ? c.cfg.tables.at(keys.table).get() : nullptr)),
        model_(c.model),
        solver_(c.solver),
        specimen_(c.specimen) {}
  void begin_stage(const StageContext& c) override;
  ModeVerdict after_step(const StageContext& c, const measure::SpecimenState& s) override;
  std::string unstable(const StageContext& c, const std::string& what) override;
  void end_stage(const StageContext& c) override;
  bool progress(const StageContext& c, ProgressReport& r) const override;
  // The corrosion clock (s) and the strain energy the layers took from bonds (J/m).
  std::vector<std::string> column_names() const override {
    return {"corrosion_time", "corrosion_energy"};
  }
  void column_values(std::vector<double>& row) const override;
  void summarise(io::Json& summary) const override;
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar, const loading::Stage& current) override;

 private:
  const io::ModelConfig& cfg_;
  const CorrosionConfig* config_;  // the [corrosion] table (nullptr: none)
  model::Model& model_;
  solver::Solver& solver_;
  const geometry::Tessellation& specimen_;
  std::optional<CorrosionControl> control_;                            // in a corrosion stage
  std::vector<std::pair<std::size_t, CorrosionStageReport>> reports_;  // (stage index, report)
};

}  // namespace vorodec::run
