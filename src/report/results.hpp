// The report's own result structs: plain data that the seam (report/runs.hpp)
// fills from the engines and analyses, and that the page writers
// (report/pages.hpp) turn into Markdown. Nothing here runs anything, so the
// pages can be tested on hand-written values. Times are wall clock (they vary
// from run to run); everything else is deterministic for a given build.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace contact2d::report {

// ------------------------------------------------------------ README.md

// One `compare` of a scene on the reference and MuJoCo.
struct ComparisonRow {
  std::string shape;              // "point_mass", …
  std::string mujoco_integrator;  // "Euler", "RK4", "implicit"
  double dt = 0.0, duration = 0.0;
  double max_pos = 0.0, rms_pos = 0.0, max_angle = 0.0, max_vel = 0.0, end_pos = 0.0;
  double impratio = 0.0;
  double ref_seconds = 0.0, mujoco_seconds = 0.0;  // wall clock of the stepping
};

// A built-in scene through `contact2d compare` (calibrated mapping): the
// three distances and the diagnosis's named causes (section 1a).
struct CauseShare {
  std::string cause;  // "damping_law", …
  double share = 0.0;
  std::string fix;
};
struct ThreeWayCase {
  std::string scene;
  std::string law;  // "as shipped" or "Kelvin–Voigt"
  bool converged = false;
  double ref_vs_converged = 0.0, mujoco_vs_converged = 0.0, ref_vs_mujoco = 0.0;  // max pos, m
  double amplification = 0.0;
  bool agrees = false;
  std::vector<CauseShare> causes;  // named causes, largest share first
  // The fine-step causes the diagnosis did not re-run (another explained
  // the difference; compare --full-diagnosis makes them).
  std::vector<std::string> not_rerun;
  std::string animation;  // file name in the report directory; empty: not drawn
  // MuJoCo 3.14 on the same scene (the model written for it, the same
  // mapping): its distance to the reference and to 2.2.2 (m, NaN when
  // MuJoCo 3 did not run), and its animation beside the reference when it
  // differs from 2.2.2 by more than rounding (empty otherwise).
  double ref_vs_v3 = std::numeric_limits<double>::quiet_NaN();
  double v2_vs_v3 = std::numeric_limits<double>::quiet_NaN();
  std::string animation_v3;
};

// The shipped goal replay on both engines (section 9).
struct ReplayEngine {
  std::string engine;   // "ref", "mujoco"
  std::string outcome;  // "goal", …
  std::string json;     // what `play --headless --replay` prints
};
struct ReplayComparison {
  bool ran = false;
  std::string replay;  // the file
  std::vector<ReplayEngine> engines;
  std::optional<double> part_1cm, part_radius;  // s: first time the balls are 0.01 m / R apart
  double radius = 0.0;                          // m
  std::string plot;                             // file name in the report directory
  // The window's video of the goal (scripts/record-goal: goal.gif and
  // goal.mp4 in validation/report/), in the report directory; empty when
  // it has not been recorded.
  std::string gif, mp4;
};

// Every scene under every mapping (sections 1 and 2).
struct MappingCase {
  std::string scene, mapping;
  ComparisonRow result;
  // In MuJoCo 3.14's list (ReadmeData::kelvin_voigt_v3): the largest
  // distance between 3.14's and 2.2.2's positions (m); NaN in 2.2.2's.
  double v2_vs_v3 = std::numeric_limits<double>::quiet_NaN();
};

// A line of the goal table (section 3): the verdict is computed by the page.
struct GoalCase {
  std::string label;
  double pos_goal = 0.0;
  std::optional<double> angle_goal;  // none: only the position is a goal
  ComparisonRow result;
  // With friction: its difference taken apart (RandomCase's three parts);
  // NaN for a frictionless case.
  double friction_shape = std::numeric_limits<double>::quiet_NaN();
  double friction_push = std::numeric_limits<double>::quiet_NaN();
  double friction_rest = std::numeric_limits<double>::quiet_NaN();
  // MuJoCo 3.14 on the same case (NaN when it did not run): against the
  // reference (max pos, max angle), the rest (with friction), and its
  // distance to 2.2.2.
  double v3_max_pos = std::numeric_limits<double>::quiet_NaN();
  double v3_max_angle = std::numeric_limits<double>::quiet_NaN();
  double v3_rest = std::numeric_limits<double>::quiet_NaN();
  double v2_vs_v3 = std::numeric_limits<double>::quiet_NaN();
};

