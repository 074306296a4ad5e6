#include "engines/engines.hpp"

#include <cctype>
#include <chrono>
#include <utility>

#include "core/format.hpp"
#include "core/input_error.hpp"
#ifdef CONTACT2D_WITH_MUJOCO
#include "mujoco/engine.hpp"
#include "mujoco3/engine.hpp"
#endif

namespace contact2d::engines {
namespace {

std::unique_ptr<Stepper> make_reference(const EngineSpec& /*spec*/, const Scene& scene) {
  return std::make_unique<ReferenceStepper>(scene);
}

// The reference solver with the scene's integrator: every integrator, no options.
const EngineInfo kReference{"ref", "ref", make_reference};

#ifndef CONTACT2D_WITH_MUJOCO
// Known by name so that asking for it says it was not built in.
const EngineInfo kMujocoAbsent{"mujoco", "MuJoCo", nullptr,
                               [](Integrator i) { return i != Integrator::ExplicitEuler; }};
const EngineInfo kMujoco3Absent{"mujoco3", "MuJoCo 3", nullptr,
                                [](Integrator i) { return i != Integrator::ExplicitEuler; }};
#endif

// "a, b, c".
std::string join(const std::vector<std::string_view>& items, const std::string& separator) {
  std::string out;
  for (std::string_view item : items) out += (out.empty() ? "" : separator) + std::string(item);
  return out;
}

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
      &mujoco3::engine_info(),
#else
      &kMujocoAbsent,
      &kMujoco3Absent,
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

// kind, then the values by position, the trailing ones left out dropped
// ("mujoco", "mujoco:exact", "mujoco::boxes").
std::string EngineSpec::name() const {
  std::string out = kind;
  const EngineInfo* info = find_engine(kind);
  if (info == nullptr) return out;
  size_t given = 0;
  for (size_t i = 0; i < info->options.size(); ++i)
    if (!option(info->options[i].name).empty()) given = i + 1;
  for (size_t i = 0; i < given; ++i) out += ":" + option(info->options[i].name);
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
    if (!info->options.empty())
      for (std::string_view value : info->options.front().values)
        names.push_back(std::string(info->kind) + ":" + std::string(value));
  }
  return names;
}

std::string engine_names_help() {
  std::string out;
  for (const EngineInfo* info : engine_list()) {
    if (info->make == nullptr) continue;
    const std::string kind(info->kind);
    out += (out.empty() ? "" : ", ") + kind;
    if (info->options.empty()) continue;
    const EngineOption& first = info->options.front();
    std::string upper(first.name);
    for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    out += ", " + kind + ":" + upper + " (" + join(first.values, ", ") + "; " + kind +
           " = its default)";
  }
  return out;
}

namespace {

// Checks `value` against the option's values: "CONTEXT: unknown NAME (a, b)".
void check_option_value(const EngineOption& option, const std::string& value,
                        const std::string& context) {
  if (value.empty()) return;
  for (std::string_view allowed : option.values)
    if (allowed == value) return;
  throw InputError(context + ": unknown " + std::string(option.name) + " (" +
                   join(option.values, ", ") + ")");
}

}  // namespace

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
  if (colon == std::string::npos) return spec;
  // VALUE[:VALUE…] by position; an empty one takes the option's fallback.
  std::string rest = name.substr(colon + 1);
  for (size_t i = 0;; ++i) {
    if (i == info->options.size()) throw InputError(unknown);
    const size_t next = rest.find(':');
    const std::string value = rest.substr(0, next);
    check_option_value(info->options[i], value, option + " " + name);
    if (!value.empty()) spec.options.emplace_back(info->options[i].name, value);
    if (next == std::string::npos) break;
    rest = rest.substr(next + 1);
  }
  return spec;
}

EngineSpec engine_with_options(const std::string& kind, const OptionValues& given, double model_dt,
                               const std::string& source,
                               const std::function<std::string(std::string_view)>& spelled) {
  EngineSpec spec = parse_engine(kind, spelled("engine"));
  const EngineInfo* info = find_engine(kind);
  for (const auto& [option_name, value] : given) {
    if (value.empty()) continue;
    const EngineOption* option = nullptr;
    for (const EngineOption& o : info->options)
      if (o.name == option_name) option = &o;
    if (option == nullptr)
      throw InputError(spelled(option_name) + " " + value + ": not an option of " + kind +
                       (info->options.empty() ? " (it takes none)" : ""));
    check_option_value(*option, value, spelled(option_name) + " " + value);
    if (const std::string named = spec.option(option_name); !named.empty())
      throw InputError(spelled(option_name) + " " + value + ": the engine's name " + kind +
                       " gives " + option_name + " " + named + " already");
  }
  // In the engine's order, as parse_engine leaves them.
  for (const EngineOption& o : info->options)
    for (const auto& [option_name, value] : given)
      if (option_name == o.name && !value.empty()) spec.options.emplace_back(o.name, value);
  if (model_dt != 0.0 && info->model_dt_help.empty())
    throw InputError(spelled("model_dt") + " " + format_number(model_dt, 6) + ": " + kind +
                     " has no Δt-dependent model values");
  spec.model_dt = model_dt;
  spec.source = source;
  return spec;
}

std::string option_value(const EngineSpec& spec, std::string_view name) {
  const EngineInfo* info = find_engine(spec.kind);
  if (info == nullptr) return {};
  for (const EngineOption& option : info->options) {
    if (option.name != name) continue;
    const std::string given = spec.option(name);
    return given.empty() ? std::string(option.fallback) : given;
  }
  return {};
}

std::unique_ptr<Stepper> make_stepper(const EngineSpec& spec, const Scene& scene) {
  const EngineInfo* info = find_engine(spec.kind);
  if (info == nullptr || info->make == nullptr)
    throw InputError("engine " + spec.name() + " is not available");
  return info->make(spec, scene);
}

void check_runs(const EngineSpec& spec, const Scene& scene) {
  const EngineInfo* info = find_engine(spec.kind);
  if (info == nullptr || info->make == nullptr)
    throw InputError("engine " + spec.name() + " is not available");
  if (info->check != nullptr) info->check(scene);
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

std::string own_integrator_name(const std::string& engine, Integrator integrator) {
  const EngineInfo* info = find_engine(engine);
  const std::string_view own = info != nullptr && info->integrator_title != nullptr
                                   ? info->integrator_title(integrator)
                                   : "";
  return own.empty() ? std::string(integrator_name(integrator)) : std::string(own);
}

Integrator contact_integrator(const std::string& engine, Integrator integrator) {
  const EngineInfo* info = find_engine(engine);
  if (info == nullptr || info->contact_integrator == nullptr) return integrator;
  return info->contact_integrator(integrator);
}

}  // namespace contact2d::engines
