// Running a scene on a named engine: "ref" (the reference solver) or
// "mujoco" (through the MuJoCo adapter, when built with it).
#pragma once

#include <string>

#include "cli/common.hpp"

namespace contact2d::cli {

// Throws InputError for an unknown or unavailable engine, or a scene the
// engine cannot load.
EngineRun run_engine(const std::string& engine, const Scene& scene);

}  // namespace contact2d::cli
