#include "cli/mujoco_engine.hpp"

#include "io/scene_file.hpp"
#include "mujoco/adapter.hpp"

namespace contact2d::cli {

void MujocoOptions::add_to(CLI::App& cmd) {
  cmd.add_option("--mapping", mapping,
                 "solref/solimp mapping: seed | exact | calibrated (default calibrated)")
      ->check(CLI::IsMember({"seed", "exact", "calibrated"}));
  cmd.add_option("--geometry", geometry,
                 "MuJoCo geoms of a box or T: corners (a small sphere per 2D contact point, "
                 "default) | boxes")
      ->check(CLI::IsMember({"corners", "boxes"}));
}

contact2d::mujoco::MjcfOptions MujocoOptions::resolve(const std::string& source) const {
  contact2d::mujoco::MjcfOptions options;
  options.mapping = *contact2d::mujoco::parse_mapping(mapping);  // checked by CLI11
  options.geometry = *contact2d::mujoco::parse_geometry(geometry);
  options.source = source;
  return options;
}

EngineRun run_mujoco_engine(const Scene& scene, const contact2d::mujoco::MjcfOptions& options,
                            contact2d::mujoco::SolverSettings* settings) {
  contact2d::mujoco::MujocoRun mj = contact2d::mujoco::run_mujoco(scene, options);
  if (settings) *settings = mj.settings;
  EngineRun run;
  run.trajectory = std::move(mj.trajectory);
  run.seconds = mj.seconds;
  run.warnings = std::move(mj.warnings);
  return run;
}

}  // namespace contact2d::cli
