// Bad input: one clear message naming file, key and line, and exit code 2 — never a crash.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "run_support.hpp"

using vorodec::testing::Outcome;
using vorodec::testing::run_capture;
namespace fs = std::filesystem;

namespace {

const char* good_model = R"(seed = 3
[specimen]
width = 0.02
height = 0.04
block_count = 60
[blocks]
density = 2600
[joints]
jkn = 2e13
jks = 8e12
tension = 10e6
cohesion = 20e6
friction = 30
[[stage]]
platen_velocity = 0.05
end_axial_strain = 0.001
)";

fs::path write_model(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "vorodec_bad_input";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << text;
  return file;
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

// Runs `vorodec check` on a model edited from the good one: rejected with exit code 2 and one
// message naming file:line, the key and the reason, never a crash.
::testing::AssertionResult rejected(const std::string& name, const std::string& text,
                                    const std::string& key, int line, const std::string& phrase) {
  const fs::path file = write_model(name, text);
  const Outcome o = run_capture("check " + file.string());
  const std::string where = file.string() + ":" + std::to_string(line);
  if (o.code != 2)
    return ::testing::AssertionFailure() << "exit code " << o.code << ": " << o.output;
  if (o.output.find(where) == std::string::npos)
    return ::testing::AssertionFailure() << "no '" << where << "' in: " << o.output;
  if (o.output.find(key) == std::string::npos)
    return ::testing::AssertionFailure() << "no key '" << key << "' in: " << o.output;
  if (o.output.find(phrase) == std::string::npos)
    return ::testing::AssertionFailure() << "no '" << phrase << "' in: " << o.output;
  if (o.output.find("terminate") != std::string::npos)
    return ::testing::AssertionFailure() << "crashed: " << o.output;
  return ::testing::AssertionSuccess();
}

}  // namespace

TEST(BadInput, GoodModelPassesCheck) {
  const Outcome o = run_capture("check " + write_model("good", good_model).string());
  EXPECT_EQ(o.code, 0) << o.output;
}

TEST(BadInput, MisspelledKeyIsNamedWithLineAndSuggestion) {
  EXPECT_TRUE(rejected("misspelled", replace(good_model, "cohesion = 20e6", "cohesoin = 20e6"),
                       "joints.cohesoin", 12, "did you mean 'cohesion'"));
}

TEST(BadInput, WrongTypeIsRejected) {
  EXPECT_TRUE(rejected("wrong_type", replace(good_model, "friction = 30", "friction = \"thirty\""),
                       "joints.friction", 13, "must be a number"));
}

TEST(BadInput, NegativeStiffnessIsRejected) {
  EXPECT_TRUE(rejected("negative_jkn", replace(good_model, "jkn = 2e13", "jkn = -2e13"),
                       "joints.jkn", 9, "must be > 0"));
}

TEST(BadInput, ZeroWeibullShapeIsRejected) {
  EXPECT_TRUE(rejected(
      "weibull_shape",
      replace(good_model, "tension = 10e6", "tension = { weibull_shape = 0, mean = 10e6 }"),
      "joints.tension.weibull_shape", 11, "must be > 0"));
}

TEST(BadInput, NonPositiveDamageGridCellIsRejected) {
  EXPECT_TRUE(rejected("damage_grid_cell",
                       replace(good_model, "end_axial_strain = 0.001",
                               "end_axial_strain = 0.001\n[output]\ndamage_grid_cell = 0"),
                       "output.damage_grid_cell", 18, "must be > 0"));
}

TEST(BadInput, MissingRequiredKeyIsNamed) {
  EXPECT_TRUE(rejected("missing_density", replace(good_model, "density = 2600", ""),
                       "blocks.density", 6, "required key is missing"));
}

TEST(BadInput, TomlSyntaxErrorGivesLine) {
  EXPECT_TRUE(rejected("syntax", replace(good_model, "width = 0.02", "width = = 0.02"), "", 3, ""));
}

TEST(BadInput, ImpossibleGeometryIsReportedAgainstTheSpecimenTable) {
  // 3 mm passes the model checks (blocks of sqrt(area / 60) = 3.65 mm) but no tessellation keeps
  // every block when edges that short are collapsed.
  EXPECT_TRUE(
      rejected("geometry",
               replace(good_model, "block_count = 60", "block_count = 60\nmin_edge_length = 0.003"),
               "[specimen]", 2, "impossible geometry"));
}

// The lengths of the specimen are checked against one another before anything is tessellated.

