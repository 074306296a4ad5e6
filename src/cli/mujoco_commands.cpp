// The subcommands that need MuJoCo: compare, report, solref, inspect,
// generate, atlas. CMake builds this file when MuJoCo is found and
// no_mujoco_commands.cpp otherwise, so main.cpp has no #ifdef.
#include "cli/common.hpp"

namespace contact2d::cli {

std::optional<Command> add_mujoco_command(CLI::App& app, std::string_view name) {
  if (name == "compare") return add_compare(app);
  if (name == "report") return add_report(app);
  if (name == "solref") return add_solref(app);
  if (name == "inspect") return add_inspect(app);
  if (name == "generate") return add_generate(app);
  if (name == "atlas") return add_atlas(app);
  return std::nullopt;
}

}  // namespace contact2d::cli
