// The engine registry: the one place that turns an engine's name into a
// Stepper (core/stepper.hpp) and runs it through the one run loop
// (core/run.hpp) into one result type. Every command, the analysis, the
// report and the game get their engines here. The registry is a list of
// descriptors (core/engine_info.hpp), one line per engine; it is the only
// code outside CMake and the engines' own folders that knows which engines
// exist and whether MuJoCo was built in.
//
//   ref                        the reference solver with the scene's integrator
//   mujoco                     MuJoCo, default mapping (calibrated) and geometry (corners)
//   mujoco:MAPPING             MAPPING = seed | exact | calibrated (mujoco/mapping.hpp)
//   mujoco:MAPPING:GEOMETRY    GEOMETRY = corners | boxes (mujoco/mjcf.hpp); an empty
//                              MAPPING ("mujoco::boxes") is the default mapping
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/engine_info.hpp"
#include "core/run.hpp"

namespace contact2d::engines {

// Parses a name of the table above. `option` names where it came from in
// the error ("--engine", "--engines"). Throws InputError for an unknown
// name, mapping or geometry, or MuJoCo when it was not built in.
EngineSpec parse_engine(const std::string& name, const std::string& option = "--engine");

bool mujoco_available();

// The names a user can give: ref, and with MuJoCo mujoco and mujoco:MAPPING
// for every mapping (geometry variants left out of the list).
std::vector<std::string> engine_names();
// The same list in prose for a help text: "ref, mujoco, mujoco:MAPPING
// (seed, exact, calibrated, compensated; mujoco = its default)".
std::string engine_names_help();

// The result of running one engine on one scene.
struct EngineRun {
  std::string engine;       // EngineSpec::name()
  std::string description;  // Stepper::describe(), e.g. "mujoco calibrated Euler"
  Trajectory trajectory;    // samples every output_dt; divergence if it stopped
  double seconds = 0.0;     // wall clock of the run loop (model building excluded)
  // When the run diverged: why, and what to try, in the engine's own terms
  // (Stepper::explain); empty otherwise.
  std::string divergence_message;
  std::vector<std::string> warnings;  // anything the engine warned about
  // Facts about the run that are not failures, e.g. "refsafe" when MuJoCo
  // raised a standard-form timeconst to 2·Δt (a softer contact than asked).
  std::vector<std::string> notes;
  // The model values of Stepper::facts the outputs print, NaN when the
  // engine gives none (the reference). MuJoCo: solref and impratio of the
  // generated model.
  std::array<double, 2> solref{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};
  double impratio = std::numeric_limits<double>::quiet_NaN();
  // MuJoCo: the rolling coefficient the model writes (compensated's
  // μ_roll' for a disc); NaN for the reference.
  double mu_roll = std::numeric_limits<double>::quiet_NaN();
};

// An engine with options given one by one (the command line's --mapping,
// the Python module's mapping=), as (name, value) pairs; an empty value is
// left out. `spelled("mapping")` is how the caller's user wrote an option
// ("--mapping", "mapping ="), to start an error. Throws InputError for an
// unknown engine, an option the engine does not take, a value it does not
// accept, one its name (`kind` may carry options: "mujoco:exact") gives
// already, or a model_dt for an engine without Δt-dependent model values.
using OptionValues = std::vector<std::pair<std::string, std::string>>;
EngineSpec engine_with_options(const std::string& kind, const OptionValues& given, double model_dt,
                               const std::string& source,
                               const std::function<std::string(std::string_view)>& spelled);

// The value of option `name` of the spec's engine: the one given, else its
// fallback; empty when the engine has no such option.
std::string option_value(const EngineSpec& spec, std::string_view name);

// A stepper at the scene's initial state. Throws InputError when the engine
// cannot run the scene (MuJoCo: a model it cannot load, explicit Euler).
std::unique_ptr<Stepper> make_stepper(const EngineSpec& spec, const Scene& scene);

// Throws InputError when the engine cannot run the scene (EngineInfo::check),
// without building anything.
void check_runs(const EngineSpec& spec, const Scene& scene);

// make_stepper + run loop, timed.
EngineRun run_engine(const EngineSpec& spec, const Scene& scene);
EngineRun run_engine(const std::string& name, const Scene& scene);

// The registry: every engine, built in or not, in the order of the lists
// (engine_names, the help's "ref | mujoco").
const std::vector<const EngineInfo*>& engine_list();

// The descriptor of an engine name ("mujoco:seed": MuJoCo's); nullptr for
// an unknown one.
const EngineInfo* find_engine(std::string_view name);

// Every engine's kind, built in or not: the values of simulate's --engine.
std::vector<std::string> engine_kinds();

// Whether an engine offers the integrator: MuJoCo 2.2 has no explicit Euler.
// A name the registry does not know offers what every engine offers.
bool engine_offers(const std::string& name, Integrator integrator);

// One set of integrator names across engines: every option value and every
// label uses the scene's names (integrator_name: "semi_implicit_euler", …);
// where an engine has its own name for it, that follows in parentheses with
// the engine's title: "rk4" for the reference, "rk4 (MuJoCo RK4)" for MuJoCo.
std::string integrator_label(const std::string& engine, Integrator integrator);

// The engine's own name of the integrator (EngineInfo::integrator_title:
// "Euler" for MuJoCo's semi-implicit Euler), else the scene's name.
std::string own_integrator_name(const std::string& engine, Integrator integrator);

// The integrator the engine's contact forces are integrated with when it
// runs `integrator` (the stability limit that applies): the same one, but
// semi-implicit Euler for MuJoCo's implicit.
Integrator contact_integrator(const std::string& engine, Integrator integrator);

}  // namespace contact2d::engines