TEST(BadInput, TinyDiscDiameterIsRefusedAtOnce) {
  const std::string disc = replace(
      replace(good_model, "width = 0.02\nheight = 0.04", "shape = \"disc\"\ndiameter = 1e-300"),
      "block_count = 60", "block_count = 60\nmin_edge_length = 2.5e-4");
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(rejected("tiny_disc", disc, "specimen.diameter", 4,
                       "must be between 1e-06 m and 1000 m (got 1e-300 m)"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(BadInput, FlatsOfABrazilianDiscBeyond60DegreesAreRefused) {
  const std::string disc =
      replace(replace(good_model, "width = 0.02\nheight = 0.04",
                      "shape = \"disc\"\ndiameter = 0.03\nflat_angle = 75"),
              "block_count = 60", "block_count = 60\nmin_edge_length = 2.5e-4");
  EXPECT_TRUE(
      rejected("steep_flats", disc, "specimen.flat_angle", 5, "must be at most 60 deg (got 75)"));
}

TEST(BadInput, HugeSpecimenWidthIsRefused) {
  EXPECT_TRUE(rejected("huge_width", replace(good_model, "width = 0.02", "width = 1e300"),
                       "specimen.width", 3, "must be between 1e-06 m and 1000 m"));
}

TEST(BadInput, SpecimenNarrowerThanItsBlocksIsRefused) {
  EXPECT_TRUE(rejected("narrow", replace(good_model, "width = 0.02", "width = 2e-5"),
                       "specimen.width", 3, "must be larger than the blocks' mean edge"));
}

TEST(BadInput, MoreThanAMillionBlocksAreRefusedBeforeTessellating) {
  EXPECT_TRUE(rejected("block_count",
                       replace(good_model, "block_count = 60", "block_count = 2000000"),
                       "specimen.block_count", 5, "must be <= 1000000"));
  EXPECT_TRUE(rejected("mean_edge",
                       replace(good_model, "block_count = 60", "mean_edge_length = 1e-5"),
                       "specimen.mean_edge_length", 5, "more than the 1000000 allowed"));
}

TEST(BadInput, MinimumEdgeLongerThanTheBlocksIsRefusedByKey) {
  EXPECT_TRUE(
      rejected("min_edge",
               replace(good_model, "block_count = 60", "block_count = 60\nmin_edge_length = 0.05"),
               "specimen.min_edge_length", 6,
               "must be shorter than the block size sqrt(area / block_count) = 3.651 mm"));
}

TEST(BadInput, RoundingLengthOverHalfTheBlockSizeIsRefused) {
  EXPECT_TRUE(
      rejected("rounding",
               replace(good_model, "[[stage]]\n", "[contact]\nrounding_length = 2e-3\n[[stage]]\n"),
               "contact.rounding_length", 15, "must be shorter than half of the block size"));
}

TEST(BadInput, ContactToleranceLongerThanTheBlocksIsRefused) {
  EXPECT_TRUE(rejected(
      "tolerance", replace(good_model, "[[stage]]\n", "[contact]\ntolerance = 0.01\n[[stage]]\n"),
      "contact.tolerance", 15, "must be shorter than the block size"));
}

TEST(BadInput, LloydIterationsBeyondTheLimitAreRefused) {
  EXPECT_TRUE(rejected(
      "lloyd",
      replace(good_model, "block_count = 60", "block_count = 60\nlloyd_iterations = 100000"),
      "specimen.lloyd_iterations", 6, "must be <= 100"));
}

TEST(BadInput, TooFineZonesAndDamageGridAreRefused) {
  EXPECT_TRUE(
      rejected("fine_zones",
               replace(good_model, "density = 2600",
                       "density = 2600\ndeformable = true\nzone_size = 1e-6\nE = 40e9\nnu = 0.2"),
               "blocks.zone_size", 9, "more than the 10000000 allowed"));
  EXPECT_TRUE(rejected("fine_damage_grid",
                       replace(good_model, "end_axial_strain = 0.001",
                               "end_axial_strain = 0.001\n[output]\ndamage_grid_cell = 1e-6"),
                       "output.damage_grid_cell", 18, "more than the 1000000 allowed"));
}

TEST(BadInput, CycleCountBeyondTheLimitIsRefused) {
  const std::string cyclic =
      "[[stage]]\ncontrol = \"cyclic\"\nreference_peak = 40e6\nfirst_upper_fraction = 0.2\n"
      "upper_increment_fraction = 0.1\ncycles = 2147483648\nplaten_velocity = 0.05\n"
      "unloading_rate = 1e9\n";
  EXPECT_TRUE(rejected("cycles", replace(good_model, "[[stage]]\n", cyclic + "[[stage]]\n"),
                       "stage[0].cycles", 19, "must be <= 10000"));
}

TEST(BadInput, WeibullShapeTooSmallForItsGammaFunctionIsRefused) {
  EXPECT_TRUE(rejected(
      "weibull_tiny",
      replace(good_model, "tension = 10e6", "tension = { weibull_shape = 1e-3, mean = 10e6 }"),
      "joints.tension.weibull_shape", 11, "Gamma(1 + 1/m) overflows"));
}

TEST(BadInput, NonFiniteGravityIsRefused) {
  EXPECT_TRUE(rejected(
      "gravity", replace(good_model, "[[stage]]\n", "[solver]\ngravity = [nan, 0]\n[[stage]]\n"),
      "solver.gravity", 15, "must hold finite numbers only"));
}

TEST(BadInput, UnwritableOutputFolderIsRejected) {
  const fs::path file = write_model("good_for_out", good_model);
  const Outcome o = run_capture("run " + file.string() + " --out /proc/vorodec_cannot_write_here");
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("--out"), std::string::npos) << o.output;
}

TEST(BadInput, UnknownCommandLineOptionExitsWithTwo) {
  EXPECT_EQ(run_capture("run --no-such-option x.toml").code, 2);
}

TEST(BadInput, CyclicBlockWithLowerLimitAboveAnUpperLimitIsRejected) {
  const std::string cyclic =
      "[[stage]]\ncontrol = \"cyclic\"\nupper_stresses = [10e6, 20e6]\nlower_stress = 15e6\n"
      "platen_velocity = 0.05\nunloading_rate = 1e9\n";
  EXPECT_TRUE(rejected("cyclic_lower", replace(good_model, "[[stage]]\n", cyclic + "[[stage]]\n"),
                       "stage[0].lower_stress", 17, "must lie below every upper stress"));
}

TEST(BadInput, CyclicBlockWithoutUnloadingRateIsRejected) {
  const std::string cyclic =
      "[[stage]]\ncontrol = \"cyclic\"\nupper_stresses = [10e6, 20e6]\nplaten_velocity = 0.05\n";
  EXPECT_TRUE(rejected("cyclic_rate", replace(good_model, "[[stage]]\n", cyclic + "[[stage]]\n"),
                       "stage[0].unloading_rate", 14, "required key is missing"));
}

TEST(BadInput, FixedTimeStepWithDensityScalingIsRejected) {
  const std::string solver = "[solver]\ntime_step = 1e-6\nfixed_time_step = 1e-8\n";
  EXPECT_TRUE(rejected("fixed_and_scaled",
                       replace(good_model, "[[stage]]\n", solver + "[[stage]]\n"),
                       "solver.fixed_time_step", 16, "cannot be combined with 'time_step'"));
}

TEST(BadInput, NonPositiveFixedTimeStepIsRejected) {
  EXPECT_TRUE(
      rejected("fixed_zero",
               replace(good_model, "[[stage]]\n", "[solver]\nfixed_time_step = 0\n[[stage]]\n"),
               "solver.fixed_time_step", 15, "must be > 0"));
}

TEST(BadInput, NonPositiveZoneSizeIsRejected) {
  EXPECT_TRUE(
      rejected("zone_size",
               replace(good_model, "density = 2600",
                       "density = 2600\ndeformable = true\nzone_size = 0\nE = 40e9\nnu = 0.2"),
               "blocks.zone_size", 9, "must be > 0"));
}

TEST(BadInput, IncompressiblePoissonRatioIsRejected) {
  EXPECT_TRUE(
      rejected("poisson_ratio",
               replace(good_model, "density = 2600",
                       "density = 2600\ndeformable = true\nzone_size = 0.002\nE = 40e9\nnu = 0.5"),
               "blocks.nu", 11, "must be > -1 and < 0.5"));
}

TEST(BadInput, AdaptiveVelocityWithMaximumBelowMinimumIsRejected) {
  EXPECT_TRUE(rejected("adaptive_range",
                       replace(good_model, "end_axial_strain = 0.001",
                               "end_axial_strain = 0.001\nadaptive_velocity = { target_ratio = "
                               "1e-3, min_velocity = 0.01, max_velocity = 0.005 }"),
                       "stage[0].adaptive_velocity.max_velocity", 17, "must be >= min_velocity"));
}

TEST(BadInput, AdaptiveVelocityStartingOutsideItsRangeIsRejected) {
  EXPECT_TRUE(rejected("adaptive_start",
                       replace(good_model, "end_axial_strain = 0.001",
                               "end_axial_strain = 0.001\nadaptive_velocity = { target_ratio = "
                               "1e-3, min_velocity = 0.001, max_velocity = 0.01 }"),
                       "stage[0].adaptive_velocity.min_velocity", 17,
                       "platen_velocity (0.05 m/s, the starting speed) must lie between"));
}

TEST(BadInput, AdaptiveVelocityMisspelledOrMissingKeyIsNamed) {
  const std::string table =
      "end_axial_strain = 0.001\nadaptive_velocity = { target_ratio = 1e-3, "
      "min_velocity = 0.01, max_velocity = 0.1, max_chnage = 2 }";
  EXPECT_TRUE(rejected("adaptive_typo", replace(good_model, "end_axial_strain = 0.001", table),
                       "stage[0].adaptive_velocity.max_chnage", 17, "did you mean 'max_change'"));
  EXPECT_TRUE(rejected("adaptive_missing",
                       replace(good_model, "end_axial_strain = 0.001",
                               "end_axial_strain = 0.001\nadaptive_velocity = { min_velocity = "
                               "0.01, max_velocity = 0.1 }"),
                       "stage[0].adaptive_velocity.target_ratio", 17, "required key is missing"));
  EXPECT_TRUE(rejected("adaptive_change",
                       replace(good_model, "end_axial_strain = 0.001",
                               "end_axial_strain = 0.001\nadaptive_velocity = { target_ratio = "
                               "1e-3, min_velocity = 0.01, max_velocity = 0.1, max_change = 1 }"),
                       "stage[0].adaptive_velocity.max_change", 17, "must be > 1"));
}

namespace {

// The good model with Burger's joints and a creep stage after its loading stage.
const char* burgers_model = R"(seed = 3
[specimen]
width = 0.02
height = 0.04
block_count = 60
[blocks]
density = 2600
[joints]
law = "burgers"
kmn = 2e13
kms = 2e13
cmn = 2e17
cms = 2e17
kkn = 4e13
kks = 4e13
ckn = 4e15
cks = 4e15
friction = 30
[[stage]]
platen_velocity = 0.05
end_axial_strain = 0.001
[[stage]]
control = "creep"
deviatoric_stress = 10e6
duration_days = 1.0
)";

}  // namespace

TEST(BadInput, BurgersModelWithACreepStagePassesCheck) {
  const Outcome o = run_capture("check " + write_model("burgers_good", burgers_model).string());
  EXPECT_EQ(o.code, 0) << o.output;
}

TEST(BadInput, NonPositiveBurgersSpringOrDashpotIsRejected) {
  EXPECT_TRUE(rejected("burgers_kmn", replace(burgers_model, "kmn = 2e13", "kmn = -2e13"),
                       "joints.kmn", 10, "must be > 0"));
  EXPECT_TRUE(rejected("burgers_ckn", replace(burgers_model, "ckn = 4e15", "ckn = 0"), "joints.ckn",
                       16, "must be > 0"));
}

TEST(BadInput, BurgersKeyUnderALawWithoutItIsRejected) {
  EXPECT_TRUE(rejected("burgers_key_under_mc",
                       replace(good_model, "jks = 8e12", "jks = 8e12\nkmn = 8e12"), "joints.kmn",
                       11, "unknown key"));
}

TEST(BadInput, CreepStageWithoutItsStressIsRejected) {
  EXPECT_TRUE(rejected("creep_no_stress",
                       replace(burgers_model, "deviatoric_stress = 10e6", "deviatoric = 10e6"),
                       "stage[1].deviatoric_stress", 22, "required"));
}

TEST(BadInput, CreepStageDurationMustBePositiveAndGivenOnce) {
  EXPECT_TRUE(rejected("creep_zero_days",
                       replace(burgers_model, "duration_days = 1.0", "duration_days = 0"),
                       "stage[1].duration_days", 25, "must be > 0"));
  EXPECT_TRUE(rejected(
      "creep_two_durations",
      replace(burgers_model, "duration_days = 1.0", "duration_days = 1.0\nduration = 86400"),
      "stage[1].duration_days", 25, "exactly one of duration"));
}

TEST(BadInput, CreepStageWithoutDashpotsOrAStepIsRejected) {
  const std::string text = std::string(good_model) +
                           "[[stage]]\ncontrol = \"creep\"\ndeviatoric_stress = 1e6\n"
                           "duration = 10\n";
  EXPECT_TRUE(rejected("creep_without_dashpots", text, "stage[1].control", 18, "has none"));
}

namespace {

// A small grain-based model with the corrosion layers and a corrosion stage.
const char* corrosion_model = R"(seed = 3
[specimen]
kind = "grains"
width = 0.01
height = 0.02
grain_size = 2.5e-3
sub_block_size = 1.2e-3
min_edge_length = 1e-4
[[mineral]]
name = "feldspar"
fraction = 1.0
density = 2600
[joints.intergranular]
jkn = 2e13
jks = 8e12
tension = 8e6
cohesion = 16e6
friction = 25
[joints.transgranular]
jkn = 4e13
jks = 1.6e13
tension = 16e6
cohesion = 32e6
friction = 35
[corrosion]
beta_up = 6e-15
beta_low = 1e-20
r_mid = 0.7
k_v = -55
beta2 = 25.8
activation_stress = 6e6
beta4 = 25.8
activation_level = 0.4
[[stage]]
control = "corrosion"
driving_stress_ratio = 0.8
peak_stress = 60e6
steps_per_failure = 4
)";

// The line of `text` that holds `needle` (1-based).
int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

}  // namespace

