#pragma once
// The split Hopkinson pressure bar test (docs/theory.md §16.2), with either bar representation:
// - exact 1D elastic bars (loading/pressure_bar.hpp) whose faces are the platens: in every step
//   the solver's face control reads the specimen's force on each platen, records it as the bar
//   face's stress, and gives the platen the face's velocity for the step. Time 0 is the incident
//   pulse's arrival at the specimen; the bars' earlier history is known exactly.
// - bars built from blocks (model/build.hpp BlockBars, the platens their first blocks): the
//   striker's pulse enters through the incident bar's far end (a quiet boundary with an input),
//   the transmitted bar's far end is quiet where asked, and the gauges record the strain of the
//   joint nearest them. The run starts at the impact; its outputs are shifted by incident length /
//   c0 to the same time 0.
// The test runs for [shpb] duration after time 0.
#include <optional>

#include "driver_steps.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/driver.hpp"
#include "vorodec/engine/good_state.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/input/toml_section.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/pressure_bar.hpp"
#include "vorodec/loading/quiet_boundary.hpp"

namespace vorodec::run {

class ShpbDriver final : public Driver {
 public:
  // The model-file keys: [shpb] with its [shpb.incident_bar] and [shpb.transmitted_bar]
  // (docs/model-file.md).
  static std::shared_ptr<const loading::ExtensionSettings> read_table(io::TomlSection& sec,
                                                                      io::TomlSection& top,
                                                                      const io::ModelConfig& cfg);
  static constexpr io::DriverKeys keys{"shpb", read_table};

  explicit ShpbDriver(const DriverContext& c);
  ~ShpbDriver() override { solver_.set_face_control({}); }
  ShpbDriver(const ShpbDriver&) = delete;
  ShpbDriver& operator=(const ShpbDriver&) = delete;

  void advance(Observers& observers) override;
  bool finished() const override { return phase_ == Phase::done; }
  bool resumable() const override { return phase_ == Phase::stepping; }
  RunView view() const override;
  ProgressReport progress() const override;
  const DriverOutcome& outcome() const override { return outcome_; }
  // The bars' own section is the outputs' analysis of their record (outputs/shpb_output).
  void summarise(io::Json&) const override {}
  void save(checkpoint::OutArchive& ar) const override;
  void load(checkpoint::InArchive& ar) override;

 private:
  enum class Phase : int { start, stepping, done };
  // A block bar's gauge: the joint between blocks near and far (from the face), its record.
  struct BlockGauge {
    double x;  // m from the face
    std::uint32_t near, far;
    double sign;  // +1 incident bar (above the specimen), -1 transmitted bar
    double youngs_modulus;
    loading::WaveHistory stress;
  };
  template <class Archive>
  void state(Archive& ar);
  void step(Observers& observers);
  void finish(Observers& observers, const std::string& label);
  void couple();  // exact bars: the solver's face control
  void set_up_block_bars();
  void record_block_bars();  // after a step
  double face_time() const { return solver_.time() - shift_; }

  const loading::ShpbConfig& cfg_;
  model::Model& model_;
  solver::Solver& solver_;
  const loading::SpecimenBoundary& boundary_;
  const geometry::Tessellation& specimen_;
  StepLimit limit_;
  long history_steps_, vtk_steps_;
  double shift_ = 0;  // s, solver time of the pulse's arrival (block bars)

  loading::ElasticBar incident_, transmitted_;
  // Block bars: gauges (incident, then transmitted), the faces' stresses, the quiet far ends.
  std::vector<BlockGauge> gauges_;
  loading::WaveHistory incident_face_, transmitted_face_;
  std::optional<loading::QuietBoundary> incident_end_, transmitted_end_;
  BarsView bars_;
  // Exact bars: each face's stress in the last step (the half-step extrapolation's).
  double last_incident_ = 0, last_transmitted_ = 0;
  bool coupled_ = false;  // a step has been coupled (the last stresses are set)
  Phase phase_ = Phase::start;
  measure::SpecimenState state_;
  GoodState good_;
  DriverOutcome outcome_;
};

}  // namespace vorodec::run
