// Three-way comparison and diagnosis (analysis/comparison.hpp).
#include "analysis/comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "analysis/compare_run.hpp"
#include "analysis/grazing.hpp"
#include "analysis/reference.hpp"
#include "core/contacts.hpp"
#include "core/dynamics.hpp"
#include "core/format.hpp"

namespace contact2d::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// "95 %", never "-0 %".
std::string percent(double share) {
  const double rounded = std::round(100.0 * share);
  return format_text("%.0f %%", rounded == 0.0 ? 0.0 : rounded);
}

// The ref ↔ MuJoCo position distance at the samples both runs have.
std::vector<std::pair<double, double>> distance_series(const Trajectory& a, const Trajectory& b) {
  std::vector<std::pair<double, double>> out;
  size_t j = 0;
  for (const Sample& s : a.samples) {
    const double tolerance = 1e-12 * std::max(1.0, s.t);
    while (j < b.samples.size() && b.samples[j].t < s.t - tolerance) ++j;
    if (j == b.samples.size()) break;
    if (std::abs(b.samples[j].t - s.t) <= tolerance)
      out.emplace_back(s.t, (s.state.q.head<2>() - b.samples[j].state.q.head<2>()).norm());
  }
  return out;
}

// One re-run of the diagnosis: the scene with a cause removed, on the
// reference (unless only MuJoCo's side changes) and on MuJoCo.
struct Rerun {
  std::string cause;
  Scene scene;
  bool ref = true;
  std::string mujoco;  // engine name
  // A MuJoCo engine the runner's names cannot express (a held model_dt):
  // run through the registry directly.
  std::optional<engines::EngineSpec> mujoco_spec;
  // Only the reference changes (its friction law): the base MuJoCo run is
  // reused.
  bool mujoco_unchanged = false;
  // The reference scene is the base scene at another Δt (time_step,
  // dt_dependent_model, refsafe): re-runs at the same Δt share one
  // reference run.
  bool ref_dt_only = false;
  // The re-run whose reference run this one reuses (-1: its own).
  int ref_from = -1;
  // Results.
  std::optional<EngineRun> ref_run;
  EngineRun mujoco_run;
  std::string failure;  // an engine threw or diverged
  TrajectoryError between;
};

Rerun rerun(const std::string& cause, const Scene& scene, bool ref, const std::string& mujoco) {
  Rerun r;
  r.cause = cause;
  r.scene = scene;
  r.ref = ref;
  r.mujoco = mujoco;
  return r;
}

}  // namespace

ConvergedSolution converged_solution(const Scene& scene, double tol) {
  ConvergedSolution out;
  out.tol = tol;
  const auto start = std::chrono::steady_clock::now();
  out.trajectory = converged_reference(scene, tol);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!out.trajectory.ok()) {
    out.why_not = out.trajectory.failure();
    return out;
  }
  out.available = true;
  const std::vector<double> times = output_times(scene.sim);
  const DenseTrajectory coarser = converged_reference(scene, 10.0 * tol);
  out.own_error = coarser.ok() ? error_between(out.trajectory, coarser, times).max_pos : kNaN;
  constexpr double kDelta = 1e-8;  // m
  Scene perturbed = scene;
  perturbed.initial.q.y() += kDelta;
  const DenseTrajectory moved = converged_reference(perturbed, tol);
  out.amplification =
      moved.ok() ? error_between(out.trajectory, moved, times).max_pos / kDelta : kNaN;
  return out;
}

ThreeWay three_way(const Scene& scene, const Trajectory& ref, const Trajectory& mujoco,
                   double tol) {
  ThreeWay t;
  t.converged = converged_solution(scene, tol);
  if (t.converged.available) {
    t.ref_vs_converged = error_against(ref, t.converged.trajectory);
    t.mujoco_vs_converged = error_against(mujoco, t.converged.trajectory);
  }
  t.ref_vs_mujoco = error_between(ref, mujoco);
  return t;
}

std::vector<SlidingPhase> sliding_phases(const Scene& scene, const Trajectory& ref,
                                         const Trajectory& mujoco) {
  const Model model = make_model(scene);
  ContactSet contacts(model);
  const double slip = 1.0 / scene.contact.alpha;  // tanh(α·v_t) ≥ tanh(1) = 0.76 beyond it
  const auto series = distance_series(ref, mujoco);
  std::vector<SlidingPhase> phases;
  bool open = false;
  size_t j = 0;
  for (const Sample& s : ref.samples) {
    while (j + 1 < series.size() && series[j].first < s.t) ++j;
    const double distance = series.empty() ? 0.0 : series[j].second;
    find_contacts(model, s.state.q, contacts);
    bool sliding = false;
    for (const Contact& c : contacts) {
      // Velocity of the body point at the contact, along the surface
      // tangent (n_y, −n_x).
      const double vx = s.state.v.x() - s.state.v.z() * c.ry;
      const double vy = s.state.v.y() + s.state.v.z() * c.rx;
      if (std::abs(vx * c.ny - vy * c.nx) >= slip) sliding = true;
    }
    if (sliding && !open) phases.push_back({s.t, s.t, distance, distance});
    if (sliding) {
      phases.back().t1 = s.t;
      phases.back().distance1 = distance;
    }
    open = sliding;
  }
  std::sort(phases.begin(), phases.end(), [](const SlidingPhase& a, const SlidingPhase& b) {
    return a.distance1 - a.distance0 > b.distance1 - b.distance0;
  });
  return phases;
}

