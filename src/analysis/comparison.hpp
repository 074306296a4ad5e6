// What `contact2d compare` measures: the fixed-step reference and MuJoCo
// against each other AND against the converged solution, and a diagnosis
// of their difference obtained by re-running without each suspected cause.
//
// Three distances. Two engines that disagree tell nothing about which is
// right; the converged reference (reference/dense_reference.hpp: adaptive
// Dormand–Prince 5(4) with every contact switch located, run at a tight
// tolerance) solves the scene's ODE to a known precision and referees:
//   ref ↔ converged      the fixed-step reference's own error (its Δt, its
//                        integrator);
//   MuJoCo ↔ converged   everything MuJoCo does differently: its step, its
//                        soft-constraint contact law, its friction cone;
//   ref ↔ MuJoCo         what `compare` always printed.
// The converged solution's own error is bounded by its distance to the run
// at 10× the tolerance (the convention of `sweep`). Scenes it refuses
// (static obstacles) get the two-way comparison and say why.
//
// The diagnosis. A difference is explained only by measurement: for each
// cause that applies to the scene, both engines are re-run with that cause
// alone removed, and the share of the ref ↔ MuJoCo maximum position
// distance that goes away, (before − after)/before, is reported with the
// exact option that removes it. Causes and the run that removes each:
//   damping_law   compression-only damper, which MuJoCo cannot represent:
//                 --set contact.damping=kelvin_voigt
//   time_step     the engines' own step errors: --dt Δt/10 (with the
//                 three-way distances at both steps, which says whose error
//                 it was)
//   friction      the tanh law against MuJoCo's elliptic cone: μ = μ_roll = 0;
//                 the sliding phases of the reference and how much the
//                 distance grew inside each are listed
//   dt_dependent_model  (calibrated with friction: impratio = 1/(c·Δt·A_t))
//                 both engines at Δt/10 with MuJoCo's model held at its Δt
//                 values (--model-dt Δt); its share is how far that moves
//                 the Δt/10 difference, (held − following)/before, named
//                 when |share| ≥ kNamedShare
//   friction_law  the reference re-run under MuJoCo's effective law
//                 (--set contact.friction_law=soft_cone at MuJoCo's
//                 impratio), MuJoCo unchanged: the share that is the law
//   friction_shape  the same with the cone's shape alone, without its push
//                 (viscous_cone): the share that is the shape
//   rolling_resistance  with sliding friction kept, μ_roll = 0 (MuJoCo's
//                 cone shares one budget between sliding and rolling)
//   mapping       a mapping other than calibrated (seed is exact only at
//                 ζ = 1): --mapping calibrated
//   refsafe       MuJoCo raised a standard-form timeconst to 2·Δt (a softer
//                 contact): a Δt at which it does not
// And one probe, which removes nothing: both engines sampled at every step
// up to where they part (analysis/grazing.hpp). A point touching in one
// engine and not the other while the runs are within 1/kGrazingGrowth of
// their final difference is a grazing contact: named first, with its time,
// the point and its heights in both runs, and no fix.
// A cause is named when removing it takes away at least kNamedShare of the
// distance; the others are kept as measured-and-ruled-out. Each share is
// measured with that cause alone removed, so shares of overlapping causes
// can add up to more than one. When the engines already agree to the
// project's goal (1e-5 m, 1e-4 rad) nothing is re-run and nothing named.
//
// Two tiers, by cost. The re-runs at the scene's Δt (damping_law, friction,
// friction_law, friction_shape, rolling_resistance, mapping) cost about
// one base run each and run first. The ones at a smaller step (time_step,
// dt_dependent_model, refsafe) step MuJoCo 10–1000 times as often — on the
// box, 400k of a full diagnosis's 480k MuJoCo steps — and run only when
// the first tier leaves the difference unexplained: when none of its causes
// takes away kExplainedShare or more. Otherwise they are listed as not
// re-run, with the share that explained it; DiagnosisOptions::full (compare
// --full-diagnosis) runs them regardless. No run is computed twice: re-runs
// whose reference scene is the same (time_step and dt_dependent_model
// both step the reference at Δt/10) share the one reference run.
#pragma once

#include <string>
#include <vector>

#include "analysis/engine.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/scene.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {

// The converged solution where the dense reference can run.
struct ConvergedSolution {
  bool available = false;
  std::string why_not;  // when not available: the dense reference's reason
  DenseTrajectory trajectory;
  double tol = 0.0;        // rtol = atol
  double own_error = 0.0;  // m: max position distance to the run at 10·tol
  double seconds = 0.0;    // wall clock of one run
  // How much the scene magnifies a change of the initial height by
  // δ = 1e-8 m: the largest position deviation of the converged solution
  // over the run, divided by δ (1 for a body that only falls and rests;
  // 1e4 and more for a tumbling box, whose engines then part ways after
  // any small difference).
  double amplification = 0.0;
};
ConvergedSolution converged_solution(const Scene& scene, double tol);