TEST(BadInput, CorrosionModelPassesCheck) {
  const Outcome o = run_capture("check " + write_model("corrosion_good", corrosion_model).string());
  EXPECT_EQ(o.code, 0) << o.output;
}

TEST(BadInput, CorrosionOnASpecimenWithoutGrainsIsRejected) {
  const std::string text =
      replace(good_model, "[[stage]]", "[corrosion]\nbeta_up = 6e-15\n[[stage]]");
  EXPECT_TRUE(rejected("corrosion_no_grains", text, "corrosion", line_of(text, "[corrosion]"),
                       "grain-based specimen"));
}

TEST(BadInput, CorrosionStageWithoutTheLayersConstantsIsRejected) {
  std::string text = corrosion_model;
  text.erase(text.find("[corrosion]"), text.find("[[stage]]") - text.find("[corrosion]"));
  EXPECT_TRUE(rejected("corrosion_no_table", text, "stage[0].control",
                       line_of(text, "control = \"corrosion\""), "[corrosion] table"));
}

TEST(BadInput, DrivingStressRatioOutsideZeroToOneIsRejected) {
  const std::string m = corrosion_model;
  const int line = line_of(m, "driving_stress_ratio");
  EXPECT_TRUE(rejected("corrosion_rs_high",
                       replace(m, "driving_stress_ratio = 0.8", "driving_stress_ratio = 1.2"),
                       "stage[0].driving_stress_ratio", line, "must be in (0, 1)"));
  EXPECT_TRUE(rejected("corrosion_rs_negative",
                       replace(m, "driving_stress_ratio = 0.8", "driving_stress_ratio = -0.5"),
                       "stage[0].driving_stress_ratio", line, "must be > 0"));
}

