// A stage mode and a driver bring their own model-file keys (docs/extending.md): the reader hands a
// stage whose control names a mode to the mode's reader, and a driver's table to the driver's, and
// still reports any key nobody asked for with its file and line. A mode and a driver defined here,
// as a new one would be, are read without a line of src/input/ knowing them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/input/toml_section.hpp"

namespace fs = std::filesystem;
using namespace vorodec;

namespace {

// A "relax" stage: the platen stops and the specimen relaxes for `relax_time` seconds.
struct RelaxSettings final : loading::ExtensionSettings {
  double damping = 0;
};

std::shared_ptr<const loading::ExtensionSettings> read_relax_stage(io::TomlSection& sec,
                                                                   loading::Stage& st,
                                                                   const io::ModelConfig&) {
  auto s = std::make_shared<RelaxSettings>();
  st.control = loading::Control::platen_velocity;
  st.end.duration = sec.positive("relax_time", laws::required);
  s->damping = sec.positive("relax_damping", 0.8);
  return s;
}

// A "[pull]" test: a load path of its own.
struct PullSettings final : loading::ExtensionSettings {
  double speed = 0;
};

std::shared_ptr<const loading::ExtensionSettings> read_pull(io::TomlSection& sec, io::TomlSection&,
                                                            const io::ModelConfig&) {
  auto s = std::make_shared<PullSettings>();
  s->speed = sec.positive("speed", laws::required);
  return s;
}

constexpr std::array kModes{io::StageModeKeys{"relax", nullptr, nullptr, read_relax_stage}};
constexpr std::array kDrivers{io::DriverKeys{"pull", read_pull}};
const io::ModelFileKeys kKeys{kModes, kDrivers};

const std::string base_model = std::string(VORODEC_SOURCE_DIR) + "/tests/models/e2e_small.toml";

fs::path write(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("vorodec_plug_in_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << "base = \"" << base_model << "\"\n" << text;
  return dir / name;
}

// The reader's message for `file`, read with `keys` (nullptr: the registered ones, as a run).
std::string error_of(const fs::path& file, const io::ModelFileKeys* keys = &kKeys) {
  try {
    if (keys)
      io::read_model_file(file, {}, *keys);
    else
      run::read_model_file(file);
  } catch (const io::ModelFileError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(PlugInKeys, AStageNamingAModeIsReadByTheModesOwnReader) {
  const io::ModelConfig cfg = io::read_model_file(
      write("relax.toml",
            "[[stage]]\nname = \"rest\"\ncontrol = \"relax\"\nrelax_time = 0.5\n"
            "relax_damping = 0.3\n"),
      {}, kKeys);
  ASSERT_EQ(cfg.load_path.stages.size(), 1u);
  const loading::Stage& st = cfg.load_path.stages[0];
  EXPECT_EQ(st.name, "rest");
  EXPECT_EQ(st.mode, "relax");
  EXPECT_EQ(st.end.duration, 0.5);
  EXPECT_EQ(static_cast<const RelaxSettings&>(*st.mode_settings).damping, 0.3);
}

TEST(PlugInKeys, AModesMisspelledKeyIsReportedWithItsLine) {
  const std::string e = error_of(
      write("typo.toml", "[[stage]]\ncontrol = \"relax\"\nrelax_time = 0.5\nrelax_dampin = 0.3\n"));
  EXPECT_NE(e.find("typo.toml:5: key 'stage[0].relax_dampin'"), std::string::npos) << e;
  EXPECT_NE(e.find("relax_damping"), std::string::npos) << e;  // the "did you mean"
}

TEST(PlugInKeys, AnUnknownControlListsTheRegisteredModes) {
  const std::string e =
      error_of(write("bogus.toml", "[[stage]]\ncontrol = \"creep\"\nend_time = 1\n"));
  EXPECT_NE(e.find("\"stress_rate\", \"relax\" or \"cyclic\" (got \"creep\")"), std::string::npos)
      << e;
}

TEST(PlugInKeys, ADriversTableIsItsLoadPathAndReplacesTheBaseStages) {
  const io::ModelConfig cfg =
      io::read_model_file(write("pull.toml", "[pull]\nspeed = 0.2\n"), {}, kKeys);
  EXPECT_TRUE(cfg.load_path.stages.empty());
  const auto* pull = io::table_settings<PullSettings>(cfg, "pull");
  ASSERT_NE(pull, nullptr);
  EXPECT_EQ(pull->speed, 0.2);
  const std::string e = error_of(
      write("both.toml", "[pull]\nspeed = 0.2\n[[stage]]\nplaten_velocity = 1\nend_time = 1\n"));
  EXPECT_NE(e.find("a [pull] test is its own load path"), std::string::npos) << e;
}

TEST(PlugInKeys, TheRegisteredModesAndDriversAreTheOnesARunReads) {
  const std::string e = error_of(write("run.toml", "[[stage]]\ncontrol = \"relax\"\n"), nullptr);
  EXPECT_NE(e.find("\"creep\", \"corrosion\", \"excavation\" or \"cyclic\" (got \"relax\")"),
            std::string::npos)
      << e;
}