struct ThreeWay {
  ConvergedSolution converged;
  TrajectoryError ref_vs_converged;     // zero when !converged.available
  TrajectoryError mujoco_vs_converged;  // zero when !converged.available
  TrajectoryError ref_vs_mujoco;
};
ThreeWay three_way(const Scene& scene, const Trajectory& ref, const Trajectory& mujoco, double tol);

// Below these the engines agree and there is nothing to diagnose (the
// project's frictionless agreement goal).
constexpr double kAgreePosition = 1e-5;  // m
constexpr double kAgreeAngle = 1e-4;     // rad
// A cause whose removal takes away at least this share of the distance is
// named.
constexpr double kNamedShare = 0.2;
// The first tier explains the difference when one of its causes takes away
// this share or more: the larger part of it. Shares of separate causes do
// not add (each is measured with that cause alone removed), so no share
// proves that a fine-step cause could not also be named beside it (on the
// shipped scenes: stiff_k1e9's time_step, 20 % beside damping_law's
// 100 %); DiagnosisOptions::full measures them regardless.
constexpr double kExplainedShare = 0.5;

// A time interval of the reference run in which some contact point slides
// (|v_t| ≥ 1/α: the tanh law past its regularised zone), with the
// ref ↔ MuJoCo position distance at its ends.
struct SlidingPhase {
  double t0 = 0.0, t1 = 0.0;
  double distance0 = 0.0, distance1 = 0.0;  // m
};

struct Finding {
  // damping_law | time_step | friction | friction_law | friction_shape |
  // rolling_resistance | mapping | refsafe | dt_dependent_model | grazing
  // (grazing: before = the difference, after = the runs' distance at the
  // switch, no fix)
  std::string cause;
  std::string explanation;           // for a newcomer, numbers included
  std::string fix;                   // the exact option that removes the cause
  double before = 0.0;               // m: ref ↔ MuJoCo max position distance as given
  double after = 0.0;                // m: the same with the cause removed
  double share = 0.0;                // (before − after)/before
  bool named = false;                // share ≥ kNamedShare
  std::vector<SlidingPhase> phases;  // friction: the sliding phases, largest growth first
};

struct Diagnosis {
  bool ran = false;               // false: --no-diagnosis
  bool agrees = false;            // within kAgreePosition and kAgreeAngle: nothing re-run
  std::vector<Finding> findings;  // named first, each group by share, largest first
  std::string summary;            // one paragraph
  // The fine-step causes not re-run because the first tier explained the
  // difference (empty after a full diagnosis), and why, in one sentence.
  std::vector<std::string> not_rerun;
  std::string not_rerun_why;
  // MuJoCo 3's friction damper, where a run has it on a scene with
  // friction (compare's measure): that run against the reference with it
  // and re-run with MuJoCo's shared damper, and what that says, one
  // paragraph per run.
  std::vector<std::string> damper_notes;
};

// A MuJoCo run of the first tier that depends on the scene and the engine
// alone (friction, rolling_resistance, mapping), so that compare can make it
// beside the base runs, before the diagnosis is asked for.
struct EarlyRun {
  std::string cause;
  std::string engine;  // the engine's name, as the runner takes it
  Scene scene;
};
std::vector<EarlyRun> early_reruns(const Scene& scene, const engines::EngineSpec& mujoco);

struct DiagnosisOptions {
  // Also run the fine-step re-runs when the first tier explains the
  // difference (compare --full-diagnosis).
  bool full = false;
  unsigned threads = 0;  // as parallel_for: 0 = default_threads()
  // MuJoCo runs already made (early_reruns), by cause: used instead of
  // running them again. A cause missing here (its run threw) is run.
  const std::vector<std::pair<std::string, EngineRun>>* early = nullptr;
};

// `mujoco` is the MuJoCo engine of the base run. The base runs and their
// three-way numbers are passed in; every extra run goes through `runner`.
Diagnosis diagnose(const Scene& scene, const engines::EngineSpec& mujoco, const EngineRun& ref,
                   const EngineRun& mujoco_run, const ThreeWay& base,
                   const EngineRunner& runner = registry_runner(),
                   const DiagnosisOptions& options = {});

// The sliding phases of a run (exposed for tests).
std::vector<SlidingPhase> sliding_phases(const Scene& scene, const Trajectory& ref,
                                         const Trajectory& mujoco);

}  // namespace contact2d::analysis
