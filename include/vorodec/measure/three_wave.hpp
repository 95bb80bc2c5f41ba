#pragma once
// Three-wave analysis of a split Hopkinson pressure bar test (docs/theory.md §16.4; [Kolsky1949]):
// the gauges' incident, reflected and transmitted strains, shifted to the specimen faces, give the
// faces' velocities and forces, hence the specimen's stress, strain rate and strain, and the
// stress-equilibrium factor. Compression and shortening positive.
#include <span>
#include <vector>

namespace vorodec::measure {

struct Bar1D {
  double wave_speed;      // m/s, c0
  double youngs_modulus;  // Pa
  double width;           // m, the diameter in the model's plane
};

struct BarPair {
  Bar1D incident, transmitted;
  double specimen_width, specimen_length;  // m
};

struct ThreeWavePoint {
  double t;                    // s, at the specimen faces
  double eps_i, eps_r, eps_t;  // incident, reflected, transmitted strain
  double s1, s2;               // Pa, stress on the incident and on the transmitted face
  double stress;               // Pa, (F1 + F2) / (2 A_s)
  double strain_rate;          // 1/s, (c_i (eps_i - eps_r) - c_t eps_t) / l_s
  double strain;               // -, the strain rate's integral (trapezoid)
  double eta;                  // -, 2 (s1 - s2) / (s1 + s2)
};

// eps_* sampled at the face times t (increasing, from the pulse's arrival).
std::vector<ThreeWavePoint> three_wave(const BarPair& bars, std::span<const double> t,
                                       std::span<const double> eps_i, std::span<const double> eps_r,
                                       std::span<const double> eps_t);

struct DynamicMeasures {
  bool valid = false;              // a compressive peak was found
  double peak_stress = 0;          // Pa, largest three-wave stress
  double peak_time = 0;            // s
  double strain_at_peak = 0;       // -
  double strain_rate_at_peak = 0;  // 1/s
  double mean_strain_rate = 0;     // 1/s, strain at peak / time to peak
  double eta_at_peak = 0;          // -
  // s, from which |eta| stays within equilibrium_tolerance up to the peak (NaN: never).
  double equilibrium_time = 0;
  double equilibrium_tolerance = 0.05;
  // -, the largest |eta| while the stress rises from half the peak to the peak.
  double eta_loading = 0;
  // s, the end of the ring-up: three transit times of the specimen, each measured as the wave's
  // first arrival at the transmitted face (its stress past 1 % of the peak). [Li2018]'s 36 us
  // ring-up is three transit times of its 50 mm granite.
  double ring_up_time = 0;
  // -, the largest |eta| from the end of the ring-up to the peak ([Li2018]'s "oscillation error"
  // after its 36 us ring-up); NaN when the peak comes first.
  double eta_after_ring_up = 0;
  double incident_energy = 0, reflected_energy = 0, transmitted_energy = 0;  // J per m
};

// A compressive pulse as a gauge recorded it (t increasing): its largest stress, its duration
// between the half-largest crossings (linear between samples), and its mean over the middle half
// of that duration (the plateau of a square or ramped pulse).
struct PulseShape {
  double peak = 0;      // Pa
  double duration = 0;  // s (NaN: the record does not hold both crossings)
  double plateau = 0;   // Pa
};
PulseShape pulse_shape(std::span<const double> t, std::span<const double> stress);

DynamicMeasures dynamic_measures(const BarPair& bars, std::span<const ThreeWavePoint> points,
                                 double equilibrium_tolerance = 0.05);

}  // namespace vorodec::measure
