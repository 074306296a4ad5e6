#include "analysis/compare_run.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include "core/input_error.hpp"
#include "io/json.hpp"

namespace contact2d::analysis {

namespace {

// Labels and keys: the engine's title and kind, or its full name where two
// runs would share one.
void name_runs(std::vector<ComparedRun>& runs) {
  auto shared = [&runs](auto field, const ComparedRun& r) {
    return std::count_if(runs.begin(), runs.end(),
                         [&](const ComparedRun& o) { return field(o) == field(r); }) > 1;
  };
  auto title = [](const ComparedRun& r) {
    const engines::EngineInfo* info = engines::find_engine(r.spec.kind);
    return info != nullptr ? std::string(info->title) : r.spec.kind;
  };
  auto kind = [](const ComparedRun& r) { return r.spec.kind; };
  for (ComparedRun& r : runs) {
    r.label = shared(title, r) ? r.spec.name() : title(r);
    r.key = shared(kind, r) ? r.spec.name() : r.spec.kind;
    std::replace(r.key.begin(), r.key.end(), ':', '_');
  }
}

// The same engine and model: one kind, every option's value (given or
// fallback) and the model's Δt alike.
bool same_engine(const engines::EngineSpec& a, const engines::EngineSpec& b) {
  if (a.kind != b.kind || a.model_dt != b.model_dt) return false;
  for (const engines::EngineOption& option : engines::find_engine(a.kind)->options)
    if (engines::option_value(a, option.name) != engines::option_value(b, option.name))
      return false;
  return true;
}

}  // namespace

std::vector<engines::EngineSpec> comparison_engines(
    const std::vector<std::string>& names, const engines::OptionValues& given, double model_dt,
    const std::string& source, const std::function<std::string(std::string_view)>& spelled) {
  std::vector<engines::EngineSpec> specs{engines::parse_engine("ref")};
  const bool options_given = std::any_of(given.begin(), given.end(),
                                         [](const auto& option) { return !option.second.empty(); });
  if (names.size() == 1 && options_given) {  // one engine: --mapping, --geometry, … as simulate's
    const engines::EngineSpec named = engines::parse_engine(names.front(), spelled("engines"));
    if (named.kind == "ref")
      throw InputError(spelled("engines") + " " + names.front() +
                       ": the reference is always compared, as the first run");
    const bool has_dt = !engines::find_engine(named.kind)->model_dt_help.empty();
    specs.push_back(engines::engine_with_options(names.front(), given, has_dt ? model_dt : 0.0,
                                                 source, spelled));
    return specs;
  }
  if (!names.empty()) {
    for (const auto& [name, value] : given)
      if (!value.empty())
        throw InputError(spelled(name) + " " + value + ": with " + spelled("engines") +
                         " an engine's options are part of its name (KIND:VALUE:VALUE)");
    for (const std::string& name : names) {
      engines::EngineSpec spec = engines::parse_engine(name, spelled("engines"));
      spec.source = source;
      if (!engines::find_engine(spec.kind)->model_dt_help.empty()) spec.model_dt = model_dt;
      for (const engines::EngineSpec& earlier : specs)
        if (same_engine(earlier, spec))
          throw InputError(spelled("engines") + " " + name + ": " +
                           (&earlier == &specs.front()
                                ? "the reference is always compared, as the first run"
                                : "the same engine as " + earlier.name() + ", named twice"));
      specs.push_back(spec);
    }
    return specs;
  }
  const engines::EngineInfo* reference = engines::find_engine("ref");
  for (const engines::EngineInfo* info : engines::engine_list()) {
    if (info->make == nullptr || info == reference || !info->compared_by_default) continue;
    engines::OptionValues own;
    for (const engines::EngineOption& option : info->options)
      for (const auto& [name, value] : given)
        if (name == option.name) own.emplace_back(name, value);
    specs.push_back(engines::engine_with_options(std::string(info->kind), own,
                                                 info->model_dt_help.empty() ? 0.0 : model_dt,
                                                 source, spelled));
  }
  return specs;
}

Comparison prepare_comparison(const Scene& scene, const std::vector<engines::EngineSpec>& specs) {
  if (specs.size() < 2)
    throw InputError("compare: at least two engines are needed, " + std::to_string(specs.size()) +
                     " given");
  Comparison c;
  c.scene = scene;
  for (const engines::EngineSpec& spec : specs) {
    engines::check_runs(spec, c.scene);  // explicit Euler on MuJoCo: fail before any work
    c.runs.push_back({spec, {}, {}, {}, {}, {}});
  }
  name_runs(c.runs);
  return c;
}

namespace {

// The run the diagnosis takes apart: the first after runs[0] with soft
// constraints (0: none has them).
size_t diagnosed_run(const Comparison& c) {
  for (size_t i = 1; i < c.runs.size(); ++i)
    if (engines::find_engine(c.runs[i].spec.kind)->soft_constraints) return i;
  return 0;
}

}  // namespace

void run_engines(Comparison& c, bool early_diagnosis, unsigned threads) {
  const size_t diagnosed = early_diagnosis ? diagnosed_run(c) : 0;
  const std::vector<EarlyRun> early =
      diagnosed > 0 ? early_reruns(c.scene, c.runs[diagnosed].spec) : std::vector<EarlyRun>{};
  // One job per run: the engines after the first, the early MuJoCo runs of
  // the diagnosis, then the first (the reference: the cheapest).
  const size_t n = c.runs.size() + early.size();
  std::vector<std::optional<EngineRun>> made(early.size());
  parallel_for(n, early.empty() ? 1 : threads, [&](size_t job) {
    if (job + 1 < c.runs.size()) {
      ComparedRun& r = c.runs[job + 1];
      r.run = engines::run_engine(r.spec, c.scene);
    } else if (job + 1 < n) {
      const EarlyRun& e = early[job + 1 - c.runs.size()];
      try {
        made[job + 1 - c.runs.size()] = registry_runner()(e.engine, e.scene);
      } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch)
        // The diagnosis runs it again and reports what it throws.
      }
    } else {
      c.runs[0].run = engines::run_engine(c.runs[0].spec, c.scene);
    }
  });
  c.early.clear();
  for (size_t i = 0; i < early.size(); ++i)
    if (made[i]) c.early.emplace_back(early[i].cause, std::move(*made[i]));
  // A contact the engine's geometry cannot make leads what it says: a
  // divergence that follows it is not the engine's step.
  for (size_t i = 1; i < c.runs.size(); ++i) {
    EngineRun& run = c.runs[i].run;
    const std::string missed =
        missed_obstacle_contact(c.scene, c.runs[i].spec, run.trajectory, c.runs[0].run.trajectory);
    if (missed.empty()) continue;
    if (run.trajectory.divergence)
      run.divergence_message = missed + " What followed: " + run.divergence_message;
    else
      run.warnings.push_back(missed);
  }
}