struct GeometryCase {
  std::string scene;
  bool friction = false;
  std::string geometry;  // "corners", "boxes"
  ComparisonRow result;
};

struct IntegratorCase {
  std::string scene;
  std::string integrator;  // the reference's name
  ComparisonRow result;
};

// A scene drawn at random (section 6), run without and with friction.
struct RandomCase {
  std::string name;  // "s00", …
  std::string shape;
  double mass = 0.0, k = 0.0, c = 0.0, mu = 0.0;
  double max_pos_frictionless = 0.0, max_angle_frictionless = 0.0;
  double max_pos_friction = 0.0;
  // With friction, the difference taken apart (analysis::friction_parts,
  // the same mapping): the cone's shape, its push, and the rest (the
  // reference under MuJoCo's own law against MuJoCo).
  double friction_shape = 0.0, friction_push = 0.0, friction_rest = 0.0;
  // In a list of MuJoCo 3.14's runs (ReadmeData::random_v3): the largest
  // distance between 3.14 and 2.2.2 over both runs (m); NaN in 2.2.2's.
  double v2_vs_v3 = std::numeric_limits<double>::quiet_NaN();
};

// MuJoCo 3.14's friction damper (`--friction damper`, compensated) on one
// scene: the reference ↔ 3.14 without it and with it (m), and the command
// that prints both with kDamperEngines' two engines.
inline constexpr const char* kDamperEngines[2] = {"mujoco3:compensated",
                                                  "mujoco3:compensated:corners:damper"};
struct DamperCase {
  std::string label;    // "point mass sliding to rest", …
  std::string command;  // "contact2d compare SCENE [--set …]", without the engine
  double without = std::numeric_limits<double>::quiet_NaN();
  double with = std::numeric_limits<double>::quiet_NaN();
};

struct RandomConfig {
  std::uint64_t seed = 0;
  int count = 0;
  double pos_goal = 0.0, angle_goal = 0.0;  // the frictionless goal
};

struct ReadmeData {
  std::vector<std::string> scenes;    // in page order
  std::vector<std::string> mappings;  // in page order
  std::vector<MappingCase> shipped;
  std::vector<MappingCase> kelvin_voigt;
  std::vector<ThreeWayCase> three_way;
  // Scenes whose shipped and Kelvin–Voigt runs are the same (calibrated:
  // every error equal), whose second plot the page leaves out.
  std::vector<std::string> law_independent;
  std::string random_dir;
  ReplayComparison replay;  // where the random scenes' files are, as the reader types it
  double converged_tol = 1e-12;
  double named_share = 0.0;    // a cause is named from this share on (analysis::kNamedShare)
  std::string animation_note;  // why there are no animations, when there are none
  std::vector<GoalCase> goals;
  std::vector<GeometryCase> geometry;
  std::vector<IntegratorCase> integrators;
  RandomConfig random_config;
  std::vector<RandomCase> random;  // under the default mapping, calibrated
  // The same scenes under the compensated mapping (empty: not run), which
  // removes the calibrated force's O(d) term: the step the report shows.
  std::vector<RandomCase> random_compensated;
  // MuJoCo 3.14 (the model written for it; `--engine mujoco3`) on the same
  // cases, each list empty when it did not run (mujoco3_not_run says why):
  // section 2's Kelvin–Voigt runs, the random scenes under each mapping
  // (their shape and push are the reference's, as 2.2.2's), and its
  // friction damper where it helps most and where it hurts most.
  std::string mujoco3_not_run;
  std::vector<MappingCase> kelvin_voigt_v3;
  std::vector<RandomCase> random_v3, random_compensated_v3;
  std::vector<DamperCase> damper_helps, damper_hurts;
};

// ------------------------------------------------------------- sweep.md

struct StudyRow {  // the reference at one tolerance against tol 1e-14
  double tol = 0.0;
  bool ok = true;
  double max_pos = 0.0;
  double seconds = 0.0;
  long long events = 0;
};

