// models/<scene>.<mapping>.xml are the generator's output for the four
// built-in scenes: regenerating them must give the same bytes, and each must
// load in MuJoCo 2.2.2 with no error and no warning (load_model throws on
// either, and the compiler takes one test step, so a bad model warns here).
#include <fstream>
#include <sstream>

#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d {
namespace {

struct ModelCase {
  std::string scene;
  mujoco::Mapping mapping;
};

std::string read_stored(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void PrintTo(const ModelCase& c, std::ostream* os) {
  *os << c.scene << "." << mujoco::mapping_name(c.mapping);
}

class Models : public ::testing::TestWithParam<ModelCase> {};

TEST_P(Models, RegenerateToTheSameBytesAndLoadWithoutWarning) {
  const ModelCase& c = GetParam();
  const std::string scene_path = "validation/scenes/" + c.scene + ".toml";
  const std::string model_path =
      "models/" + c.scene + "." + std::string(mujoco::mapping_name(c.mapping)) + ".xml";
  mujoco::MjcfOptions options;
  options.mapping = c.mapping;
  options.source =
      scene_path;  // as `contact2d generate` names it when run from the repository root
  const Scene scene = load_scene(test::source_dir() + "/" + scene_path);
  const std::string generated = mujoco::generate_mjcf(scene, options).xml;
  const std::string stored = read_stored(test::source_dir() + "/" + model_path);
  EXPECT_EQ(generated, stored)
      << model_path
      << " is out of date: regenerate it with scripts/demo (or from the repository "
         "root: contact2d generate "
      << scene_path << " --mapping " << mujoco::mapping_name(c.mapping) << " -o " << model_path
      << ")";
  EXPECT_NO_THROW(mujoco::load_model(stored, model_path));
}

std::vector<ModelCase> model_cases() {
  std::vector<ModelCase> out;
  for (const char* scene : {"point_mass", "box", "tshape", "circle"}) {
    for (mujoco::Mapping mapping : mujoco::kAllMappings) out.push_back({scene, mapping});
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenes, Models, ::testing::ValuesIn(model_cases()),
                         [](const ::testing::TestParamInfo<ModelCase>& info) {
                           return info.param.scene + "_" +
                                  std::string(mujoco::mapping_name(info.param.mapping));
                         });

}  // namespace
}  // namespace contact2d
