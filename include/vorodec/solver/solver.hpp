#pragma once
// Explicit central-difference integration of rigid blocks and of the gridpoints of deformable
// blocks (src/solver/gridpoints.cpp) with Cundall local damping (docs/theory.md §3.3, 8.1, 9, 4).
// Each step: contact geometry -> laws -> block and gridpoint forces -> damping -> integration.
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/model.hpp"
#include "vorodec/solver/contact_detection.hpp"
#include "vorodec/solver/part_balance.hpp"

namespace vorodec::solver {

struct SolverSettings {
  double local_damping = 0.8;      // Cundall alpha
  double safety_factor = 0.8;      // fraction of the critical time step
  double time_step = 0.0;          // s; > 0: density scaling to reach this step (quasi-static only)
  double fixed_time_step = 0.0;    // s; > 0: this step, capped at the critical one (warns once)
  model::Point gravity{0.0, 0.0};  // m/s^2
  double contact_tolerance = 0.0;  // m, create within / delete beyond this gap
  // -, overlap (as a fraction of the rounding length) that stops a run: the corner's arc centre
  // must stay clear of the other block's edge (the geometry breaks at 1).
  double overlap_limit = 0.5;
  int max_detection_interval = 200;  // steps between detections at most
};

// Stops a run: NaN, runaway energy or excessive overlap. The message names the cause.
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Energy terms summed since the start (J per m thickness), docs/theory.md §12.
struct Energy {
  double boundary_work = 0.0;
  double body_work = 0.0;
  double damping = 0.0;
  double slip = 0.0;
  double breakage = 0.0;
  double viscous = 0.0;    // dashpots of viscous (Burger's) contacts
  double corrosion = 0.0;  // strain energy the stress-corrosion layers took from bonds
  double initial = 0.0;    // strain energy the in-situ stress set into the contacts at the start
};

class Solver {
 public:
  Solver(model::Model& model, std::vector<std::unique_ptr<laws::LawGroup>> laws, LawTable table,
         SolverSettings settings);

  // Detects the initial (bonded) contacts and computes the time step.
  void initialise();
  // One explicit step; prescribed blocks move with the velocity already set in the model.
  void step();
  // Moves every rigid block by (dx, dy, dtheta) m, m, rad at once, then updates the contacts as
  // a step would whose increment is that displacement, without integrating: the implicit elastic
  // start's jump. Adds the held blocks' work (trapezoid: the forces are linear along the jump) and
  // the applied loads' (Blocks::fx, fy, moment, held constant), advances the time by `duration` s
  // and leaves the free blocks at rest.
  void displace(const std::vector<double>& dx, const std::vector<double>& dy,
                const std::vector<double>& dtheta, double duration);

