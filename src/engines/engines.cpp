#include "engines/engines.hpp"

#include <chrono>
#include <utility>

#include "core/input_error.hpp"
#ifdef CONTACT2D_WITH_MUJOCO
#include "mujoco/engine.hpp"
#endif

namespace contact2d::engines {
namespace {

std::unique_ptr<Stepper> make_reference(const EngineSpec& /*spec*/, const Scene& scene) {
  return std::make_unique<ReferenceStepper>(scene);
}

// The reference solver with the scene's integrator: every integrator, no options.
const EngineInfo kReference{"ref", "the reference", make_reference};

#ifndef CONTACT2D_WITH_MUJOCO
// Known by name so that asking for it says it was not built in.
const EngineInfo kMujocoAbsent{"mujoco", "MuJoCo", nullptr,
                               [](Integrator i) { return i != Integrator::ExplicitEuler; }};
#endif

// "ref or mujoco", "ref, mujoco or coulomb".
std::string kinds_in_prose() {
  const std::vector<const EngineInfo*>& list = engine_list();
  std::string out;
  for (size_t i = 0; i < list.size(); ++i) {
    if (i > 0) out += i + 1 == list.size() ? " or " : ", ";
    out += list[i]->kind;
  }
  return out;
}

}  // namespace

const std::vector<const EngineInfo*>& engine_list() {
  static const std::vector<const EngineInfo*> list{
      &kReference,
#ifdef CONTACT2D_WITH_MUJOCO
      &mujoco::engine_info(),
#else
      &kMujocoAbsent,
#endif
  };
  return list;
}

const EngineInfo* find_engine(std::string_view name) {
  const std::string_view kind = name.substr(0, name.find(':'));
  for (const EngineInfo* info : engine_list())
    if (info->kind == kind) return info;
  return nullptr;
}

std::vector<std::string> engine_kinds() {
  std::vector<std::string> kinds;
  for (const EngineInfo* info : engine_list()) kinds.emplace_back(info->kind);
  return kinds;
}

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
  std::vector<std::string> names;
  for (const EngineInfo* info : engine_list()) {
    if (info->make == nullptr) continue;
    names.emplace_back(info->kind);
    if (info->variants != nullptr)
      for (std::string& variant : info->variants()) names.push_back(std::move(variant));
  }
  return names;
}

EngineSpec parse_engine(const std::string& name, const std::string& option) {
  EngineSpec spec;
  const size_t colon = name.find(':');
  spec.kind = name.substr(0, colon);
  const EngineInfo* info = find_engine(spec.kind);
  const std::string unknown =
      option + " " + name + ": unknown engine (use " + kinds_in_prose() + ")";
  if (info == nullptr) throw InputError(unknown);
  if (info->make == nullptr) {
    throw InputError(option + " " + name + ": not available (contact2d was built without " +
                     std::string(info->title) + "; use " + std::string(kReference.kind) + ")");
  }
  if (colon != std::string::npos && info->parse_options == nullptr) throw InputError(unknown);
  if (colon != std::string::npos)
    info->parse_options(name.substr(colon + 1), option + " " + name, spec);
  return spec;
}

EngineSpec mujoco_spec(const std::string& mapping, const std::string& geometry, double model_dt,
                       const std::string& source) {
  EngineSpec spec;
  spec.kind = "mujoco";
  spec.mapping = mapping;
  spec.geometry = geometry;
  spec.source = source;
  spec.model_dt = model_dt;
  return spec;
}

std::unique_ptr<Stepper> make_stepper(const EngineSpec& spec, const Scene& scene) {
  const EngineInfo* info = find_engine(spec.kind);
  if (info == nullptr || info->make == nullptr)
    throw InputError("engine " + spec.name() + " is not available");
  return info->make(spec, scene);
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
  RunFacts facts = stepper->facts(scene);
  run.warnings = std::move(facts.warnings);
  run.notes = std::move(facts.notes);
  run.solref = {facts.value("solref[0]"), facts.value("solref[1]")};
  run.impratio = facts.value("impratio");
  run.mu_roll = facts.value("mu_roll");
  return run;
}

EngineRun run_engine(const std::string& name, const Scene& scene) {
  return run_engine(parse_engine(name), scene);
}

bool engine_offers(const std::string& name, Integrator integrator) {
  auto offers = [integrator](const EngineInfo* info) {
    return info->offers == nullptr || info->offers(integrator);
  };
  if (const EngineInfo* info = find_engine(name)) return offers(info);
  // A name the registry does not know (a caller's own runner): only what
  // every engine offers.
  for (const EngineInfo* info : engine_list())
    if (!offers(info)) return false;
  return true;
}

std::string integrator_label(const std::string& engine, Integrator integrator) {
  std::string label(integrator_name(integrator));
  const EngineInfo* info = find_engine(engine);
  if (info == nullptr || info->integrator_title == nullptr) return label;
  const std::string_view own = info->integrator_title(integrator);
  if (!own.empty()) label += " (" + std::string(info->title) + " " + std::string(own) + ")";
  return label;
}

Integrator contact_integrator(const std::string& engine, Integrator integrator) {
  const EngineInfo* info = find_engine(engine);
  if (info == nullptr || info->contact_integrator == nullptr) return integrator;
  return info->contact_integrator(integrator);
}

}  // namespace contact2d::engines
