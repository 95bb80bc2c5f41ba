#pragma once
// One stage of a load path at run time: the top platen's velocity each step and the end judgment.
#include "vorodec/loading/load_path.hpp"

namespace vorodec::loading {

// What the stage sees of the specimen after a step.
struct StageSample {
  double time_in_stage = 0;  // s
  double axial_stress = 0;   // Pa, compression +
  double axial_strain = 0;   // -, shortening +
  bool history_row = false;  // this step writes a history row (peaks are judged on rows)
  // Pa, the lateral stress now: a compressed specimen fails only above it, so a peak below it
  // is the confinement's transient (its squeeze of the specimen), never the specimen's peak.
  double confining_stress = 0;
};

enum class StageOutcome { running, done, stalled };

class StageControl {
 public:
  // v_previous: the platen velocity when the stage starts (m/s); stress and strain at its start.
  StageControl(const Stage& stage, double v_previous, double stress0, double strain0);

  // m/s, top platen, compressing +. platen_stiffness: N/m of the contacts on the top platen.
  double platen_velocity(double time_in_stage, double axial_stress, double platen_stiffness,
                         double dt, double width) const;
  StageOutcome judge(const StageSample& s);
  // Adaptive velocity stages: one control update from the current unbalanced-force ratio. The
  // speed then moves linearly to its new value over the next interval_steps steps of length dt.
  void adapt(double unbalanced_force_ratio, double time_in_stage, double dt);
  // 0..1, how far the stage has come (progress bar).
  double fraction() const { return fraction_; }
  // Pa, the highest stress of the stage's history rows, and whether the curve has passed it.
  double peak() const { return row_peak_; }
  bool past_peak() const { return past_peak_; }
  // Servo target of a stress-controlled stage at this time (Pa).
  double target(double time_in_stage) const;
  // Checkpoints: what the control has learnt (the stage itself comes from the model file).
  template <class Archive>
  void serialize(Archive& ar) {
    ar(v0_, v_, stress0_, strain0_, v_from_, t_adapt_, t_span_, row_peak_, fraction_,
       rows_since_peak_, held_, rising_, past_peak_);
  }

 private:
  const Stage& st_;
  double v0_, v_, stress0_, strain0_;
  double v_from_, t_adapt_ = 0, t_span_ = 0;  // the adaptive speed's move from v_from_ to v_
  double row_peak_ = 0, fraction_ = 0;
  long rows_since_peak_ = 0, held_ = 0;
  bool rising_ = true;      // towards end.axial_stress from below
  bool past_peak_ = false;  // as judged on the last history row
};

}  // namespace vorodec::loading
