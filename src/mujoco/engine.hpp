// MuJoCo as an engine of the registry (engines/engines.hpp): its name and
// options (mujoco[:MAPPING[:GEOMETRY]]), its names of the integrators, and
// the MujocoStepper (mujoco/stepper.hpp) it runs a scene with. The registry
// lists engine_info() and knows nothing else of MuJoCo.
#pragma once

#include "core/engine_info.hpp"

namespace contact2d::mujoco {

// MuJoCo 2.2's name of the integrator that runs this one ("Euler",
// "implicit", "RK4", as in MJCF's <option integrator>); empty for explicit
// Euler, which MuJoCo 2.2 lacks.
std::string_view integrator_title(Integrator integrator);

const engines::EngineInfo& engine_info();

}  // namespace contact2d::mujoco