TEST(BadInput, NegativeCorrosionRatesAreRejected) {
  const std::string m = corrosion_model;
  EXPECT_TRUE(rejected("corrosion_beta_negative", replace(m, "beta_up = 6e-15", "beta_up = -6e-15"),
                       "corrosion.beta_up", line_of(m, "beta_up"), "must be > 0"));
  EXPECT_TRUE(rejected("corrosion_beta2_negative", replace(m, "beta2 = 25.8", "beta2 = -25.8"),
                       "corrosion.beta2", line_of(m, "beta2"), "must be > 0"));
  EXPECT_TRUE(rejected("corrosion_kv_positive", replace(m, "k_v = -55", "k_v = 55"),
                       "corrosion.k_v", line_of(m, "k_v"), "must be negative"));
}

TEST(BadInput, FewerThanOneCorrosionStepPerFailureIsRejected) {
  const std::string m = corrosion_model;
  EXPECT_TRUE(
      rejected("corrosion_nc", replace(m, "steps_per_failure = 4", "steps_per_failure = 0.5"),
               "stage[0].steps_per_failure", line_of(m, "steps_per_failure"), "n_c must be >= 1"));
}

TEST(BadInput, QuietBoundaryModelPassesCheck) {
  const std::string text =
      replace(good_model, "[[stage]]",
              "[quiet_boundary]\nsides = [\"left\", \"right\"]\ninput_side = \"top\"\n"
              "input_velocity = 0.1\ninput_duration = 1e-5\n[[stage]]");
  const Outcome o = run_capture("check " + write_model("quiet_good", text).string());
  EXPECT_EQ(o.code, 0) << o.output;
}