std::vector<RunProblem> run_problems(const Comparison& c) {
  std::vector<RunProblem> problems;
  for (const ComparedRun& r : c.runs)
    if (r.run.trajectory.divergence) problems.push_back({r.label, true, r.run.divergence_message});
  if (!problems.empty()) return problems;
  for (const ComparedRun& r : c.runs) {
    std::string reason = nonphysical(r.run.trajectory, c.scene);
    if (!reason.empty()) problems.push_back({r.label, false, std::move(reason)});
  }
  return problems;
}

namespace {

// MuJoCo 3's friction damper (docs/mujoco3.md) matches the tanh law where a
// body slides or rolls to rest, and falls behind it where a landing loads a
// contact many times the weight: its friction is viscous with b fixed at the
// resting load, where tanh grips with μ·F_n. Which one this scene is, is
// measured: the run again with MuJoCo's shared damper, both against the
// reference.
void damper_check(Comparison& c) {
  if (!(c.scene.contact.mu > 0.0)) return;
  for (size_t i = 1; i < c.runs.size(); ++i) {
    const ComparedRun& r = c.runs[i];
    if (r.spec.kind != "mujoco3" || engines::option_value(r.spec, "friction") != "damper") continue;
    engines::EngineSpec shared = r.spec;
    shared.set("friction", "shared");
    double without = NAN;
    try {
      without =
          error_between(c.runs[0].run.trajectory, engines::run_engine(shared, c.scene).trajectory)
              .max_pos;
    } catch (const std::exception&) {
      continue;  // the shared damper cannot run it: nothing to compare
    }
    const double with = r.vs_first.max_pos;
    const bool helps = with < without;
    c.diagnosis.damper_notes.push_back(
        r.label + ": MuJoCo 3's friction damper is on. Against the reference this run is " +
        format_number(with, 3) + " m apart, and " + format_number(without, 3) +
        " m with MuJoCo's shared damper (" + shared.name() + "): here it " +
        (helps ? "helps, as where a body slides or rolls to rest on its resting load"
               : "hurts: its friction is viscous with b fixed at the resting load, and where a "
                 "landing loads a contact many times the weight the reference's tanh law grips "
                 "and the damper lets it slip (the shipped T lands on a corner and tips the "
                 "other way); run " +
                     shared.name() + " for this scene") +
        " (docs/mujoco3.md).");
  }
}

}  // namespace

