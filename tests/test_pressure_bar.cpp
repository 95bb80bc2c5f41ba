// Pressure bars (loading/pressure_bar.hpp) and the three-wave analysis (measure/three_wave.hpp):
// A12's cases, an equilibrated synthetic test, and a small SHPB run end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "../verification/cases/cases.hpp"
#include "run_support.hpp"
#include "vorodec/loading/pressure_bar.hpp"
#include "vorodec/measure/three_wave.hpp"

namespace fs = std::filesystem;
using namespace vorodec;

TEST(PressureBar, ExactBarCarriesTheStrikersPulseToRoundOff) {
  for (const auto& r : verification::a12_exact_bar())
    EXPECT_TRUE(r.pass()) << r.name << ": " << r.error;
}

TEST(PressureBar, BarAgainstBarTransmitsTheWholePulse) {
  for (const auto& r : verification::a12_bar_on_bar())
    EXPECT_TRUE(r.pass()) << r.name << ": " << r.error;
}

TEST(PressureBar, CosineRiseCarriesTheRampsImpulseWithoutItsCorners) {
  const loading::BarProperties bar{1.0, 0.02, 2.0e11, 8000.0, true};
  const double ls = 0.2, v = 5.0, rise = 2e-5;
  const double sigma = 0.5 * bar.impedance() * v, duration = 2.0 * ls / bar.wave_speed();
  const auto ramp = loading::striker_pulse(bar, ls, v, 0.0, rise);
  const auto cosine = loading::striker_pulse(bar, ls, v, 0.0, rise, true);
  double ramp_impulse = 0, cosine_impulse = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {  // midpoint rule over the pulse
    const double t = (k + 0.5) * duration / n;
    ramp_impulse += ramp(t) * duration / n;
    cosine_impulse += cosine(t) * duration / n;
  }
  EXPECT_NEAR(cosine_impulse, ramp_impulse, 1e-6 * ramp_impulse);
  EXPECT_NEAR(cosine_impulse, sigma * (duration - rise), 1e-6 * ramp_impulse);
  EXPECT_NEAR(cosine(0.5 * rise), 0.5 * sigma, 1e-9 * sigma);
  EXPECT_NEAR(cosine(rise), sigma, 1e-9 * sigma);
  // No corner: the slope is zero where the rise starts and ends (the ramp's jumps by sigma / rise).
  const double h = 1e-3 * rise;
  EXPECT_LT(cosine(h) / h, 0.01 * sigma / rise);
  EXPECT_LT((sigma - cosine(rise - h)) / h, 0.01 * sigma / rise);
  EXPECT_NEAR(ramp(h) / h, sigma / rise, 1e-6 * sigma / rise);
}

TEST(PressureBar, FreeFarEndReflectsAndQuietFarEndAbsorbs) {
  loading::BarProperties p{1.0, 0.02, 2.0e11, 8000.0, false};
  const double c = p.wave_speed();
  // A face that never moves would carry the arriving wave twice; here it carries a pulse of its
  // own (as if pushed), which the far end returns after 2 L / c with the opposite sign if free.
  for (const bool quiet : {false, true}) {
    p.quiet_far_end = quiet;
    loading::ElasticBar bar(p, nullptr);
    const double h = 1e-7;
    for (double t = 0; t < 3.0 * p.length / c; t += h) bar.record_face(t, t < 1e-5 ? 1e6 : 0.0);
    const double back = bar.arriving(2.0 * p.length / c + 5e-6);
    EXPECT_NEAR(back, quiet ? 0.0 : -1e6, 1e-6) << (quiet ? "quiet" : "free");
  }
}