  double time() const { return time_; }
  double dt() const { return dt_; }
  // s, safety factor x the smallest sqrt(m/k) at the last detection (after density scaling).
  double critical_time_step() const { return critical_dt_; }
  // s, the density-scaling step (0: none).
  double scaling_time_step() const { return settings_.time_step; }
  // Creep stages: density scaling to a new step dt (s). Free blocks' velocities scale by the old
  // over the new step, so each moves as far per step as before: with every mass proportional to
  // dt^2 the discrete motion, and the kinetic energy, are unchanged (rigid blocks only).
  void rescale_time_step(double dt);
  // s, the shortest relaxation time of any contact (infinity without viscous laws).
  double relaxation_time() const;
  // Some law group has dashpots (its work is the energy term `viscous`).
  bool viscous() const;
  long steps() const { return steps_; }
  const Energy& energy() const { return energy_; }
  const std::vector<laws::CrackEvent>& cracks() const { return cracks_; }
  double kinetic_energy() const;
  double contact_strain_energy() const;
  double zone_strain_energy() const;  // J per m, deformable blocks
  std::size_t initial_bonded_contacts() const { return initial_bonded_; }
  const LawTable& law_table() const { return detector_.law_table(); }
  std::size_t detections() const { return detections_; }
  const std::vector<std::unique_ptr<laws::LawGroup>>& laws() const { return laws_; }
  // Sum of contact forces on block b in the last step (reaction of a platen), N per m.
  model::Point contact_force(std::size_t b) const { return {sums_[b].fx, sums_[b].fy}; }
  double contact_moment(std::size_t b) const { return sums_[b].m; }  // N m per m, about b
  const SolverSettings& settings() const { return settings_; }
  // The part of it from contacts with blocks of group g (a block bar's platen: the specimen's).
  model::Point contact_force_from(std::size_t b, model::Group g) const;
  // Unbalanced-force ratio of the last step: the mean over free bodies (specimen blocks and
  // gridpoints) of |unbalanced force| (contact + applied + gravity, before damping) over the mean
  // over contacts of |(fn, fs)|. Serial and O(blocks + contacts): call it every N steps only.
  double unbalanced_force_ratio() const;
  // N/m, summed spring stiffness of the contacts touching block b (servo gain).
  double contact_stiffness_on(std::size_t b) const;
  // Excavation: the blocks go to Group::excavated, held still (a zoned block's gridpoints too),
  // and their contacts (bonds too) are deleted at once.
  void remove_blocks(std::span<const std::uint32_t> blocks);
  // Throws InstabilityError if the state is not finite or contacts overlap by more than d/2.
  void check_stability() const;
  // Stress corrosion (drivers/corrosion_mode): contact i's bond, false if its law has none.
  bool bond(std::size_t i, laws::BondView& out) const;
  // Gives contact i the degraded bond b, carrying (fn, fs) N at its gap; the strain energy this
  // takes from it is the energy term `corrosion`.
  void set_bond(std::size_t i, const laws::BondView& b, double fn, double fs);
  // In-situ stress: contact i carries (fn, fs) N at its gap; its strain energy is the energy term
  // `initial`. False if its law cannot start loaded.
  bool preload(std::size_t i, double fn, double fs);
  // In-situ stress in the zones: their strain energy (J per m) joins the term `initial`.
  void add_initial_energy(double e) { energy_.initial += e; }
  // Breaks contact i's bond: a crack of `type` at `time` s (the corrosion clock).
  void break_bond(std::size_t i, laws::ContactEvent type, double time);
  // Called in every step between the contact forces and the integration: prescribed velocities
  // that follow this step's contact forces (a pressure bar's face). Empty: nothing.
  void set_face_control(std::function<void()> f) { face_control_ = std::move(f); }
  // Cracks of the following steps are stamped with this time (s) instead of the solver's: a
  // corrosion stage's clock. NaN: the solver's time again.
  void set_crack_clock(double t) { crack_clock_ = t; }
  // Cuts every contact pass into thread parts by these shares from now on, instead of by measured
  // time (tests: unequal parts give the same bits).
  void pin_part_shares(std::vector<double> shares) {
    balance_.pin(std::move(shares));
    partition();
  }
  // Checkpoints: everything a step reads that an earlier step wrote, the law groups' state
  // included. The thread parts are redone on loading, for the thread count then.
  void save(checkpoint::OutArchive& ar) const;
  void load(checkpoint::InArchive& ar);

 private:
  template <class Archive>
  void state(Archive& ar);
  void detect(bool bond_new);
  void compute_time_step();
  void partition();
  void contact_forces();  // laws of every contact -> sums_ (and cracks_)
  void gather_shared_forces();
  void integrate();
  void integrate_gridpoints();
  double gridpoint_time_step();  // s, min 2 sqrt(m/k) over gridpoints; applies density scaling

  model::Model& model_;
  std::vector<std::unique_ptr<laws::LawGroup>> laws_;
  std::vector<std::size_t> law_begin_;
  std::vector<std::size_t> deformable_begin_;  // per law: its contacts touching deformable blocks
  std::vector<double> zfx_, zfy_;              // zone forces per gridpoint, N per m
  // J per m, each gridpoint's share of this step's boundary, body and damping work (scratch),
  // summed after the vectorised update in gridpoint order.
  std::vector<double> work_boundary_, work_body_, work_damping_;
  // J per m, each block's boundary, body and damping work of this step (scratch, three runs of
  // one entry per block), summed after the vectorised update in block order.
  std::vector<double> block_work_;
  ContactDetector detector_;
  SolverSettings settings_;
  std::vector<model::ContactForce> forces_;
  std::vector<std::uint32_t> gather_begin_, gather_;  // block -> contacts (top bit: block is b)
  std::vector<model::BlockForceSum> sums_;            // contact force sums per block
  // Thread parts of the contact loop (laws::StepContext): per contact which of its blocks are
  // shared between parts, and the shared blocks, whose sums gather_shared_forces() takes.
  int chunks_ = 0;
  PartBalance balance_;  // ranges 2l and 2l + 1: law l's rigid and deformable contacts
  std::vector<std::size_t> block_cuts_;  // each thread's blocks in the per-block loops
  std::vector<std::uint8_t> shared_sides_;
  std::vector<std::uint32_t> shared_blocks_;
  std::vector<double> x_detect_, y_detect_, t_detect_;  // positions at the last detection
  std::vector<std::vector<laws::CrackEvent>> cracks_per_chunk_;
  std::vector<laws::CrackEvent> cracks_;
  Energy energy_;
  double dt_ = 0.0, critical_dt_ = 0.0, time_ = 0.0;
  double crack_clock_ = std::numeric_limits<double>::quiet_NaN();
  bool fixed_step_warned_ = false;
  std::function<void()> face_control_;
  long steps_ = 0, last_detection_ = 0;
  std::size_t initial_bonded_ = 0, detections_ = 0;
};

}  // namespace vorodec::solver