struct SweepRun {
  std::string engine;      // "ref", "mujoco"
  std::string integrator;  // "rk4", …; "dopri5_events" for the adaptive method
  double dt = 0.0;         // 0 for the adaptive method
  double tol = 0.0;        // the adaptive method's tolerance
  std::string status;      // "ok", "diverged", "failed"
  double max_pos = 0.0;
  std::optional<double> self_max_pos;  // against the engine's own finest run
  double seconds = 0.0;
};

struct OrderRow {
  std::string engine, integrator, against;
  double nominal = 0.0;
  std::optional<double> observed;
  double observed_stderr = 0.0;
  int points = 0;
  double dt_min = 0.0, dt_max = 0.0;
  std::string note;
};

struct SceneSweep {
  std::string name;             // "point_mass", …, "point_mass_kv": names the plot
  std::string scene;            // the scene's shape, as the analysis names it
  std::vector<StudyRow> study;  // empty for a sweep without a reference study
  double amplification = 0.0;
  std::vector<SweepRun> runs;
  std::vector<OrderRow> orders;
};

struct BenchRow {
  std::string scene, integrator;
  double ref_cpu_ns = 0.0, ref_real_ns = 0.0;
  std::optional<double> mj_cpu_ns, mj_real_ns;  // none without MuJoCo
};

struct Bench {
  bool ran = false;
  std::string command;  // "contact2d_bench --benchmark_min_time=0.2"
  std::vector<BenchRow> rows;
  double sincos_ns = -1.0, tanh_ns = -1.0, free_flight_ns = -1.0;
  // The scenes whose contact points turn with θ (a sincos on every force
  // evaluation's chain): the box and the T; a point mass never turns, a
  // disc's point stays below its centre.
  std::vector<std::string> turning;
};

struct RunInfo {  // how this run went: all of it varies
  unsigned cores = 0;
  std::string load;  // the 1, 5 and 15 minute load averages
  long long total_seconds = 0, sweep_seconds = 0, stability_seconds = 0;
};

struct SweepData {
  bool mujoco = false;
  std::string engines;     // "ref,mujoco"
  std::string mujoco_dts;  // "1e-3,5e-4,2e-4,1e-4"
  std::vector<std::string> scenes;
  std::vector<SceneSweep> sweeps;  // the scenes, then point_mass_kv
  Bench bench;
  RunInfo info;
};

// --------------------------------------------------------- stability.md

struct StabilityRow {
  std::string engine, integrator;
  double k = 0.0, c = 0.0;       // N/m, N·s/m
  double zeta = 0.0;             // damping ratio at that k
  std::optional<double> theory;  // none: unconditionally stable (∞)
  std::string verdict;           // analysis::verdict_name()
  double dt_stable = 0.0, dt_unstable = 0.0, dt_min = 0.0, dt_max = 0.0;
  double omega_dt_stable = 0.0;  // NaN when no Δt was stable
  std::optional<double> penetration, penetration_small_step, reference_penetration;
  std::string failure;  // how the first unstable probe failed
  std::string note;
};

struct StabilityMap {
  std::string name;   // "point_mass", "point_mass_scene_c", "mujoco.box", …: names the plot
  std::string scene;  // the scene's shape, as the analysis names it
  std::vector<StabilityRow> rows;
};

struct StabilityData {
  bool mujoco = false;
  std::vector<std::string> scenes;
  std::vector<StabilityMap> reference;  // the scenes at ζ = 1
  StabilityMap scene_c;                 // the point mass with its own c
  std::vector<std::string> mujoco_scenes;
  std::vector<StabilityMap> mujoco_maps;
};

// ----------------------------------------------------------- extreme.md

// What `contact2d simulate` would have answered: its exit status and its
// output, standard error (warnings, diagnostic) before standard output (the
// summary line "shape [engine, …]: final x = …").
struct EngineOutcome {
  int status = 0;
  std::string text;
};

struct ExtremeCase {
  std::string path;                   // "validation/scenes/extreme/large_alpha.toml"
  std::vector<std::string> expected;  // the file's "# expect:" lines
  EngineOutcome ref;
  std::optional<EngineOutcome> mujoco;  // none without MuJoCo
};

struct ExtremeData {
  std::vector<ExtremeCase> cases;
};

}  // namespace contact2d::report
