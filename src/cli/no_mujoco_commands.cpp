// Built without MuJoCo: no generate, compare, report, solref, atlas or inspect subcommand (see
// mujoco_commands.cpp).
#include "cli/common.hpp"

namespace contact2d::cli {

std::vector<Command> add_mujoco_commands(CLI::App&) { return {}; }

}  // namespace contact2d::cli
