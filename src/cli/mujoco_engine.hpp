// The MuJoCo side of the command line: --mapping / --geometry options and a
// run of the MuJoCo engine as an EngineRun.
#pragma once

#include <string>

#include "cli/common.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d::cli {

struct MujocoOptions {
  std::string mapping{contact2d::mujoco::mapping_name(contact2d::mujoco::kDefaultMapping)};
  std::string geometry{contact2d::mujoco::geometry_name(contact2d::mujoco::kDefaultGeometry)};

  void add_to(CLI::App& cmd);
  contact2d::mujoco::MjcfOptions resolve(const std::string& source) const;
};

// Runs the scene in MuJoCo; the solver settings used go into `settings`
// when given. Throws InputError when the scene cannot be mapped or loaded.
EngineRun run_mujoco_engine(const Scene& scene, const contact2d::mujoco::MjcfOptions& options,
                            contact2d::mujoco::SolverSettings* settings = nullptr);

}  // namespace contact2d::cli
