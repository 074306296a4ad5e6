// One set of integrator names across engines: every option value and every
// label uses the scene's names (integrator_name: "semi_implicit_euler", …);
// where MuJoCo runs, MuJoCo's own name follows in parentheses:
// "semi_implicit_euler (MuJoCo Euler)".
#pragma once

#include <string>
#include <string_view>

#include "core/integrators.hpp"

namespace contact2d {

// MuJoCo 2.2's name of the integrator that runs this one ("Euler", "implicit",
// "RK4", as in MJCF's <option integrator>); empty for explicit Euler, which
// MuJoCo 2.2 lacks.
inline std::string_view mujoco_integrator_title(Integrator integrator) {
  switch (integrator) {
    case Integrator::SemiImplicitEuler: return "Euler";
    case Integrator::ImplicitEuler: return "implicit";
    case Integrator::RK4: return "RK4";
    case Integrator::ExplicitEuler: break;
  }
  return {};
}

// "rk4" for the reference; "rk4 (MuJoCo RK4)" where MuJoCo runs.
inline std::string integrator_label(Integrator integrator, bool mujoco) {
  std::string label(integrator_name(integrator));
  const std::string_view own = mujoco_integrator_title(integrator);
  if (mujoco && !own.empty()) label += " (MuJoCo " + std::string(own) + ")";
  return label;
}

// An engine name of --engine/--engines ("ref", "mujoco", "mujoco:seed") runs MuJoCo.
inline bool is_mujoco_engine(std::string_view engine) { return engine.rfind("mujoco", 0) == 0; }

}  // namespace contact2d