namespace {

// What every stage of the diagnosis reads: the base runs and the facts
// about the scene and the mapping that decide which re-runs exist.
struct DiagnosisInputs {
  const Scene& scene;
  const engines::EngineSpec& mujoco;
  const EngineRun& ref;
  const EngineRun& mujoco_run;
  const ThreeWay& base;
  std::string mapping;    // the engine's mapping, given or its fallback; empty: it has none
  bool friction = false;  // μ > 0 or μ_roll > 0
  bool dt_dependent_impratio = false;  // the mapping's impratio = 1/(c·Δt·A_t)
  double refsafe_dt = kNaN;            // the refsafe re-run's Δt (NaN: none)
};

// The step of the refsafe re-run. MuJoCo's refsafe raises a timeconst
// below 2·Δt to 2·Δt; the largest Δt/10^j (j ≤ 3) whose double is within
// the timeconst is a step at which it does not. NaN when refsafe did not
// act or no such step exists.
double refsafe_step(double dt, const EngineRun& mujoco_run) {
  const bool refsafe = std::find(mujoco_run.notes.begin(), mujoco_run.notes.end(), "refsafe") !=
                       mujoco_run.notes.end();
  double refsafe_dt = kNaN;
  if (refsafe && mujoco_run.solref[0] > 0.0) {
    for (int j = 1; j <= 3 && !(refsafe_dt > 0.0); ++j) {
      const double candidate = dt / std::pow(10.0, j);
      if (2.0 * candidate <= mujoco_run.solref[0]) refsafe_dt = candidate;
    }
  }
  return refsafe_dt;
}

DiagnosisInputs diagnosis_inputs(const Scene& scene, const engines::EngineSpec& mujoco,
                                 const EngineRun& ref, const EngineRun& mujoco_run,
                                 const ThreeWay& base) {
  // Empty for an engine without a mapping: then no mapping cause.
  std::string mapping = engines::option_value(mujoco, "mapping");
  const bool friction = scene.contact.mu > 0.0 || scene.contact.mu_roll > 0.0;
  // compensated keeps calibrated's friction rows, impratio included.
  const bool dt_dependent_impratio = mapping == "calibrated" || mapping == "compensated";
  return DiagnosisInputs{scene,
                         mujoco,
                         ref,
                         mujoco_run,
                         base,
                         std::move(mapping),
                         friction,
                         dt_dependent_impratio,
                         refsafe_step(scene.sim.dt, mujoco_run)};
}

// The re-runs of the friction law: the reference under MuJoCo's own
// effective law (soft_cone, at MuJoCo's impratio), and under the cone's
// shape without its push (viscous_cone); MuJoCo as it was. Their shares say
// how much of the difference is the law (core/contact.hpp).
void plan_friction_law_reruns(const DiagnosisInputs& in, const std::string& mj,
                              std::vector<Rerun>& reruns) {
  const Scene& scene = in.scene;
  const bool cone_ratio_known =
      std::isfinite(in.mujoco_run.impratio) && in.mujoco_run.impratio > 0.0;
  if (scene.contact.mu > 0.0 && scene.contact.friction == FrictionLaw::Tanh) {
    for (const FrictionLaw law : {FrictionLaw::SoftCone, FrictionLaw::ViscousCone}) {
      Rerun r =
          rerun(law == FrictionLaw::SoftCone ? "friction_law" : "friction_shape", scene, true, mj);
      r.scene.contact.friction = law;
      r.scene.contact.cone_ratio = cone_ratio_known ? in.mujoco_run.impratio : 1.0;
      // MuJoCo's own rolling coefficient (compensated writes μ_roll').
      if (std::isfinite(in.mujoco_run.mu_roll)) r.scene.contact.mu_roll = in.mujoco_run.mu_roll;
      r.mujoco_unchanged = true;
      reruns.push_back(r);
    }
  }
}

// Which re-runs test which cause, in the order the findings list them
// before ranking.
std::vector<Rerun> plan_reruns(const DiagnosisInputs& in) {
  const Scene& scene = in.scene;
  const std::string mj = in.mujoco.name();
  const double dt = scene.sim.dt;
  std::vector<Rerun> reruns;
  if (scene.contact.damping == DampingLaw::Compression) {
    Rerun r = rerun("damping_law", scene, true, mj);
    r.scene.contact.damping = DampingLaw::KelvinVoigt;
    // MuJoCo's damper is Kelvin–Voigt whatever the scene's law: its model
    // and run are the base ones (tests/mujoco/test_compare_diagnosis.cpp,
    // CompareDiagnosis.MujocoRunsTheSameModelUnderEitherDampingLaw).
    r.mujoco_unchanged = true;
    reruns.push_back(r);
  }
  {
    Rerun r = rerun("time_step", scene, true, mj);
    r.scene.sim.dt = dt / 10.0;
    r.ref_dt_only = true;
    reruns.push_back(r);
  }
  if (in.friction) {
    Rerun r = rerun("friction", scene, true, mj);
    r.scene.contact.mu = 0.0;
    r.scene.contact.mu_roll = 0.0;
    reruns.push_back(r);
  }
  plan_friction_law_reruns(in, mj, reruns);
  if (scene.contact.mu > 0.0 && scene.contact.mu_roll > 0.0) {
    // Rolling resistance alone, sliding friction kept.
    Rerun r = rerun("rolling_resistance", scene, true, mj);
    r.scene.contact.mu_roll = 0.0;
    reruns.push_back(r);
  }
  // The mapping: seed and exact against calibrated (MuJoCo's default
  // impedance), calibrated against compensated (the O(d) term of MuJoCo's
  // soft contact, docs/mujoco.md). compensated has no better one to try.
  const std::string better_mapping = in.mapping == "calibrated" ? "compensated" : "calibrated";
  if (!in.mapping.empty() && in.mapping != "compensated") {
    engines::EngineSpec better = in.mujoco;
    better.set("mapping", better_mapping);
    reruns.push_back(rerun("mapping", scene, false, better.name()));
  }
  // The calibrated impratio = 1/(c·Δt·A_t) follows Δt unless the user held
  // it (--model-dt): the Δt/10 re-run then changes MuJoCo's model as well as
  // its step. This re-run steps at Δt/10 with the model of Δt.
  const bool model_follows_dt = in.friction && in.dt_dependent_impratio &&
                                in.mujoco.model_dt == 0.0 && std::isfinite(in.mujoco_run.impratio);
  if (model_follows_dt) {
    Rerun r = rerun("dt_dependent_model", scene, true, mj);
    r.scene.sim.dt = dt / 10.0;
    engines::EngineSpec held = in.mujoco;
    held.model_dt = dt;
    r.mujoco_spec = held;
    r.ref_dt_only = true;
    reruns.push_back(r);
  }
  if (in.refsafe_dt > 0.0) {
    Rerun r = rerun("refsafe", scene, true, mj);
    r.scene.sim.dt = in.refsafe_dt;
    r.ref_dt_only = true;
    reruns.push_back(r);
  }
  // One reference run per Δt among the re-runs that change only Δt.
  for (size_t i = 0; i < reruns.size(); ++i)
    for (size_t j = 0; j < i && reruns[i].ref_dt_only; ++j)
      if (reruns[j].ref_dt_only && reruns[j].ref_from < 0 &&
          reruns[j].scene.sim.dt == reruns[i].scene.sim.dt) {
        reruns[i].ref_from = static_cast<int>(j);
        break;
      }
  return reruns;
}

}  // namespace