TEST(BadInput, QuietBoundaryOnAMisspelledSideIsRejected) {
  const std::string text = replace(good_model, "[[stage]]",
                                   "[quiet_boundary]\nsides = [\"left\", \"rihgt\"]\n[[stage]]");
  EXPECT_TRUE(rejected("quiet_side", text, "quiet_boundary.sides", line_of(text, "rihgt"),
                       "'rihgt' is not a side"));
}

TEST(BadInput, QuietBoundaryInputSideAmongTheAbsorbingSidesIsRejected) {
  const std::string text = replace(good_model, "[[stage]]",
                                   "[quiet_boundary]\nsides = [\"left\"]\ninput_side = \"left\"\n"
                                   "input_velocity = 0.1\ninput_duration = 1e-5\n[[stage]]");
  EXPECT_TRUE(rejected("quiet_input_twice", text, "quiet_boundary.input_side",
                       line_of(text, "input_side"), "absorbs as well"));
}

TEST(BadInput, NonPositiveAcousticEmissionRadiusIsRejected) {
  const std::string text =
      replace(good_model, "[[stage]]", "[output]\nae_radius = -1e-3\n[[stage]]");
  EXPECT_TRUE(
      rejected("ae_radius", text, "output.ae_radius", line_of(text, "ae_radius"), "must be > 0"));
}

