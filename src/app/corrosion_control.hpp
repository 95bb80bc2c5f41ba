#pragma once
// A corrosion stage's time advancement (PHYSICS 13; POT07's psc.fis, paper 000 Fig. 9). At each
// equilibrium under the held stress: every corroding bond's time to failure, forces held; one
// corrosion step for all; the degraded bonds. A specimen that finds no equilibrium within
// max_equilibrium_steps has collapsed: the corrosion time of its last equilibrium is its failure
// time.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "vorodec/app/simulation.hpp"
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/measure/specimen.hpp"

namespace vorodec::app {

// The corrosion step (POT07): the shortest estimated time to failure / n_c at first, doubled
// after n_c steps without a break, estimated afresh after one; never past the next estimated
// failure, so the bond that fails first fails at its estimated time.
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
  CorrosionControl(const loading::Stage& stage, const io::CorrosionConfig& config,
                   const model::Model& model, const solver::Solver& solver,
                   std::span<const std::int32_t> block_grain);
  // A control whose state a checkpoint then loads.
  CorrosionControl(const loading::Stage& stage, const io::CorrosionConfig& config)
      : stage_(stage), config_(config), clock_(stage.corrosion.steps_per_failure) {}
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

  const loading::Stage& stage_;
  const io::CorrosionConfig& config_;
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

}  // namespace vorodec::app