void measure(Comparison& c, double converged_tol, bool diagnosis, const DiagnosisOptions& options) {
  c.converged = converged_solution(c.scene, converged_tol);
  const Trajectory& first = c.runs[0].run.trajectory;
  for (size_t i = 0; i < c.runs.size(); ++i) {
    ComparedRun& r = c.runs[i];
    if (c.converged.available)
      r.vs_converged = error_against(r.run.trajectory, c.converged.trajectory);
    if (i > 0) r.vs_first = error_between(first, r.run.trajectory);
  }
  if (!diagnosis) return;
  c.diagnosed = diagnosed_run(c);
  if (c.diagnosed == 0) {
    std::string others;
    for (size_t i = 1; i < c.runs.size(); ++i)
      others += (i > 1 ? (i + 1 == c.runs.size() ? " and " : ", ") : "") + c.runs[i].label;
    c.diagnosis.summary =
        "Not run: its causes (the mapping, refsafe, the friction cone at its impratio) are "
        "those of an engine with soft constraints such as MuJoCo, and " +
        others + (c.runs.size() > 2 ? " have none." : " has none.");
    damper_check(c);
    return;
  }
  const size_t i = c.diagnosed;
  DiagnosisOptions how = options;
  if (!c.early.empty()) how.early = &c.early;
  c.diagnosis = diagnose(c.scene, c.runs[i].spec, c.runs[0].run, c.runs[i].run, pair(c, i),
                         registry_runner(), how);
  damper_check(c);
}

ThreeWay pair(const Comparison& c, size_t i) {
  // converged, first ↔ converged, this one ↔ converged, first ↔ this one.
  return ThreeWay{c.converged, c.runs[0].vs_converged, c.runs[i].vs_converged, c.runs[i].vs_first};
}

Energies energies(const Scene& scene, const Trajectory& t) {
  const Model model = make_model(scene);
  return {energy(model, t.samples.front().state), energy(model, t.samples.back().state)};
}

namespace {

// `prefix`_max_pos_err, …: one pair's distances (null when not measured).
void json_errors(std::ostringstream& o, const std::string& prefix, const TrajectoryError& e,
                 bool measured) {
  auto n = [measured](double v) { return measured ? json::number(v, 10) : std::string("null"); };
  o << ", \"" << prefix << "_max_pos_err\": " << n(e.max_pos) << ", \"" << prefix
    << "_rms_pos_err\": " << n(e.rms_pos) << ", \"" << prefix << "_end_pos_err\": " << n(e.end_pos)
    << ", \"" << prefix << "_max_angle_err\": " << n(e.max_angle) << ", \"" << prefix
    << "_end_angle_err\": " << n(e.end_angle) << ", \"" << prefix
    << "_max_vel_err\": " << n(e.max_vel) << ", \"" << prefix
    << "_max_omega_err\": " << n(e.max_omega);
}

void json_diagnosis(std::ostringstream& o, const Diagnosis& d) {
  o << ", \"diagnosis_ran\": " << (d.ran ? "true" : "false")
    << ", \"agrees\": " << (d.agrees ? "true" : "false")
    << ", \"diagnosis_summary\": " << json::string(d.summary) << ", \"diagnosis\": [";
  bool first = true;
  for (const Finding& f : d.findings) {
    if (!f.named) continue;
    o << (first ? "" : ", ");
    first = false;
    o << "{\"cause\": " << json::string(f.cause) << ", \"share\": " << json::number(f.share, 10)
      << ", \"before\": " << json::number(f.before, 10)
      << ", \"after\": " << json::number(f.after, 10) << ", \"fix\": " << json::string(f.fix)
      << ", \"explanation\": " << json::string(f.explanation);
    if (f.cause == "friction") {
      o << ", \"sliding_phases\": [";
      for (size_t i = 0; i < f.phases.size(); ++i)
        o << (i ? ", " : "") << "{\"t0\": " << json::number(f.phases[i].t0, 10)
          << ", \"t1\": " << json::number(f.phases[i].t1, 10)
          << ", \"distance0\": " << json::number(f.phases[i].distance0, 10)
          << ", \"distance1\": " << json::number(f.phases[i].distance1, 10) << "}";
      o << "]";
    }
    o << "}";
  }
  o << "], \"ruled_out\": [";
  first = true;
  for (const Finding& f : d.findings) {
    if (f.named) continue;
    o << (first ? "" : ", ") << "{\"cause\": " << json::string(f.cause)
      << ", \"share\": " << json::number(f.share, 10)
      << ", \"after\": " << json::number(f.after, 10) << "}";
    first = false;
  }
  o << "], \"not_rerun\": [";
  for (size_t i = 0; i < d.not_rerun.size(); ++i)
    o << (i ? ", " : "") << json::string(d.not_rerun[i]);
  o << "], \"not_rerun_why\": " << json::string(d.not_rerun_why) << ", \"damper_notes\": [";
  for (size_t i = 0; i < d.damper_notes.size(); ++i)
    o << (i ? ", " : "") << json::string(d.damper_notes[i]);
  o << "]";
}

}  // namespace

