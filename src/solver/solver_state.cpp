// Solver::save and Solver::load: one field list for both directions (Solver::state).
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::solver {

// A member added to Solver is either state a checkpoint carries (save and load it in Solver::state)
// or comes again from the model file or the loaded state (say so there); then update these sizes.
// face_control_ is the driver's, set again when it is made; the work_* and block_work_ are scratch.
// The detector's law table (its joint pairs too) comes again from the model file. balance_ sets
// no result (any cut gives the same bits): a loaded run starts from equal parts.
static_assert(sizeof(Solver) == 1184, "Solver changed: see Solver::state");

template <class Archive>
void Solver::state(Archive& ar) {
  using checkpoint::bytes;
  using checkpoint::pod;
  ar(pod(law_begin_), pod(deformable_begin_), pod(zfx_), pod(zfy_), pod(forces_),
     pod(gather_begin_), pod(gather_), pod(sums_), pod(x_detect_), pod(y_detect_), pod(t_detect_),
     pod(cracks_), bytes(energy_));
  ar(dt_, critical_dt_, time_, fixed_step_warned_, steps_, last_detection_, initial_bonded_,
     detections_, settings_.time_step,  // creep stages change the density-scaling step
     crack_clock_);
  std::uint64_t next_id = detector_.next_id();
  ar(next_id);
  detector_.set_next_id(next_id);
}

void Solver::save(checkpoint::OutArchive& ar) const {
  const_cast<Solver*>(this)->state(ar);  // saving only reads
  for (const auto& law : laws_) law->save(ar);
}

void Solver::load(checkpoint::InArchive& ar) {
  state(ar);
  for (auto& law : laws_) law->load(ar);
  partition();
}

}  // namespace vorodec::solver
