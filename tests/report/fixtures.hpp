// Hand-written result structs for the page tests: small, fixed values chosen
// by hand (not produced by running the code under test), each page's cases
// covered: winners with a clear and a close second, goals met and missed,
// diverged and failed runs, missing orders, unbounded theory, a MuJoCo-less
// bench row, outcomes with warnings and with status 2 and 3.
#pragma once

#include <cmath>

#include "report/results.hpp"

namespace contact2d::report::fixtures {

inline ComparisonRow comparison(double max_pos, double max_angle, double impratio = 1e-15) {
  ComparisonRow c;
  c.shape = "box";
  c.mujoco_integrator = "Euler";
  c.dt = 1e-4;
  c.duration = 2.0;  // 2e4 steps
  c.max_pos = max_pos;
  c.rms_pos = max_pos / 2;
  c.max_angle = max_angle;
  c.max_vel = 10 * max_pos;
  c.end_pos = max_pos / 4;
  c.impratio = impratio;
  c.ref_seconds = 0.002;    // 0.1 µs per step
  c.mujoco_seconds = 0.05;  // 2.5 µs per step
  return c;
}

// MuJoCo 3.14 beside 2.2.2 in the README's fixture: every case within
// rounding of 2.2.2 (2e-13 m) except box / exact with the Kelvin–Voigt law
// (0.03 m against 2.2.2's 0.02 m, 0.01 m apart), the box's friction goal
// (0.005 m, 0.001 m apart) and the random scene s01 (0.02 m with friction,
// 0.01 m apart); its damper helps on a sliding point mass (0.00165 → 7e-08
// m) and hurts on the T (0.018 → 0.338 m).
inline void add_mujoco3(ReadmeData& d) {
  d.kelvin_voigt_v3 = d.kelvin_voigt;
  for (MappingCase& c : d.kelvin_voigt_v3) {
    c.v2_vs_v3 = 2e-13;
    if (c.scene == "box" && c.mapping == "exact") {
      c.result.max_pos = 0.03;
      c.v2_vs_v3 = 0.01;
    }
  }
  for (ThreeWayCase& c : d.three_way) {
    c.ref_vs_v3 = c.ref_vs_mujoco;
    c.v2_vs_v3 = 2e-13;
  }
  for (GoalCase& g : d.goals) {
    g.v3_max_pos = g.result.max_pos;
    g.v3_max_angle = g.result.max_angle;
    g.v3_rest = g.friction_rest;
    g.v2_vs_v3 = 0.0;
    if (g.label == "box, c = 200, friction") {
      g.v3_max_pos = 0.005;
      g.v2_vs_v3 = 0.001;
    }
  }
  d.random_v3 = d.random;
  d.random_compensated_v3 = d.random_compensated;
  for (std::vector<RandomCase>* runs : {&d.random_v3, &d.random_compensated_v3}) {
    for (RandomCase& c : *runs) c.v2_vs_v3 = 2e-13;
  }
  d.random_v3[1].max_pos_friction = 0.02;
  d.random_v3[1].v2_vs_v3 = 0.01;
  d.damper_helps = {{"point mass sliding to rest",
                     "contact2d compare validation/report/friction/point_slide.toml", 0.00165,
                     7e-8}};
  d.damper_hurts = {{"the built-in tshape with the Kelvin–Voigt law",
                     "contact2d compare validation/scenes/tshape.toml --set "
                     "contact.damping=kelvin_voigt",
                     0.018, 0.338}};
}

inline ReadmeData readme() {
  ReadmeData d;
  d.scenes = {"point_mass", "box"};
  d.mappings = {"seed", "exact", "calibrated"};
  // point_mass: calibrated 0.1 m, next exact 0.25 m (2.5×); box: exact 0.02,
  // next calibrated 0.03 (1.5×). Means: seed √(0.5·0.2) = 0.316,
  // exact √(0.25·0.02) = 0.0707, calibrated √(0.1·0.03) = 0.0548.
  const double errors[2][3] = {{0.5, 0.25, 0.1}, {0.2, 0.02, 0.03}};
  for (size_t s = 0; s < 2; ++s) {
    for (size_t m = 0; m < 3; ++m) {
      d.shipped.push_back({d.scenes[s], d.mappings[m], comparison(errors[s][m], 0.01 * (m + 1))});
      d.kelvin_voigt.push_back(
          {d.scenes[s], d.mappings[m], comparison(errors[s][m] / 10, 0.001 * (m + 1))});
    }
  }
  d.goals = {{"point_mass, c = 200, frictionless", 1e-5, 1e-4, comparison(2e-6, 0)},
             {"box, c = 200, frictionless", 1e-5, 1e-4, comparison(3e-6, 2e-4)},
             {"box, c = 200, friction", 3e-3, std::nullopt, comparison(0.004, 0.5, 12.5),
              // shape, push, rest (analysis::friction_parts)
              3e-5, 0.0041, 9e-10}};
  d.geometry = {{"box", false, "corners", comparison(1.2e-6, 5e-6)},
                {"box", true, "boxes", comparison(0.002, 0.008)}};
  d.integrators = {{"box", "rk4", comparison(1.1e-6, 4.9e-6)}};
  d.integrators.back().result.mujoco_integrator = "RK4";
  // Three-way rows: a diagnosed scene with two causes (shares 0.954 → "95 %",
  // 0.585 → "59 %"), one where the engines agree, one without a converged
  // solution; one animation.
  ThreeWayCase diagnosed;
  diagnosed.scene = "point_mass";
  diagnosed.law = "as shipped";
  diagnosed.converged = true;
  diagnosed.ref_vs_converged = 0.0028;
  diagnosed.mujoco_vs_converged = 0.525;
  diagnosed.ref_vs_mujoco = 0.524;
  diagnosed.amplification = 3.1;
  diagnosed.causes = {{"damping_law", 0.954, "--set contact.damping=kelvin_voigt"},
                      {"friction", 0.585, "--set contact.mu=0"}};
  diagnosed.animation = "point_mass.gif";
  ThreeWayCase agrees = diagnosed;
  agrees.law = "Kelvin–Voigt";
  agrees.ref_vs_mujoco = 2e-6;
  agrees.agrees = true;
  agrees.causes.clear();
  agrees.animation.clear();
  ThreeWayCase unconverged = agrees;
  unconverged.scene = "box";
  unconverged.converged = false;
  unconverged.agrees = false;
  unconverged.ref_vs_mujoco = 0.01;
  d.three_way = {diagnosed, agrees, unconverged};
  d.named_share = 0.2;
  d.random_dir = "validation/report/random";
  d.replay.ran = true;
  d.replay.replay = "validation/replays/goal.replay";
  d.replay.radius = 0.11;
  d.replay.engines = {{"ref", "goal", "{\"goal\":true}"}, {"mujoco", "goal", "{\"goal\":true}"}};
  d.replay.part_1cm = 0.38;  // the radius parting left out: printed as "never"
  d.replay.plot = "goal_replay.png";
  d.random_config = {42, 4, 1e-5, 1e-4};
  // ζ = c/(2√(k·m)) chosen so that √(k·m) is round: s00 √(0.5·2e4) = 100,
  // ζ = 30/200 = 0.15; s01 √(2·5000) = 100, ζ = 0.5; s02 √(1.25·3e5) = 612.4,
  // ζ = 1500/1224.7 = 1.22; s03 √(0.1·1e5) = 100, ζ = 0.25. Bands: ζ < 0.3
  // s00 (reached) and s03 (missed), median (2e-6 + 3e-4)/2 = 1.51e-4;
  // 0.3–1 s01 (angle 2e-4 misses); ≥ 1 s02 (2e-5 misses).
  // With friction (the last three: shape, push, rest): medians over the four
  // scenes (0.002 + 0.01)/2 = 0.006 with friction, shape (2e-6 + 4e-5)/2 =
  // 2.1e-5, push (0.002 + 0.01)/2 = 0.006, rest (1e-9 + 3e-9)/2 = 2e-9, the
  // largest rest 2e-6 (s02, a tumbling T); 1 of 4 within 1e-3 m, all four
  // with the reference under MuJoCo's law.
  d.random = {{"s00", "point_mass", 0.5, 20000, 30, 0.5, 2e-6, 0, 0.001, 1e-6, 0.001, 1e-9},
              {"s01", "box", 2, 5000, 100, 0.1, 5e-6, 2e-4, 0.01, 4e-5, 0.01, 3e-9},
              {"s02", "tshape", 1.25, 300000, 1500, 1, 2e-5, 1e-5, 0.1, 0.05, 0.09, 2e-6},
              {"s03", "circle", 0.1, 100000, 50, 0.3, 3e-4, 1e-9, 0.002, 2e-6, 0.002, 5e-10}};
  // The same scenes under compensated: all four frictionless within the
  // goal, so every band reports its whole count.
  d.random_compensated = {{"s00", "point_mass", 0.5, 20000, 30, 0.5, 1e-11, 0, 0.0009},
                          {"s01", "box", 2, 5000, 100, 0.1, 2e-12, 3e-11, 0.011},
                          {"s02", "tshape", 1.25, 300000, 1500, 1, 4e-13, 1e-12, 0.1},
                          {"s03", "circle", 0.1, 100000, 50, 0.3, 3e-12, 1e-14, 0.001}};
  add_mujoco3(d);
  return d;
}

// The README's fixture without MuJoCo 3.14 (as a build without Node).
inline ReadmeData readme_without_mujoco3() {
  ReadmeData d = readme();
  d.mujoco3_not_run = "node not found";
  d.kelvin_voigt_v3.clear();
  d.random_v3.clear();
  d.random_compensated_v3.clear();
  d.damper_helps.clear();
  d.damper_hurts.clear();
  const double nan = std::nan("");
  for (ThreeWayCase& c : d.three_way) c.ref_vs_v3 = c.v2_vs_v3 = nan;
  for (GoalCase& g : d.goals) g.v3_max_pos = g.v3_max_angle = g.v3_rest = g.v2_vs_v3 = nan;
  return d;
}

inline SweepRun run(const char* engine, const char* integrator, double dt, const char* status,
                    double max_pos, double seconds, std::optional<double> self = std::nullopt) {
  SweepRun r;
  r.engine = engine;
  r.integrator = integrator;
  r.dt = dt;
  r.status = status;
  r.max_pos = max_pos;
  r.seconds = seconds;
  r.self_max_pos = self;
  return r;
}

inline SweepRun dense(double tol, double max_pos, double seconds) {
  SweepRun r = run("ref", "dopri5_events", 0.0, "ok", max_pos, seconds);
  r.tol = tol;
  return r;
}

inline SceneSweep scene_sweep(const std::string& name, double scale) {
  SceneSweep s;
  s.name = name;
  s.scene = name == "point_mass_kv" ? "point_mass" : name;
  if (name != "point_mass_kv") {
    s.study = {{1e-3, true, 0.01 * scale, 0.0004, 10},
               {1e-12, true, 1e-11 * scale, 0.002, 12},
               {1e-13, false, 0, 0, 0}};
    s.amplification = 3.5 * scale;
  }
  s.runs = {run("ref", "semi_implicit_euler", 1e-3, "ok", 0.05 * scale, 0.0001),
            run("ref", "semi_implicit_euler", 1e-4, "ok", 0.005 * scale, 0.001),
            run("ref", "rk4", 1e-3, "diverged", 0, 0),
            run("ref", "rk4", 1e-4, "ok", 0.0005 * scale, 0.003),
            run("mujoco", "semi_implicit_euler", 1e-3, "ok", 0.2 * scale, 0.01, 0.02),
            run("mujoco", "semi_implicit_euler", 2e-4, "ok", 0.15 * scale, 0.05, 0.004),
            run("mujoco", "semi_implicit_euler", 1e-4, "ok", 0.1 * scale, 0.1),
            run("mujoco", "rk4", 1e-4, "failed", 0, 0),
            dense(1e-4, 2e-4 * scale, 0.0002),
            dense(1e-8, 1e-7 * scale, 0.0008)};
  OrderRow euler{"ref", "semi_implicit_euler", "reference", 1, 1.004, 0.012, 2, 1e-4, 1e-3, ""};
  OrderRow rk4{"ref", "rk4", "reference", 4, 4.61, 0.14, 3, 2e-4, 1e-3, "impacts: c·|v_n| jumps"};
  OrderRow none{"mujoco", "rk4", "own finest", 4, std::nullopt, 0, 1, 0, 0, "too few runs"};
  s.orders = {euler, rk4, none};
  return s;
}

inline SweepData sweep() {
  SweepData d;
  d.mujoco = true;
  d.engines = "ref,mujoco";
  d.mujoco_dts = "1e-3,5e-4,2e-4,1e-4";
  d.scenes = {"point_mass", "circle"};
  d.sweeps = {scene_sweep("point_mass", 1), scene_sweep("circle", 0.1),
              scene_sweep("point_mass_kv", 0.01)};
  d.bench.ran = true;
  d.bench.command = "contact2d_bench --benchmark_min_time=0.2";
  // Ratios 1000/20 = 50, 4000/50 = 80, 2000/200 = 10; the circle has no MuJoCo row.
  d.bench.rows = {{"point_mass", "semi_implicit_euler", 20, 20.5, 1000, 1001},
                  {"point_mass", "rk4", 50, 50.5, 4000, 4001},
                  {"point_mass", "implicit_euler", 200, 201, 2000, 2001},
                  {"circle", "semi_implicit_euler", 30, 30.5, std::nullopt, std::nullopt}};
  d.bench.sincos_ns = 26.1;
  d.bench.tanh_ns = 41.6;
  d.bench.free_flight_ns = 10.1;
  d.info = {2, "1.00 0.50 0.25", 30, 10, 12};
  return d;
}

inline StabilityRow srow(const char* engine, const char* integrator, double k,
                         std::optional<double> theory, const char* verdict, double dt_stable,
                         double omega, const char* failure = "", const char* note = "") {
  StabilityRow r;
  r.engine = engine;
  r.integrator = integrator;
  r.k = k;
  r.theory = theory;
  r.verdict = verdict;
  r.dt_stable = dt_stable;
  r.dt_unstable = dt_stable * 1.02;
  r.dt_min = 1e-6;
  r.dt_max = 0.01;
  r.omega_dt_stable = omega * dt_stable;
  r.failure = failure;
  r.note = note;
  return r;
}

inline StabilityData stability() {
  StabilityData d;
  d.mujoco = true;
  d.scenes = {"point_mass", "box"};
  const double nan = std::nan("");
  StabilityMap pm{"point_mass", "point_mass", {}};
  pm.rows = {
      srow("ref", "explicit_euler", 1e3, 2, "stable at dt_max", 0.01, 31.6),
      srow("ref", "explicit_euler", 1e5, 2, "bracketed", 0.0016, 316, "energy gain at t = 0.5 s"),
      srow("ref", "explicit_euler", 1e7, 2, "bracketed", 0.00017, 3162, "energy gain at t = 0.2 s"),
      srow("ref", "semi_implicit_euler", 1e5, 0.828, "bracketed", 0.0027, 316,
           "penetration at t = 1 s"),
      srow("ref", "rk4", 1e5, 2.79, "bracketed", 0.009, 316, "energy gain at t = 1 s"),
      srow("ref", "implicit_euler", 1e3, std::nullopt, "stable at dt_max", 0.01, 31.6),
      srow("ref", "implicit_euler", 1e5, std::nullopt, "stable at dt_max", 0.01, 316),
      srow("ref", "implicit_euler", 1e9, std::nullopt, "bracketed", 0.00024, 31623,
           "Newton failed at t = 0.1 s")};
  StabilityMap box{"box", "box", {}};
  box.rows = {
      srow("ref", "explicit_euler", 1e5, 2, "bracketed", 0.0011, 700, "energy gain at t = 0.3 s"),
      srow("ref", "implicit_euler", 1e9, std::nullopt, "unstable at dt_min", nan, 31623,
           "Newton failed at t = 0 s")};
  d.reference = {pm, box};
  // The point mass (1 kg) with c = 20 at every k: ζ = 20/(2√k).
  StabilityRow soft = srow("ref", "explicit_euler", 1e3, 0.632, "stable at dt_max", 0.01, 31.6);
  soft.c = 20;
  soft.zeta = 0.316;
  StabilityRow stiff =
      srow("ref", "explicit_euler", 1e9, 0.000632, "bracketed", 3.8e-6, 31623, "energy gain");
  stiff.c = 20;
  stiff.zeta = 0.000316;
  d.scene_c = {"point_mass_scene_c", "point_mass", {soft, stiff}};
  d.mujoco_scenes = {"point_mass"};
  StabilityMap mj{"mujoco.point_mass", "point_mass", {}};
  StabilityRow a = srow("mujoco", "semi_implicit_euler", 1e4, 0.828, "bracketed", 0.008, 100,
                        "MuJoCo warning: Nan", "");
  a.penetration = 0.002;
  a.reference_penetration = 0.001;
  StabilityRow b = srow("mujoco:exact", "semi_implicit_euler", 1e8, 0.828, "stable at dt_max", 0.01,
                        10000, "", "refsafe: penetration 5x the small step's");
  b.penetration = 0.5;
  b.penetration_small_step = 0.1;
  StabilityRow c =
      srow("mujoco", "rk4", 1e8, 2.79, "unstable at dt_min", nan, 10000, "energy gain");
  mj.rows = {a, b, c};
  d.mujoco_maps = {mj};
  return d;
}

inline ExtremeCase extreme_case(const char* path, std::vector<std::string> expected, int status,
                                const char* text) {
  ExtremeCase c;
  c.path = path;
  c.expected = std::move(expected);
  c.ref.status = status;
  c.ref.text = text;
  return c;
}

inline ExtremeData extreme() {
  ExtremeData d;
  ExtremeCase alpha = extreme_case(
      "validation/scenes/extreme/large_alpha.toml",
      {"exit 0", "final x in [0.1, 0.2]", "after 0.3: max |vx| <= 4.9e-4"}, 0,
      "point_mass [ref, semi_implicit_euler, dt = 0.0001 s, 2 s in 12.5 ms]: final x = 0.102 m, "
      "|v| = 0.0004 m/s\n");
  alpha.mujoco = EngineOutcome();
  alpha.mujoco->text =
      "contact2d: mujoco warning: Nan, Inf or huge value\n"
      "point_mass [mujoco, semi_implicit_euler, dt = 0.0001 s, 2 s in 99 ms]: final x = 0.101 m\n";
  d.cases.push_back(alpha);
  d.cases.push_back(extreme_case(
      "validation/scenes/extreme/stiff.toml", {"exit 3", "diagnostic \"exceeds; the limit\""}, 3,
      "contact2d: validation/scenes/extreme/stiff.toml: simulation diverged at t = 0.3 s\n"));
  ExtremeCase bad = extreme_case("validation/scenes/extreme/bad.toml", {}, 2,
                                 "contact2d: bad.toml: body.mass = -1 is out of range\n");
  bad.mujoco = bad.ref;
  d.cases.push_back(bad);
  return d;
}

}  // namespace contact2d::report::fixtures