TEST(ThreeWave, EquilibratedSpecimenHasEtaZeroAndTheTransmittedStress) {
  const measure::BarPair bars{{5000, 2e11, 0.05}, {5000, 2e11, 0.05}, 0.05, 0.025};
  std::vector<double> t, ei, er, et;
  for (int k = 0; k <= 100; ++k) {
    t.push_back(k * 1e-6);
    ei.push_back(1e-3);
    et.push_back(0.4e-3);
    er.push_back(0.4e-3 - 1e-3);  // eps_I + eps_R = eps_T: both faces carry the same force
  }
  const auto p = measure::three_wave(bars, t, ei, er, et);
  EXPECT_NEAR(p.back().eta, 0.0, 1e-12);
  EXPECT_NEAR(p.back().stress, 2e11 * 0.4e-3, 1e-3);
  const double rate = 5000 / 0.025 * (1e-3 - (0.4e-3 - 1e-3) - 0.4e-3);
  EXPECT_NEAR(p.back().strain_rate, rate, 1e-9 * rate);
  EXPECT_NEAR(p.back().strain, rate * 1e-4, 1e-9 * rate * 1e-4);
  const measure::DynamicMeasures m = measure::dynamic_measures(bars, p);
  EXPECT_TRUE(m.valid);
  EXPECT_NEAR(m.equilibrium_time, 0.0, 1e-15);
  // Energy flux E c A eps^2 over 1e-4 s.
  EXPECT_NEAR(m.incident_energy, 2e11 * 5000 * 0.05 * 1e-6 * 1e-4, 1e-9);
}

// A ramp whose transmitted face starts 10 us late (one transit) and lags 40 % behind at first,
// 5 % from 30 us on: the ring-up ends at three transit times, 30 us, and only the lag after it
// counts.
TEST(ThreeWave, EtaAfterTheRingUpCountsFromThreeTransitTimes) {
  const measure::BarPair bars{{5000, 2e11, 0.05}, {5000, 2e11, 0.05}, 0.05, 0.025};
  std::vector<double> t, ei, er, et;
  for (int k = 0; k <= 60; ++k) {
    const double time = k * 1e-6, s1 = 1e-5 * k;  // eps_I + eps_R, rising to the peak at 60 us
    const double s2 = k < 10 ? 0.0 : (k < 30 ? 0.6 : 0.95) * s1;
    t.push_back(time);
    ei.push_back(2e-3);
    er.push_back(s1 - 2e-3);
    et.push_back(s2);
  }
  const auto p = measure::three_wave(bars, t, ei, er, et);
  const measure::DynamicMeasures m = measure::dynamic_measures(bars, p);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(m.ring_up_time, 30e-6, 1e-12);
  EXPECT_NEAR(m.eta_after_ring_up, 2.0 * 0.05 / 1.95, 1e-12);
}

using vorodec::testing::json_number;
using vorodec::testing::slurp;

// The bars' account (incident - reflected - transmitted energy, from the face histories) and the
// solver's (the platens' force at t_n times their velocity over the step) differ at first order
// in the time step: the gap is below 1 % and halves with the step.
TEST(ShpbRun, EnergyLeavingTheBarsIsTheWorkDoneOnTheSpecimenToFirstOrder) {
  double gap[2] = {0, 0};
  for (const int k : {0, 1}) {
    const fs::path out = fs::temp_directory_path() / ("vorodec_shpb_small_" + std::to_string(k));
    fs::remove_all(out);
    ASSERT_EQ(
        vorodec::testing::run_vorodec("run " + std::string(VORODEC_SOURCE_DIR) +
                                      "/tests/models/shpb_small.toml --threads 1 --no-vtk --out " +
                                      out.string() + (k ? " --set solver.safety_factor=0.4" : "")),
        0);
    const std::string s = slurp(out / "summary.json");
    const double absorbed = json_number(s, "absorbed"), work = json_number(s, "boundary_work");
    EXPECT_GT(absorbed, 0.0);
    gap[k] = std::abs(absorbed - work) / work;
    EXPECT_LT(gap[k], 1e-2);
    // The three-wave stress and the stress from the face forces agree at the peak.
    EXPECT_NEAR(json_number(s, "dynamic_strength_Pa"), json_number(s, "peak_face_force_stress_Pa"),
                0.02 * json_number(s, "peak_face_force_stress_Pa"));
    EXPECT_TRUE(fs::exists(out / "bars.csv"));
    EXPECT_TRUE(fs::exists(out / "gauges.csv"));
  }
  EXPECT_LT(gap[1], 0.7 * gap[0]) << gap[0] << " -> " << gap[1];
}

