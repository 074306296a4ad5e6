// MuJoCo 3 as an engine of the registry (engines/engines.hpp): the kind
// "mujoco3", MuJoCo's options (mujoco3[:MAPPING[:GEOMETRY]]) and integrator
// names, and the Mujoco3Stepper (mujoco3/stepper.hpp) it runs a scene with.
#pragma once

#include "core/engine_info.hpp"

namespace contact2d::mujoco3 {

const engines::EngineInfo& engine_info();

}  // namespace contact2d::mujoco3