namespace {
// The good model with a [shpb] test instead of its stage.
std::string shpb_model(const std::string& incident_extra = "", const std::string& striker = "0.1") {
  return replace(good_model, "[[stage]]\nplaten_velocity = 0.05\nend_axial_strain = 0.001\n",
                 "[shpb]\nstriker_length = " + striker +
                     "\nstriker_velocity = 5\n[shpb.incident_bar]\nlength = 0.5\n"
                     "diameter = 0.02\nE = 2e11\ndensity = 7800\ngauges = [0.25]\n" +
                     incident_extra + "[shpb.transmitted_bar]\nlength = 0.3\ngauges = [0.15]\n");
}
}  // namespace

TEST(BadInput, PressureBarModelPassesCheck) {
  const Outcome o = run_capture("check " + write_model("shpb_good", shpb_model()).string());
  EXPECT_EQ(o.code, 0) << o.output;
}

TEST(BadInput, PressureBarGaugeOutsideItsBarIsRejected) {
  const std::string text = replace(shpb_model(), "gauges = [0.15]", "gauges = [0.45]");
  EXPECT_TRUE(rejected("shpb_gauge", text, "shpb.transmitted_bar.gauges",
                       line_of(text, "gauges = [0.45]"), "outside its bar"));
}

TEST(BadInput, PressureBarShorterThanThePulseIsRejected) {
  const std::string text = shpb_model("", "0.3");
  EXPECT_TRUE(rejected("shpb_short_bar", text, "shpb.striker_length",
                       line_of(text, "striker_length"), "longer than the incident bar"));
}

TEST(BadInput, PressureBarWithANonPositiveModulusIsRejected) {
  const std::string text = replace(shpb_model(), "E = 2e11", "E = -2e11");
  EXPECT_TRUE(rejected("shpb_modulus", text, "shpb.incident_bar.E", line_of(text, "E = -2e11"),
                       "must be > 0"));
}

TEST(BadInput, PressureBarWithAnUnknownRiseShapeIsRejected) {
  const std::string text =
      replace(shpb_model(), "striker_velocity = 5\n",
              "striker_velocity = 5\nrise_time = 1e-5\nrise_shape = \"sine\"\n");
  EXPECT_TRUE(rejected("shpb_rise_shape", text, "shpb.rise_shape", line_of(text, "rise_shape"),
                       "\"linear\" (a ramp) or \"cosine\""));
}

TEST(BadInput, PressureBarWithStagesIsRejected) {
  const std::string text = shpb_model() + "[[stage]]\nplaten_velocity = 0.05\n";
  EXPECT_TRUE(
      rejected("shpb_stages", text, "stage", line_of(text, "[[stage]]"), "its own load path"));
}

TEST(BadInput, BlockBarsWithAFreeStruckEndAreRejected) {
  const std::string text = replace(shpb_model("far_end = \"free\"\n"), "striker_velocity = 5\n",
                                   "striker_velocity = 5\nbars = \"blocks\"\n");
  EXPECT_TRUE(rejected("shpb_block_free_end", text, "shpb.incident_bar.far_end",
                       line_of(text, "far_end = \"free\""), "enters through the incident bar"));
}

