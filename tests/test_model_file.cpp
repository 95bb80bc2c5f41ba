// Model files that start from a base model file (`base = "..."`): tables merge key by key, the
// derived file's values win, and its stage list replaces the base's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "vorodec/drivers/registry.hpp"
#include "vorodec/input/model_file.hpp"

namespace fs = std::filesystem;
using namespace vorodec;

namespace {
fs::path write(const std::string& name, const std::string& text) {
  const fs::path dir =
      fs::temp_directory_path() / ("vorodec_model_file_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}
const std::string base_model = std::string(VORODEC_SOURCE_DIR) + "/tests/models/e2e_small.toml";
}  // namespace

TEST(ModelFile, DerivedModelOverridesKeysAndKeepsTheRestOfItsBase) {
  const io::ModelConfig base = run::read_model_file(base_model);
  const io::ModelConfig d = run::read_model_file(
      write("derived.toml", "base = \"" + base_model +
                                "\"\ntitle = \"derived\"\n[joints]\nfriction = 31.0\n"
                                "[loading]\nconfining_stress = 5e6\n"));
  EXPECT_EQ(d.title, "derived");
  EXPECT_EQ(d.joints.params.at("friction").value, 31.0);
  EXPECT_EQ(d.joints.params.at("jkn").value, base.joints.params.at("jkn").value);
  EXPECT_EQ(d.load_path.confining_stress, 5e6);
  EXPECT_EQ(d.tessellation.block_count, base.tessellation.block_count);
  ASSERT_EQ(d.load_path.stages.size(), base.load_path.stages.size());
}

TEST(ModelFile, DerivedStageListReplacesTheBaseStages) {
  const io::ModelConfig d = run::read_model_file(
      write("stages.toml", "base = \"" + base_model +
                               "\"\n[[stage]]\nname = \"a\"\nplaten_velocity = 0.01\n"
                               "end_axial_strain = 1e-3\n[[stage]]\nname = \"b\"\n"
                               "platen_velocity = 0.01\nend_axial_strain = 2e-3\n"));
  ASSERT_EQ(d.load_path.stages.size(), 2u);
  EXPECT_EQ(d.load_path.stages[1].name, "b");
}

TEST(ModelFile, MissingBaseFileIsNamedWithItsLine) {
  try {
    run::read_model_file(write("nobase.toml", "seed = 1\nbase = \"no_such_base.toml\"\n"));
    FAIL() << "accepted a missing base file";
  } catch (const io::ModelFileError& e) {
    EXPECT_NE(std::string(e.what()).find("nobase.toml:2: key 'base': no such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(ModelFile, ErrorInADerivedFileNamesItsOwnLine) {
  try {
    run::read_model_file(
        write("derived_bad.toml", "base = \"" + base_model +
                                      "\"\n[[stage]]\nplaten_velocity = 0.01\n"
                                      "end_axial_strain = 1e-3\nramp_time = -1\n"));
    FAIL() << "accepted a negative ramp_time";
  } catch (const io::ModelFileError& e) {
    EXPECT_NE(std::string(e.what()).find("derived_bad.toml:5: key 'stage[0].ramp_time'"),
              std::string::npos)
        << e.what();
  }
}

TEST(ModelFile, MarbleModelsShareTheUcsModelsContacts) {
  const std::string dir = std::string(VORODEC_SOURCE_DIR) + "/models/";
  const io::ModelConfig ucs = run::read_model_file(dir + "ucs_marble.toml");
  for (const char* other : {"brazilian_marble.toml", "tension_marble.toml", "cyclic_marble.toml",
                            "triaxial_marble.toml"}) {
    const io::ModelConfig m = run::read_model_file(dir + other);
    EXPECT_EQ(m.density, ucs.density) << other;
    EXPECT_EQ(m.rounding_length, ucs.rounding_length) << other;
    ASSERT_EQ(m.joints.params.size(), ucs.joints.params.size()) << other;
    for (const auto& [key, d] : ucs.joints.params) {
      EXPECT_EQ(m.joints.params.at(key).value, d.value) << other << " " << key;
      EXPECT_EQ(m.joints.params.at(key).weibull_shape, d.weibull_shape) << other << " " << key;
    }
  }
}