// Bars built from blocks: the striker's square pulse reaches the gauge at rho c0 v / 2 within
// 1 % and lasts 2 L / c0 within 2 % (the lattice rounds the fronts); with the model's ramped
// pulse the three-wave stress agrees with the platens' contact forces at the peak.
TEST(ShpbRun, BlockBarsCarryTheStrikersPulseAndAgreeWithTheFaceForces) {
  const fs::path out = fs::temp_directory_path() / "vorodec_shpb_small_blocks";
  for (const char* rise : {"0", "5e-6"}) {
    fs::remove_all(out);
    ASSERT_EQ(vorodec::testing::run_vorodec(
                  "run " + std::string(VORODEC_SOURCE_DIR) +
                  "/tests/models/shpb_small.toml --threads 1 --no-vtk --set shpb.bars=blocks "
                  "--set shpb.rise_time=" +
                  rise + " --out " + out.string()),
              0);
    const std::string s = slurp(out / "summary.json");
    if (std::string(rise) == "0") {
      EXPECT_NEAR(json_number(s, "measured_incident_stress_Pa"),
                  json_number(s, "incident_stress_Pa"),
                  0.01 * json_number(s, "incident_stress_Pa"));
      EXPECT_NEAR(json_number(s, "measured_pulse_duration_s"), json_number(s, "pulse_duration_s"),
                  0.02 * json_number(s, "pulse_duration_s"));
    } else {
      EXPECT_NEAR(json_number(s, "dynamic_strength_Pa"),
                  json_number(s, "peak_face_force_stress_Pa"),
                  0.02 * json_number(s, "peak_face_force_stress_Pa"));
    }
  }
}

// The incident wave as a striker speed, a particle velocity (half of it) or a stress
// (rho c0 v / 2) is the same test: the same history and gauges, the same strength to the rounding
// of 2 sigma / (rho c0).
TEST(ShpbRun, StrikerSpeedParticleVelocityAndIncidentStressGiveTheSameTest) {
  const fs::path dir = fs::temp_directory_path() / "vorodec_shpb_input";
  fs::create_directories(dir);
  const std::string base = slurp(fs::path(VORODEC_SOURCE_DIR) / "tests/models/shpb_small.toml");
  const std::string striker_line = "striker_velocity = 5.0       # m/s";
  ASSERT_NE(base.find(striker_line), std::string::npos);
  const auto run = [&](const std::string& name, const std::string& line) {
    std::string text = base;
    text.replace(text.find(striker_line), striker_line.size(), line);
    std::ofstream(dir / (name + ".toml")) << text;
    const fs::path out = dir / name;
    fs::remove_all(out);
    EXPECT_EQ(vorodec::testing::run_vorodec("run " + (dir / (name + ".toml")).string() +
                                            " --threads 1 --no-vtk --out " + out.string()),
              0)
        << name;
    return out;
  };
  // shpb_small's bar: E 210.912 GPa, 7800 kg/m^3; striker 5 m/s.
  const double stress = 0.5 * 7800 * std::sqrt(210.912e9 / 7800) * 5.0;
  const fs::path striker_run = run("striker", striker_line);
  const fs::path particle_run = run("particle", "incident_particle_velocity = 2.5");
  char line[64];
  std::snprintf(line, sizeof line, "incident_stress = %.17g", stress);
  const fs::path stress_run = run("stress", line);
  for (const char* f : {"history.csv", "gauges.csv"})
    EXPECT_EQ(slurp(particle_run / f), slurp(striker_run / f)) << f;
  const std::string striker = slurp(striker_run / "summary.json");
  const std::string by_stress = slurp(stress_run / "summary.json");
  EXPECT_NEAR(json_number(by_stress, "incident_stress_Pa"), stress, 1e-9 * stress);
  EXPECT_NEAR(json_number(by_stress, "dynamic_strength_Pa"),
              json_number(striker, "dynamic_strength_Pa"),
              1e-9 * json_number(striker, "dynamic_strength_Pa"));
}
