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

#include <algorithm>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/integrators.hpp"
#include "core/scene.hpp"

namespace contact2d {
class Stepper;
}

namespace contact2d::engines {

// One option an engine's name may carry after its kind, as data: the
// registry parses "kind:VALUE[:VALUE…]" by position against the engine's
// options, names them in its errors and lists, and the command line and
// the Python module offer each one as --NAME / NAME= with these values.
struct EngineOption {
  std::string_view name;  // "mapping": the flag --mapping, the key in EngineSpec
  std::string_view what;  // prose before the values in the help ("solref/solimp mapping")
  std::vector<std::string_view> values;  // the accepted values, in the order the help lists
  std::string_view fallback;             // the value an option left out takes
};

// One engine to run: what --engine names, parsed. `options` are the
// engine's own (EngineInfo::options) by name; one left out takes its
// fallback, and an engine without options has none.
struct EngineSpec {
  std::string kind = "ref";                                  // EngineInfo::kind
  std::vector<std::pair<std::string, std::string>> options;  // (name, value); name() orders them
  std::string source;  // the scene file, named in a generated model's header
  // The Δt the engine's Δt-dependent model values are computed for (0: the
  // scene's timestep), for an engine whose model depends on Δt
  // (EngineInfo::model_dt_help non-empty).
  double model_dt = 0.0;

  // The value given for option `name`; empty when it was left out.
  std::string option(std::string_view option_name) const {
    for (const auto& [key, value] : options)
      if (key == option_name) return value;
    return {};
  }
  // Gives option `name` the value (empty: leaves it out). The registry
  // checks names and values where a user gives them (parse_engine,
  // engine_with_options); code that sets one names an option it knows.
  void set(std::string_view option_name, const std::string& value) {
    options.erase(std::remove_if(options.begin(), options.end(),
                                 [&](const auto& o) { return o.first == option_name; }),
                  options.end());
    if (!value.empty()) options.emplace_back(std::string(option_name), value);
  }
  // Back to "mujoco:exact" etc. (the registry's: it orders the options as
  // the engine does).
  std::string name() const;
};

struct EngineInfo {
  std::string_view kind;   // the name before any ':' ("ref", "mujoco")
  std::string_view title;  // the engine's name in tables and prose ("ref", "MuJoCo")
  // How to make its Stepper at the scene's initial state; nullptr when the
  // engine was not built in (parse_engine then says so).
  std::unique_ptr<Stepper> (*make)(const EngineSpec& spec, const Scene& scene) = nullptr;
  // Whether it offers the integrator; nullptr: every one.
  bool (*offers)(Integrator integrator) = nullptr;
  // Throws InputError, in the engine's own words, when it cannot run the
  // scene (an integrator it lacks) — before any work; nullptr: it runs any.
  void (*check)(const Scene& scene) = nullptr;
  // Its own name of the integrator that runs this one, shown after the
  // scene's name ("semi_implicit_euler (MuJoCo Euler)"); nullptr or empty:
  // the scene's name alone.
  std::string_view (*integrator_title)(Integrator integrator) = nullptr;
  // The integrator its contact forces are integrated with when it runs this
  // one (the stability limit that applies); nullptr: the same one.
  Integrator (*contact_integrator)(Integrator integrator) = nullptr;
  // The options its name may carry, in the order "kind:FIRST:SECOND" takes
  // them; the lists name "kind:VALUE" for every value of the first. ({} here
  // and below: the tables that leave them out stay clear of GCC's
  // -Wmissing-field-initializers.)
  std::vector<EngineOption> options{};  // NOLINT(readability-redundant-member-init)
  // Non-empty when its model has values computed for a Δt (EngineSpec::
  // model_dt): the help of --model-dt, which holds them at another Δt.
  std::string_view model_dt_help{};  // NOLINT(readability-redundant-member-init)
  // Its contacts are soft constraints of MuJoCo's kind (solref/solimp
  // impedance, an elliptic cone with impratio), so that the causes of
  // compare's diagnosis (analysis/comparison.hpp: mapping, refsafe, the
  // cone law at its impratio) are its causes; the diagnosis runs only on
  // such an engine.
  bool soft_constraints = false;
  // In the comparison when no list of engines is given (compare without
  // --engines, Python's compare without engines=). An engine that needs an
  // outside runtime (mujoco3: Node) is compared when named.
  bool compared_by_default = true;
};

}  // namespace contact2d::engines
