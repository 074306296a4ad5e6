// contact2d generate SCENE [-o FILE] [--engine mujoco|mujoco3] [--mapping NAME]
//   [--geometry NAME] [--friction shared|damper] [overrides]
#include <iostream>
#include <memory>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco3/node_mujoco.hpp"

namespace contact2d::cli {
namespace {

struct GenerateOptions {
  SceneOptions scene;
  EngineOptions engine_options;  // MuJoCo's --mapping, --geometry, --model-dt
  std::string output;
  OutputOptions outputs;          // -o
  std::string engine = "mujoco";  // the MuJoCo it is written for
};

int generate(const GenerateOptions& options) {
  options.outputs.check();
  const Scene scene = options.scene.load();
  std::unique_ptr<AtomicFile> out;
  if (!options.output.empty()) out = std::make_unique<AtomicFile>(options.output);
  contact2d::mujoco::MjcfOptions mjcf =
      contact2d::mujoco::mjcf_options(options.engine_options.value("mapping"),
                                      options.engine_options.value("geometry"), options.scene.path);
  mjcf.model_dt = options.engine_options.model_dt;
  mjcf.friction_damper = options.engine_options.value("friction") == "damper";
  if (options.engine == "mujoco3") mjcf.version = contact2d::mujoco::Version::V3;
  const auto model = contact2d::mujoco::generate_mjcf(scene, mjcf);
  // MuJoCo 2.2.2 checked it in generate_mjcf; MuJoCo 3's is checked by MuJoCo 3.
  if (options.engine == "mujoco3") {
    const auto node = contact2d::mujoco3::Node::of_this_thread();
    node->free(node->load(model.xml, contact2d::mujoco::generated_origin(options.scene.path)).id);
  }
  if (model.settings.refsafe_clamped) {
    std::cerr << "contact2d: note: timeconst " << format_number(model.settings.solref[0])
              << " s < 2 dt: MuJoCo raises it to 2 dt (refsafe), a softer contact than contact.k\n";
  }
  if (!out) {
    std::cout << model.xml;
    return kExitOk;
  }
  std::fputs(model.xml.c_str(), out->get());
  out->commit();
  // One line on what was written (to standard output, where the model goes
  // without -o).
  std::cout << "contact2d generate: wrote " << options.output << ": the MJCF model of "
            << options.scene.path << " for "
            << (options.engine == "mujoco3" ? "MuJoCo 3.14" : "MuJoCo 2.2.2") << " (mapping "
            << contact2d::mujoco::mapping_name(mjcf.mapping) << ", geometry "
            << contact2d::mujoco::geometry_name(mjcf.geometry) << "; " << model.xml.size()
            << " bytes)\n";
  return kExitOk;
}

}  // namespace

Command add_generate(CLI::App& app) {
  auto options = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand("generate", "Write the MuJoCo MJCF model of a scene");
  options->scene.add_to(*cmd);
  options->outputs.input("scene file", options->scene.path);
  options->engine_options.add_to(*cmd);
  cmd->add_option("--engine", options->engine,
                  "The MuJoCo the model is for: mujoco (2.2.2) or mujoco3 (3.14: the model that "
                  "engine runs, checked by MuJoCo 3)")
      ->type_name("KIND")
      ->check(CLI::IsMember({"mujoco", "mujoco3"}));
  options->outputs.file(*cmd, "-o,--output", options->output,
                        "Write the MJCF to this file (default: standard output)", "FILE.xml");
  return {cmd, [options] { return generate(*options); }};
}

}  // namespace contact2d::cli