// The keys of one run beyond the first: runs[1]'s unprefixed ("mapping",
// "solref", "mujoco_warnings" — the pair a two-engine comparison has always
// printed), every later one's prefixed by its key ("mujoco_exact_mapping").
std::string comparison_json(const Comparison& c, const std::string& scene_label) {
  const std::vector<ComparedRun>& runs = c.runs;
  const TrajectoryError& e = runs[1].vs_first;
  const ConvergedSolution& conv = c.converged;
  auto prefix = [&runs](size_t i) { return i == 1 ? std::string() : runs[i].key + "_"; };
  std::ostringstream o;
  o << "{\"scene\": " << json::string(scene_label) << ", \"shape\": \"" << shape_name(c.scene.shape)
    << "\"";
  for (size_t i = 1; i < runs.size(); ++i) {
    const engines::EngineInfo* info = engines::find_engine(runs[i].spec.kind);
    for (const engines::EngineOption& option : info->options) {
      o << ", \"" << prefix(i) << option.name << "\": \""
        << engines::option_value(runs[i].spec, option.name) << "\"";
    }
  }
  o << ", \"damping\": \"" << damping_law_name(c.scene.contact.damping) << "\""
    << ", \"friction_law\": \"" << friction_law_name(c.scene.contact.friction) << "\""
    << ", \"integrators\": {";
  for (size_t i = 0; i < runs.size(); ++i)
    o << (i ? ", " : "") << "\"" << runs[i].key << "\": \""
      << engines::own_integrator_name(runs[i].spec.kind, c.scene.sim.integrator) << "\"";
  o << "}"
    << ", \"dt\": " << json::number(c.scene.sim.dt, 10)
    << ", \"duration\": " << json::number(c.scene.sim.duration, 10)
    << ", \"samples\": " << e.samples << ", \"max_pos_err\": " << json::number(e.max_pos, 10)
    << ", \"rms_pos_err\": " << json::number(e.rms_pos, 10)
    << ", \"max_angle_err\": " << json::number(e.max_angle, 10)
    << ", \"max_vel_err\": " << json::number(e.max_vel, 10)
    << ", \"max_omega_err\": " << json::number(e.max_omega, 10)
    << ", \"end_pos_err\": " << json::number(e.end_pos, 10)
    << ", \"end_angle_err\": " << json::number(e.end_angle, 10)
    << ", \"time_of_max_pos_err\": " << json::number(e.time_of_max_pos, 10);
  for (const ComparedRun& r : runs) {
    const Energies en = energies(c.scene, r.run.trajectory);
    o << ", \"" << r.key << "_energy\": [" << json::number(en.initial, 10) << ", "
      << json::number(en.final, 10) << "]";
  }
  for (const ComparedRun& r : runs)
    o << ", \"" << r.key << "_seconds\": " << json::number(r.run.seconds, 10);
  for (size_t i = 1; i < runs.size(); ++i) {
    const engines::EngineRun& run = runs[i].run;
    o << ", \"" << prefix(i) << "solref\": [" << json::number(run.solref[0], 10) << ", "
      << json::number(run.solref[1], 10) << "]"
      << ", \"" << prefix(i) << "impratio\": " << json::number(run.impratio, 10) << ", \""
      << runs[i].key << "_warnings\": [";
    for (size_t w = 0; w < run.warnings.size(); ++w)
      o << (w ? ", " : "") << json::string(run.warnings[w]);
    o << "]";
  }
  o << ", \"converged_tol\": " << json::number(conv.tol, 10)
    << ", \"converged_available\": " << (conv.available ? "true" : "false")
    << ", \"converged_why_not\": " << (conv.available ? "null" : json::string(conv.why_not))
    << ", \"converged_own_error\": "
    << (conv.available ? json::number(conv.own_error, 10) : std::string("null"))
    << ", \"converged_seconds\": " << json::number(conv.seconds, 10) << ", \"amplification\": "
    << (conv.available ? json::number(conv.amplification, 10) : std::string("null"));
  for (const ComparedRun& r : runs)
    json_errors(o, r.key + "_vs_converged", r.vs_converged, conv.available);
  for (size_t i = 1; i < runs.size(); ++i)
    json_errors(o, runs[0].key + "_vs_" + runs[i].key, runs[i].vs_first, true);
  json_diagnosis(o, c.diagnosis);
  if (const std::vector<std::string> notes = version_notes(c); !notes.empty()) {
    o << ", \"version_notes\": [";
    for (size_t i = 0; i < notes.size(); ++i) o << (i ? ", " : "") << json::string(notes[i]);
    o << "]";
  }
  o << "}\n";
  return o.str();
}

}  // namespace contact2d::analysis