std::vector<EarlyRun> early_reruns(const Scene& scene, const engines::EngineSpec& mujoco) {
  // The plan of the first tier's MuJoCo runs reads nothing of the base runs
  // (friction_law's ratio and the fine-step tier do, and are left out), so
  // empty runs stand in for them.
  const EngineRun none;
  const ThreeWay no_distances;
  const DiagnosisInputs in = diagnosis_inputs(scene, mujoco, none, none, no_distances);
  std::vector<EarlyRun> early;
  for (const Rerun& r : plan_reruns(in))
    if (r.scene.sim.dt == scene.sim.dt && !r.mujoco_unchanged && !r.mujoco_spec)
      early.push_back({r.cause, r.mujoco, r.scene});
  return early;
}

namespace {

// The re-runs at a smaller step than the scene's: 10–1000 times the steps.
bool fine_step(const Rerun& r, const Scene& scene) { return r.scene.sim.dt < scene.sim.dt; }

// The re-runs `which` on `threads` threads, each with its ref ↔ MuJoCo
// distance; an engine that throws or diverges leaves the re-run's failure.
// Each re-run's two engines are separate jobs, MuJoCo's first: a MuJoCo run
// costs 36–60 reference runs (docs/speed.md), so the longest jobs start
// first and the short ones fill the gaps. A re-run that shares another's
// reference run (ref_from) takes it after all ran, so it is computed once.
void run_reruns(std::vector<Rerun>& reruns, const std::vector<size_t>& which,
                const DiagnosisInputs& in, const EngineRunner& runner, unsigned threads,
                const std::vector<std::pair<std::string, EngineRun>>* early = nullptr) {
  struct Job {
    size_t rerun;
    bool mujoco;
  };
  std::vector<Job> jobs;
  for (const bool mujoco : {true, false})
    for (const size_t i : which) {
      Rerun& r = reruns[i];
      if (mujoco && early) {
        const auto made = std::find_if(early->begin(), early->end(),
                                       [&r](const auto& run) { return run.first == r.cause; });
        if (made != early->end()) {
          r.mujoco_run = made->second;
          continue;
        }
      }
      if (mujoco ? !r.mujoco_unchanged : r.ref && r.ref_from < 0) jobs.push_back({i, mujoco});
    }
  std::vector<std::string> failures(jobs.size());
  parallel_for(jobs.size(), threads, [&](size_t k) {
    Rerun& r = reruns[jobs[k].rerun];
    try {
      if (!jobs[k].mujoco)
        r.ref_run = runner("ref", r.scene);
      else
        r.mujoco_run = r.mujoco_spec ? engines::run_engine(*r.mujoco_spec, r.scene)
                                     : runner(r.mujoco, r.scene);
    } catch (const std::exception& e) {
      failures[k] = e.what();
    }
  });
  for (size_t k = 0; k < jobs.size(); ++k) {
    Rerun& r = reruns[jobs[k].rerun];
    if (!failures[k].empty() && r.failure.empty()) r.failure = failures[k];
  }
  for (const size_t i : which)
    if (reruns[i].mujoco_unchanged) reruns[i].mujoco_run = in.mujoco_run;
  for (const size_t i : which) {
    Rerun& r = reruns[i];
    if (r.ref_from >= 0) {
      const Rerun& from = reruns[static_cast<size_t>(r.ref_from)];
      if (!from.ref_run && r.failure.empty()) r.failure = from.failure;
      r.ref_run = from.ref_run;
    }
    if (!r.failure.empty()) continue;
    const Trajectory& a = r.ref_run ? r.ref_run->trajectory : in.ref.trajectory;
    const EngineRun* ref_side = r.ref_run ? &*r.ref_run : &in.ref;
    for (const EngineRun* run : {ref_side, static_cast<const EngineRun*>(&r.mujoco_run)})
      if (run->trajectory.divergence) r.failure = run->engine + " diverged";
    r.between = error_between(a, r.mujoco_run.trajectory);
  }
}

// The time_step re-run (Δt/10, MuJoCo's model following Δt), against which
// dt_dependent_model measures the held model.
struct FollowingModel {
  double after = kNaN;
  double impratio = kNaN;
};

FollowingModel following_model(const std::vector<Rerun>& reruns) {
  FollowingModel follow;
  for (const Rerun& r : reruns) {
    if (r.cause == "time_step" && r.failure.empty()) {
      follow.after = r.between.max_pos;
      follow.impratio = r.mujoco_run.impratio;
    }
  }
  return follow;
}

// One cause's before and after: the distance as given and with the cause
// removed, the share removed and whether that names the cause.
Finding measured_finding(const Rerun& r, double before) {
  Finding f;
  f.cause = r.cause;
  f.before = before;
  f.after = r.failure.empty() ? r.between.max_pos : kNaN;
  f.share = r.failure.empty() ? (before - f.after) / before : kNaN;
  f.named = r.failure.empty() && f.share >= kNamedShare;
  return f;
}

// "the difference goes from … m to … m (… of it removed)", or why it was
// not measured.
std::string measured_text(const Rerun& r, const Finding& f) {
  return r.failure.empty()
             ? "the difference goes from " + format_number(f.before, 3) + " m to " +
                   format_number(f.after, 3) + " m (" + percent(f.share) + " of it removed)"
             : "the run failed (" + r.failure + "), so it was not measured";
}

void explain_damping_law(Finding& f, const std::string& falls, const DiagnosisInputs& in) {
  f.fix = "--set contact.damping=kelvin_voigt";
  f.explanation =
      "The scene damps only while a point moves into the ground (damping = "
      "\"compression\"); MuJoCo's contact damper acts both ways (Kelvin–Voigt) and cannot "
      "represent it, so the two engines run different contact laws. With the Kelvin–Voigt "
      "law in both, " +
      falls + ".";
  if (in.base.converged.available)
    f.explanation += " As given, MuJoCo is " +
                     format_number(in.base.mujoco_vs_converged.max_pos, 3) +
                     " m from the converged compression-law solution.";
}

// Both engines at Δt and Δt/10 against the converged solution.
std::string time_step_against_converged(const Rerun& r, const ThreeWay& base) {
  const DenseTrajectory& c = base.converged.trajectory;
  const double ref_fine = error_against(r.ref_run->trajectory, c).max_pos;
  const double mj_fine = error_against(r.mujoco_run.trajectory, c).max_pos;
  const bool ref_larger = base.ref_vs_converged.max_pos > base.mujoco_vs_converged.max_pos;
  std::string text = " Against the converged solution: the fixed-step reference " +
                     format_number(base.ref_vs_converged.max_pos, 3) + " m at Δt, " +
                     format_number(ref_fine, 3) + " m at Δt/10; MuJoCo " +
                     format_number(base.mujoco_vs_converged.max_pos, 3) + " m, " +
                     format_number(mj_fine, 3) + " m. ";
  const bool neither_closer = ref_fine > 0.5 * base.ref_vs_converged.max_pos &&
                              mj_fine > 0.5 * base.mujoco_vs_converged.max_pos;
  if (neither_closer)
    text +=
        "Neither engine comes much closer to the converged solution: the "
        "scene magnifies a 1e-8 m change of the initial height " +
        format_number(base.converged.amplification, 3) +
        "-fold, so a smaller step changes which of the nearby trajectories "
        "each engine follows more than how close it stays.";
  else
    text += ref_larger ? "The fixed-step reference's own error is the larger part."
                       : "MuJoCo's own error is the larger part.";
  return text;
}

void explain_time_step(Finding& f, const Rerun& r, const std::string& falls,
                       const DiagnosisInputs& in) {
  f.fix = "--dt " + format_shortest(r.scene.sim.dt);
  f.explanation = "Each engine's own step error. At Δt = " + format_shortest(r.scene.sim.dt) +
                  " (ten times smaller), " + falls + ".";
  if (in.base.converged.available && r.failure.empty())
    f.explanation += time_step_against_converged(r, in.base);
  const double impratio = in.mujoco_run.impratio;
  if (in.friction && in.dt_dependent_impratio && std::isfinite(impratio) &&
      std::isfinite(r.mujoco_run.impratio) && r.mujoco_run.impratio != impratio)
    f.explanation += " The " + in.mapping + " mapping ties MuJoCo's impratio to Δt (" +
                     format_number(impratio, 3) + " at Δt, " +
                     format_number(r.mujoco_run.impratio, 3) +
                     " at Δt/10), so part of MuJoCo's change is a different model.";
}

void explain_friction(Finding& f, const std::string& falls, const DiagnosisInputs& in) {
  const Scene& scene = in.scene;
  f.fix = scene.contact.mu_roll > 0.0 ? "--set contact.mu=0 --set contact.mu_roll=0"
                                      : "--set contact.mu=0";
  f.phases = sliding_phases(scene, in.ref.trajectory, in.mujoco_run.trajectory);
  const bool cone = scene.contact.friction != FrictionLaw::Tanh;
  f.explanation =
      cone ? "Both engines run MuJoCo's friction law here (friction_law = " +
                 std::string(friction_law_name(scene.contact.friction)) +
                 "); with friction the body slides under it and, under the soft cone, hops "
                 "(the push c·μ·|v_t| on the normal force), so contacts open and close. "
                 "Without friction in both engines, " +
                 falls + "."
      : engines::option_value(in.mujoco, "friction") == "damper"
          ? "Friction laws differ: the reference's is −μ·Fn·tanh(α·v_t); MuJoCo 3's friction "
            "damper is viscous inside its elliptic cone with a stick slope fixed at the "
            "resting load (where tanh's grows with the load)" +
                (scene.contact.mu_roll > 0.0
                     ? std::string(", and its one cone holds sliding and rolling under one "
                                   "budget, so a body that slides feels no rolling torque "
                                   "(tanh's rolling resistance acts at once)")
                     : std::string()) +
                ". Without friction in both engines, " + falls + "."
          : "Friction laws differ: the reference's is −μ·Fn·tanh(α·v_t); MuJoCo's elliptic "
            "cone is viscous inside the cone and, while sliding, its damper's slip term adds "
            "to the normal force (the body hops). Without friction in both engines, " +
                falls + ".";
  if (!f.phases.empty()) {
    double grown = 0.0;
    for (const SlidingPhase& p : f.phases) grown += std::max(0.0, p.distance1 - p.distance0);
    f.explanation += " The reference slides in " + std::to_string(f.phases.size()) +
                     " phase(s); the distance grew by " + format_number(grown, 3) +
                     " m inside them";
    const size_t shown = std::min<size_t>(3, f.phases.size());
    for (size_t i = 0; i < shown; ++i) {
      const SlidingPhase& p = f.phases[i];
      f.explanation += (i ? ", " : " (largest: ") + std::string("t = ") + format_number(p.t0, 4) +
                       "–" + format_number(p.t1, 4) + " s " +
                       (p.distance1 >= p.distance0 ? "+" : "−") +
                       format_number(std::abs(p.distance1 - p.distance0), 3) + " m";
    }
    f.explanation += ").";
  }
  f.explanation += cone ? " The fix removes friction from the scene."
                        : " No MuJoCo setting reproduces the tanh law; the fix removes friction "
                          "from the scene.";
}

// friction_law (the full soft cone) and friction_shape (without its push).
void explain_friction_law(Finding& f, const Rerun& r, const std::string& falls,
                          const DiagnosisInputs& in) {
  const bool soft = r.cause == "friction_law";
  // Round-trip numbers (at least 6 digits, more where the value needs
  // them): pasted, they are MuJoCo's impratio and μ_roll' to the bit, and
  // the model writes a cone law's ratio and μ_roll as given
  // (mujoco/mjcf.hpp), so compare then runs both engines as this re-run did.
  f.fix = std::string("--set contact.friction_law=") + (soft ? "soft_cone" : "viscous_cone") +
          " --set contact.cone_ratio=" + format_shortest(r.scene.contact.cone_ratio, 6);
  if (r.scene.contact.mu_roll != in.scene.contact.mu_roll)
    f.fix += " --set contact.mu_roll=" + format_shortest(r.scene.contact.mu_roll, 6);
  f.explanation =
      soft ? "MuJoCo's friction is its soft cone, not −μ·Fn·tanh(α·v_t): viscous (slope "
             "impratio·c) inside the cone and, while sliding, a normal force raised by the "
             "push c·√((μ·v_t)² + (μ_roll·ω)²) and divided by 1 + μ²/impratio, applied "
             "halfway into the penetration (docs/physics.md). With the reference running "
             "that law (friction_law = soft_cone, at MuJoCo's impratio " +
                 format_number(r.scene.contact.cone_ratio, 3) + ") and MuJoCo as it was, " + falls +
                 ": that share of the difference is the friction law; the rest is MuJoCo's "
                 "soft contact and step."
           : "The shape of MuJoCo's friction law without its push: viscous inside the cone, "
             "μ·Fn on it, sliding and rolling under one budget, the reference's normal law "
             "unchanged (friction_law = viscous_cone). With it, " +
                 falls + ".";
  f.explanation += soft ? " The soft cone is a conformance law, not physics: it tells what "
                          "the difference is made of; the push has no physical counterpart."
                        : " What the full soft cone removes beyond this is the push.";
}

void explain_rolling_resistance(Finding& f, const std::string& falls) {
  f.fix = "--set contact.mu_roll=0";
  f.explanation =
      "Rolling resistance differs: the reference applies −μ_roll·Fn·tanh(α·R·ω) on top of "
      "its sliding friction; MuJoCo's elliptic cone puts the rolling torque and the "
      "sliding force under one budget, (f_t/μ)² + (τ/μ_roll)² ≤ Fn², and resists rolling "
      "viscously inside it. Without rolling resistance in both engines (sliding friction "
      "kept), " +
      falls + ".";
}

// calibrated against compensated, or seed and exact against calibrated.
void explain_mapping(Finding& f, const std::string& falls, const DiagnosisInputs& in) {
  const std::string& mapping = in.mapping;
  if (mapping == "calibrated") {
    f.fix = "--mapping compensated";
    f.explanation =
        "The calibrated force differs from the Kelvin–Voigt law by a relative d·A/Â and an "
        "offset d·g/Â (MuJoCo's soft contact at its smallest impedance d = 1e-4): a slightly "
        "different restitution at every impact, which a bouncing or tumbling body carries "
        "from bounce to bounce. The compensated mapping scales solref by MuJoCo's own divisor "
        "and raises Â by a lever, so that the term falls by 10⁶ (docs/mujoco.md). With the "
        "compensated mapping, " +
        falls + ".";
    return;
  }
  const Scene& scene = in.scene;
  f.fix = "--mapping calibrated";
  const double zeta = scene.contact.c / (2.0 * std::sqrt(scene.contact.k * scene.mass));
  f.explanation =
      mapping == "seed"
          ? "The seed mapping sets timeconst = √(m/k) and dampratio = ζ (here ζ = " +
                format_number(zeta, 3) +
                "), which reproduces k/m and c/m only at ζ = 1, and keeps MuJoCo's default "
                "impedance 0.9–0.95, under which gravity inside a contact is scaled by (1 − d)."
          : "The " + mapping +
                " mapping keeps MuJoCo's default impedance 0.9–0.95, under which gravity "
                "inside a contact is scaled by (1 − d) and the body rests at 5–10 % of m·g/k.";
  f.explanation += " With the calibrated mapping, " + falls + ".";
}

// Not "removed" like the others: how much the Δt/10 comparison moves when
// MuJoCo's model is held at its Δt values instead of following.
void explain_dt_dependent_model(Finding& f, const Rerun& r, const DiagnosisInputs& in,
                                const FollowingModel& follow) {
  // The re-run's step and the held model both: pasted, compare runs it.
  f.fix = "--dt " + format_shortest(r.scene.sim.dt, 6) + " --model-dt " +
          format_shortest(in.scene.sim.dt, 6);
  if (r.failure.empty() && std::isfinite(follow.after)) {
    f.share = (f.after - follow.after) / f.before;
    f.named = std::abs(f.share) >= kNamedShare;
  } else {
    f.share = kNaN;
    f.named = false;
  }
  f.explanation =
      "MuJoCo's model depends on Δt: the calibrated impratio = 1/(c·Δt·A_t) is " +
      format_number(in.mujoco_run.impratio, 3) + " at Δt and " + format_number(follow.impratio, 3) +
      " at Δt/10. Both engines at Δt/10 differ by " + format_number(follow.after, 3) +
      " m with MuJoCo's model following Δt, and by " + format_number(f.after, 3) +
      " m with it held at its Δt values (" + f.fix +
      "): the model's dependence on Δt moves the difference by " +
      percent(std::isfinite(f.share) ? std::abs(f.share) : 0.0) +
      " of its size at Δt. Hold the model with --model-dt " + format_shortest(in.scene.sim.dt, 6) +
      " to see the step's effect alone when changing --dt.";
}

void explain_refsafe(Finding& f, const std::string& falls, const DiagnosisInputs& in) {
  f.fix = "--dt " + format_shortest(in.refsafe_dt);
  f.explanation =
      "MuJoCo's refsafe raised the solref timeconst " + format_number(in.mujoco_run.solref[0], 3) +
      " s to 2·Δt = " + format_number(2.0 * in.scene.sim.dt, 3) +
      " s: a softer contact than the scene's. At Δt = " + format_shortest(in.refsafe_dt) +
      ", where it does not, " + falls + ".";
}

// The fix and the explanation of one cause.
void explain(Finding& f, const Rerun& r, const DiagnosisInputs& in, const FollowingModel& follow) {
  const std::string falls = measured_text(r, f);
  if (r.cause == "damping_law") {
    explain_damping_law(f, falls, in);
  } else if (r.cause == "time_step") {
    explain_time_step(f, r, falls, in);
  } else if (r.cause == "friction") {
    explain_friction(f, falls, in);
  } else if (r.cause == "friction_law" || r.cause == "friction_shape") {
    explain_friction_law(f, r, falls, in);
  } else if (r.cause == "rolling_resistance") {
    explain_rolling_resistance(f, falls);
  } else if (r.cause == "mapping") {
    explain_mapping(f, falls, in);
  } else if (r.cause == "dt_dependent_model") {
    explain_dt_dependent_model(f, r, in, follow);
  } else if (r.cause == "refsafe") {
    explain_refsafe(f, falls, in);
  }
}

// The grazing probe (analysis/grazing.hpp): both engines at the scene's Δt,
// sampled at every step up to the base runs' departure at 1/kGrazingGrowth
// of their difference. None when the runs are that far apart at their first
// sample (different from the start: no contact decided it), or when the
// window holds more than kMaxProbeSteps steps (56 bytes a sample, twice:
// 22 MB at the limit).
constexpr double kMaxProbeSteps = 2e5;
std::optional<Rerun> grazing_probe(const DiagnosisInputs& in) {
  const Trajectory& a = in.ref.trajectory;
  const double departure = departure_time(in.scene, a, in.mujoco_run.trajectory,
                                          in.base.ref_vs_mujoco.max_pos / kGrazingGrowth);
  if (!std::isfinite(departure) || a.samples.empty() || departure <= a.samples.front().t ||
      departure / in.scene.sim.dt > kMaxProbeSteps)
    return std::nullopt;
  Rerun r = rerun("grazing", in.scene, true, in.mujoco.name());
  if (in.mujoco.model_dt != 0.0) r.mujoco_spec = in.mujoco;
  r.scene.sim.duration = departure;
  r.scene.sim.output_dt = in.scene.sim.dt;
  return r;
}

// A point's height for the text: "1.5e-12 m above the ground", "2e-13 m into
// obstacle 1", or "clear of it" (an obstacle the run does not touch).
std::string height_text(double height, const GrazingContact& g) {
  const bool ground = g.where.find("ground") != std::string::npos;
  if (!std::isfinite(height)) return "clear of it";
  return format_number(std::abs(height), 2) + " m " +
         (height < 0.0 ? "into "
          : ground     ? "above "
                       : "from ") +
         (ground ? "the ground" : "it");
}

// What is left of the difference once the distance that decided the
// grazing contact is gone: the reference restarted from MuJoCo's own state
// at its last sample before the switch and run to the end; its largest
// distance to MuJoCo's run from there. (The distance at the switch gives a
// share of 1 − apart/before ≥ 1 − 1/kGrazingGrowth by construction; this
// one is measured.) NaN when there is no such sample or the run fails.
double after_grazing(const GrazingContact& g, const DiagnosisInputs& in,
                     const EngineRunner& runner) {
  const Sample* start = nullptr;
  for (const Sample& s : in.mujoco_run.trajectory.samples)
    if (s.t < g.t) start = &s;
  if (start == nullptr) return kNaN;
  Scene from = in.scene;
  from.initial = start->state;
  from.sim.duration = in.scene.sim.duration - start->t;
  if (!(from.sim.duration > 0.0)) return kNaN;
  try {
    EngineRun run = runner("ref", from);
    for (Sample& s : run.trajectory.samples) s.t += start->t;  // on the base runs' clock
    if (run.trajectory.divergence) return kNaN;
    return error_between(in.mujoco_run.trajectory, run.trajectory).max_pos;
  } catch (const std::exception&) {
    return kNaN;
  }
}

Finding grazing_finding(const GrazingContact& g, double before, double after,
                        const DiagnosisInputs& in) {
  Finding f;
  f.cause = "grazing";
  f.before = before;
  f.after = after;
  f.share = (before - after) / before;  // NaN when not measured
  f.named = std::isfinite(f.share) && f.share >= kNamedShare;
  const std::string mj = in.mujoco_run.engine.empty() ? "MuJoCo" : in.mujoco_run.engine;
  f.explanation =
      "At t = " + format_number(g.t, 6) + " s the body's " + g.where + " touches in " +
      (g.touches_a ? "the reference" : mj) + " and not in " + (g.touches_a ? mj : "the reference") +
      ": " + height_text(g.height_a, g) + " in the reference, " + height_text(g.height_b, g) +
      " in " + mj + "; the two runs' points are " + format_number(g.apart, 2) + " m apart there (" +
      (g.apart <= kRoundingAgreement
           ? "the same run up to rounding"
           : "what the engines' models still differ by, before any contact differs") +
      "). A contact this close to grazing is decided by that distance, not by the contact "
      "law; one engine applies a contact force the other does not, and from that step the "
      "runs part, to " +
      format_number(before, 3) + " m (" + format_number(before / g.apart, 2) +
      " times as far). No option removes it: any change of the state by that much moves the "
      "contact either way. Measured: the reference restarted from MuJoCo's state just "
      "before the switch " +
      (std::isfinite(after) ? "ends within " + format_number(after, 3) + " m of MuJoCo (" +
                                  percent(f.share) + " of the difference removed)."
                            : "could not be run, so the share is not measured.");
  if (in.base.converged.available)
    f.explanation += " The scene magnifies a 1e-8 m change of the initial height " +
                     format_number(in.base.converged.amplification, 3) + "-fold.";
  return f;
}

// Named causes first, each group by the size of its share, largest first.
void rank_findings(std::vector<Finding>& findings) {
  std::stable_sort(findings.begin(), findings.end(), [](const Finding& a, const Finding& b) {
    if (a.named != b.named) return a.named;
    const double sa = std::isfinite(a.share) ? std::abs(a.share) : -1e300;
    const double sb = std::isfinite(b.share) ? std::abs(b.share) : -1e300;
    return sa > sb;
  });
}

// One paragraph: the named causes and their shares, or that none is named.
std::string diagnosis_summary(const std::vector<Finding>& findings, double before) {
  std::string named, model, grazing;
  for (const Finding& f : findings) {
    if (!f.named) continue;
    if (f.cause == "grazing")
      grazing =
          "The engines part at a grazing contact (grazing): restarted from MuJoCo's state "
          "before it, the reference stays within " +
          format_number(f.after, 2) + " m of MuJoCo (" + percent(f.share) +
          " of the difference removed). ";
    else if (f.cause == "dt_dependent_model")
      model = " Holding MuJoCo's Δt-dependent model fixed moves the Δt/10 difference by " +
              percent(std::abs(f.share)) + " of it (dt_dependent_model).";
    else
      named += (named.empty() ? "" : ", ") + f.cause + " (" + percent(f.share) + ")";
  }
  std::string summary;
  if (named.empty())
    summary = "None of the causes re-run here takes away " + percent(kNamedShare) +
              " or more of the " + format_number(before, 3) +
              " m difference, so these runs do not attribute it (not re-run here: MuJoCo's "
              "soft-constraint contact law itself, and a tumbling body's magnification of a "
              "small early difference).";
  else
    summary = "Of the " + format_number(before, 3) +
              " m difference, removing each cause alone takes away: " + named + ".";
  return grazing + summary + model;
}

}  // namespace

