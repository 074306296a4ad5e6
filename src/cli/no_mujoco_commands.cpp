// Built without MuJoCo: no compare, report, solref, inspect, generate or atlas
// subcommand (see mujoco_commands.cpp).
#include "cli/common.hpp"

namespace contact2d::cli {

std::optional<Command> add_mujoco_command(CLI::App&, std::string_view) { return std::nullopt; }

}  // namespace contact2d::cli
