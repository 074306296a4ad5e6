// MuJoCo's descriptor for the engine registry (mujoco/engine.hpp).
#include "mujoco/engine.hpp"

#include "core/input_error.hpp"
#include "mujoco/stepper.hpp"

namespace contact2d::mujoco {
namespace {

std::unique_ptr<Stepper> make_mujoco(const engines::EngineSpec& spec, const Scene& scene) {
  MjcfOptions options = mjcf_options(spec.mapping, spec.geometry, spec.source);
  options.model_dt = spec.model_dt;
  return std::make_unique<MujocoStepper>(scene, options);
}

bool offers(Integrator integrator) { return integrator != Integrator::ExplicitEuler; }

// MuJoCo's implicit integrates joint damping and actuators implicitly but
// contact forces explicitly: for a contact it is semi-implicit Euler.
Integrator contact_integrator(Integrator integrator) {
  return integrator == Integrator::ImplicitEuler ? Integrator::SemiImplicitEuler : integrator;
}

// MAPPING[:GEOMETRY]; an empty MAPPING is the default mapping.
void parse_options(const std::string& options, const std::string& context,
                   engines::EngineSpec& spec) {
  const size_t second = options.find(':');
  spec.mapping = options.substr(0, second);
  if (second != std::string::npos) spec.geometry = options.substr(second + 1);
  if (!spec.mapping.empty() && !parse_mapping(spec.mapping))
    throw InputError(context + ": unknown mapping (seed, exact, calibrated, compensated)");
  if (!spec.geometry.empty() && !parse_geometry(spec.geometry))
    throw InputError(context + ": unknown geometry (corners, boxes)");
}

// mujoco:MAPPING for every mapping (geometry variants left out).
std::vector<std::string> variants() {
  std::vector<std::string> names;
  for (Mapping m : kAllMappings) names.push_back("mujoco:" + std::string(mapping_name(m)));
  return names;
}

}  // namespace

std::string_view integrator_title(Integrator integrator) {
  switch (integrator) {
    case Integrator::SemiImplicitEuler: return "Euler";
    case Integrator::ImplicitEuler: return "implicit";
    case Integrator::RK4: return "RK4";
    case Integrator::ExplicitEuler: break;
  }
  return {};
}

const engines::EngineInfo& engine_info() {
  static const engines::EngineInfo info{"mujoco",      "MuJoCo",         make_mujoco,
                                        offers,        integrator_title, contact_integrator,
                                        parse_options, variants};
  return info;
}

}  // namespace contact2d::mujoco