Diagnosis diagnose(const Scene& scene, const engines::EngineSpec& mujoco, const EngineRun& ref,
                   const EngineRun& mujoco_run, const ThreeWay& base, const EngineRunner& runner,
                   const DiagnosisOptions& options) {
  Diagnosis dg;
  dg.ran = true;
  const TrajectoryError& d0 = base.ref_vs_mujoco;
  if (d0.max_pos <= kAgreePosition && d0.max_angle <= kAgreeAngle) {
    dg.agrees = true;
    dg.summary = "The engines agree within " + format_number(kAgreePosition, 3) + " m and " +
                 format_number(kAgreeAngle, 3) + " rad: nothing to explain.";
    return dg;
  }
  const DiagnosisInputs in = diagnosis_inputs(scene, mujoco, ref, mujoco_run, base);
  std::vector<Rerun> reruns = plan_reruns(in);
  const double before = d0.max_pos;
  // First tier: the re-runs at the scene's Δt.
  std::vector<size_t> first, fine;
  for (size_t i = 0; i < reruns.size(); ++i)
    (fine_step(reruns[i], scene) ? fine : first).push_back(i);
  // The grazing probe runs with the first tier; it removes no cause.
  const size_t causes = reruns.size();
  if (std::optional<Rerun> probe = grazing_probe(in)) {
    first.push_back(reruns.size());
    reruns.push_back(std::move(*probe));
  }
  run_reruns(reruns, first, in, runner, options.threads, options.early);
  const Rerun* explains = nullptr;  // the first tier's largest share, if it explains
  for (const size_t i : first) {
    if (i >= causes) continue;
    const Finding f = measured_finding(reruns[i], before);
    if (f.named && f.share >= kExplainedShare &&
        (!explains || f.share > measured_finding(*explains, before).share))
      explains = &reruns[i];
  }
  std::vector<bool> ran(reruns.size(), true);
  if (explains && !options.full) {
    for (const size_t i : fine) {
      ran[i] = false;
      dg.not_rerun.push_back(reruns[i].cause);
    }
    if (!fine.empty())
      dg.not_rerun_why = explains->cause + " already takes away " +
                         percent(measured_finding(*explains, before).share) +
                         " of the difference, so the re-runs at a smaller step (" +
                         format_shortest(reruns[fine.front()].scene.sim.dt) + " s and below, " +
                         "ten times the steps or more) were not made; --full-diagnosis makes them.";
  } else {
    run_reruns(reruns, fine, in, runner, options.threads);
  }
  const FollowingModel follow = following_model(reruns);
  for (size_t i = 0; i < causes; ++i) {
    if (!ran[i]) continue;
    Finding f = measured_finding(reruns[i], before);
    explain(f, reruns[i], in, follow);
    dg.findings.push_back(f);
  }
  if (reruns.size() > causes && reruns[causes].failure.empty()) {
    const Rerun& probe = reruns[causes];
    if (const std::optional<GrazingContact> g = grazing_contact(
            scene, probe.ref_run->trajectory, probe.mujoco_run.trajectory, before / kGrazingGrowth))
      dg.findings.push_back(grazing_finding(*g, before, after_grazing(*g, in, runner), in));
  }
  rank_findings(dg.findings);
  // A grazing contact is where the runs part: it leads, before the causes
  // whose removal also removes it (friction, when the body hops).
  std::stable_partition(dg.findings.begin(), dg.findings.end(),
                        [](const Finding& f) { return f.cause == "grazing"; });
  dg.summary = diagnosis_summary(dg.findings, before);
  return dg;
}

