#include "engines/engines.hpp"

#include <chrono>

#include "core/input_error.hpp"
#ifdef CONTACT2D_WITH_MUJOCO
#include "mujoco/stepper.hpp"
#endif

namespace contact2d::engines {
namespace {

#ifdef CONTACT2D_WITH_MUJOCO
mujoco::MjcfOptions mjcf_options(const EngineSpec& spec) {
  mujoco::MjcfOptions options = mujoco::mjcf_options(spec.mapping, spec.geometry, spec.source);
  options.model_dt = spec.model_dt;
  return options;
}
#endif

}  // namespace

std::string EngineSpec::name() const {
  std::string out = kind;
  if (!mapping.empty() || !geometry.empty()) out += ":" + mapping;
  if (!geometry.empty()) out += ":" + geometry;
  return out;
}

bool mujoco_available() {
#ifdef CONTACT2D_WITH_MUJOCO
  return true;
#else
  return false;
#endif
}

std::vector<std::string> engine_names() {
  std::vector<std::string> names{"ref"};
#ifdef CONTACT2D_WITH_MUJOCO
  names.emplace_back("mujoco");
  for (mujoco::Mapping m : mujoco::kAllMappings)
    names.push_back("mujoco:" + std::string(mujoco::mapping_name(m)));
#endif
  return names;
}

EngineSpec parse_engine(const std::string& name, const std::string& option) {
  EngineSpec spec;
  const size_t colon = name.find(':');
  spec.kind = name.substr(0, colon);
  if (spec.kind == "ref" && colon == std::string::npos) return spec;
  if (spec.kind != "mujoco")
    throw InputError(option + " " + name + ": unknown engine (use ref or mujoco)");
  if (!mujoco_available()) {
    throw InputError(option + " " + name +
                     ": not available (contact2d was built without MuJoCo; use ref)");
  }
  if (colon == std::string::npos) return spec;
  const std::string rest = name.substr(colon + 1);
  const size_t second = rest.find(':');
  spec.mapping = rest.substr(0, second);
  if (second != std::string::npos) spec.geometry = rest.substr(second + 1);
#ifdef CONTACT2D_WITH_MUJOCO
  if (!spec.mapping.empty() && !mujoco::parse_mapping(spec.mapping))
    throw InputError(option + " " + name +
                     ": unknown mapping (seed, exact, calibrated, compensated)");
  if (!spec.geometry.empty() && !mujoco::parse_geometry(spec.geometry))
    throw InputError(option + " " + name + ": unknown geometry (corners, boxes)");
#endif
  return spec;
}

std::unique_ptr<Stepper> make_stepper(const EngineSpec& spec, const Scene& scene) {
  if (spec.kind == "ref") return std::make_unique<ReferenceStepper>(scene);
#ifdef CONTACT2D_WITH_MUJOCO
  if (spec.kind == "mujoco")
    return std::make_unique<mujoco::MujocoStepper>(scene, mjcf_options(spec));
#endif
  throw InputError("engine " + spec.name() + " is not available");
}

EngineRun run_engine(const EngineSpec& spec, const Scene& scene) {
  std::unique_ptr<Stepper> stepper = make_stepper(spec, scene);
  EngineRun run;
  run.engine = spec.name();
  run.description = stepper->describe();
  const auto start = std::chrono::steady_clock::now();
  run.trajectory = simulate(*stepper, scene.sim);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.trajectory.divergence)
    run.divergence_message = stepper->explain(*run.trajectory.divergence, scene);
#ifdef CONTACT2D_WITH_MUJOCO
  if (const auto* mj = dynamic_cast<const mujoco::MujocoStepper*>(stepper.get())) {
    run.warnings = mj->warnings();
    run.solref = mj->settings().solref;
    run.impratio = mj->settings().impratio;
    run.mu_roll = mujoco::cone_mu_roll(scene, mj->settings());
    if (mj->settings().refsafe_clamped) run.notes.emplace_back("refsafe");
  }
#endif
  return run;
}

EngineRun run_engine(const std::string& name, const Scene& scene) {
  return run_engine(parse_engine(name), scene);
}

bool engine_offers(const std::string& name, Integrator integrator) {
  return name == "ref" || integrator != Integrator::ExplicitEuler;
}

}  // namespace contact2d::engines