TEST(BadInput, ConfiningRampWithoutConfinementOrWithAnImplicitStartIsRejected) {
  EXPECT_TRUE(
      rejected("ramp_alone",
               replace(good_model, "[[stage]]", "[loading]\nconfining_ramp_time = 1e-3\n[[stage]]"),
               "loading.confining_ramp_time", 15, "give confining_stress too"));
  EXPECT_TRUE(rejected(
      "ramp_implicit",
      replace(replace(good_model, "[[stage]]",
                      "[loading]\nconfining_stress = 5e6\nconfining_ramp_time = 1e-3\n[[stage]]"),
              "end_axial_strain = 0.001", "end_axial_strain = 0.001\nimplicit_start = true"),
      "implicit_start", 20, "leave out loading.confining_ramp_time"));
}

TEST(BadInput, PlatensOtherThanTopOrBothAreRejected) {
  EXPECT_TRUE(
      rejected("platens_bottom",
               replace(good_model, "[[stage]]", "[loading]\nplatens = \"bottom\"\n[[stage]]"),
               "loading.platens", 15, "must be \"top\" or \"both\""));
}

TEST(BadInput, IncidentWaveGivenTwiceOrNotAtAllIsRejected) {
  const std::string twice = replace(shpb_model(), "striker_velocity = 5\n",
                                    "striker_velocity = 5\nincident_stress = 2e8\n");
  EXPECT_TRUE(rejected("shpb_wave_twice", twice, "shpb.incident_stress",
                       line_of(twice, "incident_stress"), "given twice"));
  const std::string none = replace(shpb_model(), "striker_velocity = 5\n", "");
  EXPECT_TRUE(rejected("shpb_wave_none", none, "shpb.striker_velocity", line_of(none, "[shpb]"),
                       "incident_particle_velocity"));
}

namespace {
const char* joint_set = R"([[joint_set]]
dip = 30
spacing = 0.005
friction = 30
)";

fs::path write_fractures(const std::string& name, const std::string& rows) {
  const fs::path file = fs::temp_directory_path() / "vorodec_bad_input" / (name + ".csv");
  fs::create_directories(file.parent_path());
  std::ofstream(file) << rows;
  return file;
}

std::string fracture_model(const fs::path& csv) {
  return std::string(good_model) + "[[joint_set]]\nfile = \"" + csv.string() +
         "\"\nfriction = 30\n";
}
}  // namespace

TEST(BadInput, JointSetSpacingOfZeroIsRejected) {
  EXPECT_TRUE(
      rejected("joint_spacing",
               std::string(good_model) + replace(joint_set, "spacing = 0.005", "spacing = 0"),
               "joint_set[0].spacing", 19, "must be > 0"));
}

TEST(BadInput, JointSetOriginOutsideTheSpecimenIsRejected) {
  EXPECT_TRUE(rejected("joint_origin",
                       std::string(good_model) + joint_set + "origin = [0.5, 0.01]\n",
                       "joint_set[0].origin", 21, "bounding box"));
}

TEST(BadInput, JointSetWithATraceButNoGapIsRejected) {
  EXPECT_TRUE(rejected("joint_gap", std::string(good_model) + joint_set + "trace = 0.01\n",
                       "joint_set[0].gap", 17, "required"));
}