std::string missed_obstacle_contact(const Scene& scene, const engines::EngineSpec& spec,
                                    const Trajectory& run, const Trajectory& reference) {
  if (scene.obstacles.empty() || !shape_features(scene.shape).corners) return "";
  if (engines::option_value(spec, "geometry") != "corners") return "";
  const Model model = make_model(scene);
  ContactSet contacts(model);
  // A contact point farther than this from every corner of the body is not
  // a corner's (1 % of the body's smallest extent between two corners).
  double spacing = std::numeric_limits<double>::infinity();
  const std::vector<Vec2>& points = model.body.points;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      spacing = std::min(spacing, (points[i] - points[j]).norm());
  const double tolerance = 0.01 * spacing;
  double deepest_reference = 0.0;  // of its obstacle contacts
  for (const Sample& s : reference.samples) {
    if (!s.state.q.allFinite()) break;
    find_contacts(model, s.state.q, contacts);
    for (const Contact& k : contacts)
      if (k.obstacle >= 0) deepest_reference = std::max(deepest_reference, k.depth);
  }
  const bool v2 = spec.kind == "mujoco";
  for (const Sample& s : run.samples) {
    const Vec3& q = s.state.q;
    if (!q.allFinite()) break;
    find_contacts(model, q, contacts);
    const double c = std::cos(q.z()), sn = std::sin(q.z());
    for (const Contact& k : contacts) {
      if (k.obstacle < 0) continue;
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec2& p : points) {
        const Vec2 r(c * p.x() - sn * p.y(), sn * p.x() + c * p.y());
        nearest = std::min(nearest, (r - k.r()).norm());
      }
      if (nearest <= tolerance) {  // a corner's contact: MuJoCo's sphere is there
        const bool box =
            scene.obstacles[static_cast<size_t>(k.obstacle)].shape == ObstacleShape::Box;
        if (v2 && box && k.depth > 2.0 * deepest_reference + 1e-6)
          return "MuJoCo 2.2.2 has no spring where the reference has one: at t = " +
                 format_number(s.t, 4) + " s a corner of the body is " + format_number(k.depth, 3) +
                 " m inside obstacle " + std::to_string(k.obstacle) +
                 ", more than twice the reference's deepest (" +
                 format_number(deepest_reference, 3) +
                 " m). 2.2.2's sphere-box collider gives a sphere whose centre is inside the box "
                 "the depth -radius whatever the true depth, and the corners geometry's spheres "
                 "(radius 1e-9 m) are inside as soon as they touch, so only the damper acts and "
                 "the body sinks in. MuJoCo 3 computes the depth (the engine mujoco3), or use "
                 "the geometry that avoids it: mujoco:" +
                 engines::option_value(spec, "mapping") + ":boxes (--geometry boxes).";
        continue;
      }
      return "MuJoCo has no contact where the reference has one: at t = " + format_number(s.t, 4) +
             " s a corner of obstacle " + std::to_string(k.obstacle) + " is " +
             format_number(k.depth, 3) + " m inside the body's face (" + format_number(nearest, 3) +
             " m from its nearest corner), and the corners geometry puts MuJoCo's geoms at the "
             "body's corners only, so MuJoCo makes no contact there and the body passes into "
             "the obstacle. Use the geometry that sees it: " +
             std::string(spec.kind) + ":" + engines::option_value(spec, "mapping") +
             ":boxes (--geometry boxes).";
    }
  }
  return "";
}

