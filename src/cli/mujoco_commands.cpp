// The subcommands that need MuJoCo: generate, compare, report, solref, atlas,
// inspect. CMake builds this file when MuJoCo is found and
// no_mujoco_commands.cpp otherwise, so main.cpp has no #ifdef.
#include "cli/common.hpp"

namespace contact2d::cli {

std::vector<Command> add_mujoco_commands(CLI::App& app) {
  return {add_generate(app), add_compare(app), add_report(app),
          add_solref(app),   add_atlas(app),   add_inspect(app)};
}

}  // namespace contact2d::cli