TEST(BadInput, FractureFileWithABadRowIsRejectedWithItsLine) {
  const fs::path csv =
      write_fractures("bad_row", "x1,y1,x2,y2\n0,0.01,0.02,0.03\n0,0.02,abc,0.03\n");
  const Outcome o = run_capture("check " + write_model("bad_row", fracture_model(csv)).string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(csv.string() + ":3:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("'abc'"), std::string::npos) << o.output;
}

TEST(BadInput, FractureOutsideTheSpecimenIsRejectedWithItsLine) {
  const fs::path csv = write_fractures("outside", "x1,y1,x2,y2\n0.5,0.5,0.6,0.7\n");
  const Outcome o = run_capture("check " + write_model("outside", fracture_model(csv)).string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(csv.string() + ":2:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("outside the specimen"), std::string::npos) << o.output;
}

TEST(BadInput, FractureRowNamingAnUnknownSetIsRejected) {
  const fs::path csv = write_fractures("unknown_set", "x1,y1,x2,y2,set\n0,0.01,0.02,0.03,faults\n");
  const Outcome o =
      run_capture("check " + write_model("unknown_set", fracture_model(csv)).string());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(csv.string() + ":2:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("'faults'"), std::string::npos) << o.output;
}

namespace {
std::string excavation(const std::string& shape) {
  return std::string(good_model) + "[[stage]]\nname = \"dig\"\ncontrol = \"excavation\"\n" + shape +
         "\ntarget_stress = 1e6\nend_time = 0.01\n";
}
}  // namespace

TEST(BadInput, ExcavationOutsideTheSpecimenIsRejected) {
  EXPECT_TRUE(rejected("excavation_outside",
                       excavation("circle = { centre = [0.01, 0.02], radius = 0.05 }"),
                       "stage[1].circle", 20, "inside the specimen"));
}

TEST(BadInput, OverlappingExcavationsAreRejected) {
  const std::string first = excavation("circle = { centre = [0.01, 0.02], radius = 0.004 }");
  const std::string both = first +
                           "[[stage]]\nname = \"again\"\ncontrol = \"excavation\"\n"
                           "polygon = [[0.008, 0.018], [0.015, 0.018], [0.015, 0.03]]\n"
                           "target_stress = 1e6\nend_time = 0.01\n";
  EXPECT_TRUE(rejected("excavation_overlap", both, "stage[2].polygon", 26, "overlaps stage 'dig'"));
}

TEST(BadInput, ExcavationCircleWithoutCentreIsRejected) {
  EXPECT_TRUE(rejected("excavation_centre", excavation("circle = { radius = 0.004 }"),
                       "stage[1].circle.centre", 20, "required"));
}

TEST(BadInput, InSituStressThatTheModelCannotHoldIsRejected) {
  const std::string in_situ = "[in_situ]\nstress = [5e6, 10e6, 0.0]\n";
  EXPECT_TRUE(rejected("in_situ_two_numbers",
                       std::string(good_model) + "[in_situ]\nstress = [5e6, 10e6]\n",
                       "in_situ.stress", 18, "three numbers"));
  EXPECT_TRUE(rejected("in_situ_confined",
                       replace(std::string(good_model) + in_situ, "[[stage]]",
                               "[loading]\nconfining_stress = 1e6\n[[stage]]"),
                       "in_situ.stress", 20, "remove loading.confining_stress"));
  EXPECT_TRUE(rejected("in_situ_shear",
                       std::string(good_model) + "[in_situ]\nstress = [5e6, 10e6, 1e6]\n",
                       "in_situ.stress", 18, "bonded = true"));
  const std::string creep = replace(std::string(good_model) + in_situ,
                                    "jkn = 2e13\njks = 8e12\ntension = 10e6\ncohesion = 20e6\n"
                                    "friction = 30",
                                    "law = \"burgers\"\nkmn = 2e13\ncmn = 1e15\nkkn = 2e13\n"
                                    "ckn = 1e14\nkms = 8e12\ncms = 1e15\nkks = 8e12\ncks = 1e14\n"
                                    "tension = 10e6\ncohesion = 20e6\nfriction = 30");
  EXPECT_TRUE(rejected("in_situ_burgers", creep, "in_situ.stress", 25, "cannot start loaded"));
}

TEST(BadInput, SideSupportsThatContradictTheLoadingAreRejected) {
  const std::string loading = "[loading]\nsides = \"rollers\"\n[[stage]]";
  EXPECT_TRUE(rejected("sides_typo", replace(good_model, "[[stage]]", loading), "loading.sides", 15,
                       "\"stress\", \"roller\" or \"fixed\""));
  EXPECT_TRUE(rejected("sides_confined",
                       replace(good_model, "[[stage]]",
                               "[loading]\nconfining_stress = 1e6\nsides = \"roller\"\n[[stage]]"),
                       "loading.sides", 16, "no confining_stress"));
  EXPECT_TRUE(rejected("sides_viscous",
                       replace(good_model, "[[stage]]",
                               "[loading]\nsides = \"fixed\"\n[quiet_boundary]\n"
                               "sides = [\"left\"]\n[[stage]]"),
                       "quiet_boundary.sides", 17, "not viscous too"));
}

TEST(BadInput, GradualReleaseOfZonedBlocksIsRejected) {
  const std::string zoned = replace(
      excavation("circle = { centre = [0.01, 0.02], radius = 0.004 }\nrelaxation_time = 0.005"),
      "density = 2600",
      "density = 2600\ndeformable = true\nzone_size = 0.004\nE = 50e9\nnu = 0.25");
  EXPECT_TRUE(rejected("excavation_zoned_relaxation", zoned, "stage[1].relaxation_time", 25,
                       "rigid blocks"));
}