std::vector<std::string> version_notes(const Comparison& c) {
  // An option's value, or the fallback the engine gives it when left out.
  auto value = [](const engines::EngineSpec& spec, std::string_view name) {
    std::string v = spec.option(name);
    if (const engines::EngineInfo* info = engines::find_engine(spec.kind); v.empty() && info)
      for (const engines::EngineOption& o : info->options)
        if (o.name == name) v = std::string(o.fallback);
    return v;
  };
  std::vector<std::string> notes;
  for (const ComparedRun& two : c.runs) {
    if (two.spec.kind != "mujoco") continue;
    for (const ComparedRun& three : c.runs) {
      if (three.spec.kind != "mujoco3") continue;
      const double apart = error_between(two.run.trajectory, three.run.trajectory).max_pos;
      std::string note = two.label + " (MuJoCo 2.2.2) <-> " + three.label +
                         " (MuJoCo 3.14): " + format_number(apart, 4) + " m. ";
      const bool damper = value(three.spec, "friction") == "damper" && c.scene.contact.mu > 0.0;
      if (value(two.spec, "mapping") != value(three.spec, "mapping") ||
          value(two.spec, "geometry") != value(three.spec, "geometry")) {
        note += "Their models differ in mapping or geometry (" + two.spec.name() + ", " +
                three.spec.name() + "): compare one mapping on both to see the versions alone.";
      } else if (const auto off = std::find_if(
                     two.run.warnings.begin(), two.run.warnings.end(),
                     [](const std::string& w) {
                       return w.rfind("MuJoCo 2.2.2 made a contact off the body", 0) == 0;
                     });
                 off != two.run.warnings.end()) {
        note += "Not rounding: " + *off + ". Against the reference 2.2.2 is " +
                format_number(two.vs_first.max_pos, 3) + " m away, 3.14 " +
                format_number(three.vs_first.max_pos, 3) + " m.";
      } else if (damper) {
        note +=
            "MuJoCo 3's friction damper (--friction damper) is the cause: its friction rows "
            "have a damper of their own, which takes away the push mu*c*|v_t| that 2.2.2's "
            "shared damper puts on the normal force; against the reference 2.2.2 is " +
            format_number(two.vs_first.max_pos, 3) + " m away, 3.14 " +
            format_number(three.vs_first.max_pos, 3) + " m (docs/mujoco3.md).";
      } else {
        note +=
            "The same contact law on both: the model for MuJoCo 3 undoes its three changes "
            "(3.0's effective mass of a slide-only body, 3.9's margin/gap, 3.11's early "
            "exits; docs/mujoco3.md), so what is left is rounding of two builds, as far as "
            "this scene amplifies it.";
      }
      notes.push_back(note);
    }
  }
  return notes;
}

}  // namespace contact2d::analysis
