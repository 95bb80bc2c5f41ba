#pragma once
// Exact 1D elastic pressure bars (docs/theory.md §16.1): a bar carries two waves, one towards the
// specimen face and one away from it, each travelling unchanged at c0 = sqrt(E / rho) (d'Alembert).
// The bar keeps the history of the wave its face emits and of the wave its far end emits; the
// stress anywhere at any past time follows from the two, so there is no grid and no dispersion.
#include <cmath>
#include <functional>
#include <vector>

#include "vorodec/loading/load_path.hpp"

namespace vorodec::loading {

struct BarProperties {
  double length = 0;           // m
  double width = 0;            // m, the bar's diameter in the model's plane
  double youngs_modulus = 0;   // Pa
  double density = 0;          // kg/m^3
  bool quiet_far_end = false;  // the far end absorbs (viscous end); otherwise it is free
  double wave_speed() const { return std::sqrt(youngs_modulus / density); }  // m/s
  double impedance() const { return density * wave_speed(); }                // Pa s/m
};

// A stress history sampled at increasing times, linear between samples, zero before the first.
class WaveHistory {
 public:
  void add(double t, double sigma);
  double at(double t) const;
  std::vector<double>& times() { return t_; }
  std::vector<double>& values() { return s_; }

 private:
  std::vector<double> t_, s_;
};

class ElasticBar {
 public:
  // source(t): the stress (Pa, compression +) the far end emits at t s on its own (a striker's
  // pulse), on top of what it reflects.
  ElasticBar(BarProperties p, std::function<double(double)> source);

  const BarProperties& properties() const { return p_; }
  // Pa, the stress of the wave arriving at the face at t s.
  double arriving(double t) const { return far_emitted(t - p_.length / c_); }
  // m/s, the face's velocity towards the specimen while it carries sigma_face Pa at t s.
  double face_velocity(double t, double sigma_face) const {
    return (2.0 * arriving(t) - sigma_face) / z_;
  }
  // The face carried sigma_face Pa at t s (times increase from call to call): the wave it emits.
  void record_face(double t, double sigma_face) { emitted_.add(t, sigma_face - arriving(t)); }
  // Pa, the stress at x m from the face at t s, and its two parts.
  double towards_face(double x, double t) const { return arriving(t + x / c_); }
  double away_from_face(double x, double t) const { return emitted_.at(t - x / c_); }
  double stress(double x, double t) const { return towards_face(x, t) + away_from_face(x, t); }
  // Checkpoints: the face's emitted history is the bar's whole state.
  WaveHistory& face_history() { return emitted_; }

 private:
  double far_emitted(double t) const;

  BarProperties p_;
  std::function<double(double)> source_;
  double c_, z_;
  WaveHistory emitted_;
};

// The stress a striker of length ls m and speed v m/s, of the incident bar's material, sends into
// it from impact time t0 s: rho c0 v / 2 for 2 ls / c0 (verification case A12); then it has
// separated. rise > 0 s: the pulse rises and falls over that time within the same duration (a
// pulse shaper's ramp), linearly or, `smooth`, as a raised cosine (no corner at either end of the
// rise, which would set the specimen ringing: docs/dynamics.md).
std::function<double(double)> striker_pulse(const BarProperties& bar, double ls, double v,
                                            double t0, double rise = 0.0, bool smooth = false);

// [shpb]: a split Hopkinson pressure bar test instead of [[stage]]s (docs/theory.md §16): a striker
// hits the incident bar, whose face is the top platen; the transmitted bar's face is the bottom
// platen. Time 0 is the pulse's arrival at the specimen.
struct ShpbConfig final : ExtensionSettings {
  loading::BarProperties incident, transmitted;
  std::vector<double> incident_gauges, transmitted_gauges;  // m from the specimen face
  double striker_length = 0;                                // m, of the incident bar's material
  double striker_velocity = 0;                              // m/s
  double rise_time = 0;        // s, the pulse's rise and fall (a pulse shaper); 0: none
  bool smooth_rise = false;    // the rise and fall as a raised cosine, not a linear ramp
  double duration = 0;         // s of the specimen's loading; 0: twice the pulse's duration
  double record_interval = 0;  // s between bars.csv rows; 0: the pulse's duration / 1000
  double equilibrium_tolerance = 0.05;  // -, |eta| of "in equilibrium"
  // Bars built from rectangular blocks of this length (m) with a bar contact law, instead of the
  // exact 1D bars; the striker's pulse enters through the incident bar's far end; gauges at the
  // joints nearest their positions.
  bool block_bars = false;
  double bar_block_length = 0;
};

}  // namespace vorodec::loading
