// What the registry (engines/engines.hpp) knows of one engine, as data: its
// name, its title, the integrators it offers and its own names for them,
// the options its name may carry, and how to make its Stepper. Each engine
// describes itself in its own folder (mujoco/engine.hpp); the reference,
// whose stepper is the core's, is described in the registry. The registry
// is the list of these descriptors, so nothing outside an engine's folder
// and the registry needs to know which engines exist.
// It is a core type because every engine's folder, below the registry in
// the layers (docs/architecture.md), fills one.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/integrators.hpp"
#include "core/scene.hpp"

namespace contact2d {
class Stepper;
}

namespace contact2d::engines {

// One engine to run: what --engine names, parsed. The option fields are the
// engine's own (MuJoCo's mapping and geometry, mujoco/engine.hpp); an engine
// without options leaves them empty.
struct EngineSpec {
  std::string kind = "ref";  // EngineInfo::kind
  std::string mapping;       // MuJoCo: empty = the default mapping
  std::string geometry;      // MuJoCo: empty = the default geometry
  std::string source;        // the scene file, named in a generated model's header
  // MuJoCo: the Δt its model's Δt-dependent values are computed for (0: the
  // scene's timestep; mujoco/mjcf.hpp MjcfOptions::model_dt).
  double model_dt = 0.0;

  std::string name() const;  // back to "mujoco:exact" etc.
};

struct EngineInfo {
  std::string_view kind;   // the name before any ':' ("ref", "mujoco")
  std::string_view title;  // the engine's name in prose ("MuJoCo")
  // How to make its Stepper at the scene's initial state; nullptr when the
  // engine was not built in (parse_engine then says so).
  std::unique_ptr<Stepper> (*make)(const EngineSpec& spec, const Scene& scene) = nullptr;
  // Whether it offers the integrator; nullptr: every one.
  bool (*offers)(Integrator integrator) = nullptr;
  // Its own name of the integrator that runs this one, shown after the
  // scene's name ("semi_implicit_euler (MuJoCo Euler)"); nullptr or empty:
  // the scene's name alone.
  std::string_view (*integrator_title)(Integrator integrator) = nullptr;
  // The integrator its contact forces are integrated with when it runs this
  // one (the stability limit that applies); nullptr: the same one.
  Integrator (*contact_integrator)(Integrator integrator) = nullptr;
  // Reads the options after "kind:" into `spec`; `context` ("--engine
  // mujoco:x") starts any InputError. nullptr: the name takes no options.
  void (*parse_options)(const std::string& options, const std::string& context,
                        EngineSpec& spec) = nullptr;
  // The names with options that engine_names lists after `kind`.
  std::vector<std::string> (*variants)() = nullptr;
};

}  // namespace contact2d::engines
