// The three-way comparison (analysis/comparison.hpp) against a closed form,
// and the diagnosis's bookkeeping with runners of the test's own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "analysis/comparison.hpp"
#include "benchmarks/oscillator.hpp"
#include "io/scene_file.hpp"

namespace contact2d {
namespace {

// An undamped point mass bouncing on the ground (k = 1e4 N/m, m = 1 kg,
// c = 0, μ = 0, contact point h = 0.05 m below the COM), dropped from rest at
// y0 = 0.3 m: flight, a harmonic contact about y = h − m·g/k, flight again,
// repeating without loss — benchmarks::bouncing_height (oscillator.hpp) with
// the apex y0 − h and k/m = 1e4 1/s².
constexpr double kY0 = 0.3, kH = 0.05, kK = 1e4, kG = 9.81;

Scene bouncing_point() {
  return parse_scene(
      "scene = \"point_mass\"\n[body]\nmass = 1.0\nhalf_height = 0.05\n"
      "[contact]\nk = 1e4\nc = 0\nmu = 0\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.3\n[sim]\ndt = 1e-4\nduration = 2.0\ngravity = 9.81\n",
      "bouncing point");
}

// The body's centre: the contact point's height above the ground plus h.
double closed_form_y(double t) { return kH + benchmarks::bouncing_height(kG, kK, kY0 - kH, t); }

// The closed form as a sampled trajectory at the run's sample times.
Trajectory closed_form_like(const Trajectory& run) {
  Trajectory t = run;
  for (Sample& s : t.samples) {
    s.state.q = Vec3(0.0, closed_form_y(s.t), 0.0);
    s.state.v = Vec3::Zero();  // velocities are not compared below
  }
  return t;
}

TEST(ThreeWay, ConvergedColumnEqualsTheClosedForm) {
  const Scene scene = bouncing_point();
  const engines::EngineRun ref = engines::run_engine("ref", scene);
  Scene coarse = scene;
  coarse.sim.dt = 1e-3;  // stands in for the second engine: a visibly different run
  const engines::EngineRun other = engines::run_engine("ref", coarse);
  ASSERT_FALSE(ref.trajectory.divergence);
  ASSERT_FALSE(other.trajectory.divergence);
  const analysis::ThreeWay three =
      analysis::three_way(scene, ref.trajectory, other.trajectory, 1e-12);
  ASSERT_TRUE(three.converged.available) << three.converged.why_not;

  // The converged solution against the closed form at every sample: DOPRI5
  // at tol 1e-12 with located impacts; measured 4.4e-11 m over the bounces of 2 s
  // (its error estimate, own_error, is printed alongside). 1e-8 m leaves a
  // factor 100 for rounding in the located events; a wrong contact time or
  // a missed bounce would be off by millimetres.
  double worst = 0.0;
  for (const Sample& s : ref.trajectory.samples)
    worst =
        std::max(worst, std::abs(three.converged.trajectory.at(s.t).q.y() - closed_form_y(s.t)));
  std::printf("converged vs closed form: %.3g m (own error %.3g m)\n", worst,
              three.converged.own_error);
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(three.converged.own_error, 1e-8);

  // Each "against converged" column is the run's distance to the closed
  // form, to within the converged solution's distance to it (triangle
  // inequality on the maxima).
  const analysis::TrajectoryError ref_exact =
      analysis::error_between(ref.trajectory, closed_form_like(ref.trajectory));
  const analysis::TrajectoryError other_exact =
      analysis::error_between(other.trajectory, closed_form_like(other.trajectory));
  std::printf("ref: %.6g m vs closed form %.6g m; coarse: %.6g vs %.6g m\n",
              three.ref_vs_converged.max_pos, ref_exact.max_pos, three.mujoco_vs_converged.max_pos,
              other_exact.max_pos);
  EXPECT_NEAR(three.ref_vs_converged.max_pos, ref_exact.max_pos, worst + 1e-15);
  EXPECT_NEAR(three.mujoco_vs_converged.max_pos, other_exact.max_pos, worst + 1e-15);
  // And the runs really are apart from the closed form (the test can fail).
  EXPECT_GT(ref_exact.max_pos, 1e3 * worst);
  // The third column is what compare always printed.
  EXPECT_DOUBLE_EQ(three.ref_vs_mujoco.max_pos,
                   analysis::error_between(ref.trajectory, other.trajectory).max_pos);
  // A falling and bouncing point magnifies a height change about as much as
  // a bounce shifts it in time: order one, not the thousands of a tumbling box.
  EXPECT_GT(three.converged.amplification, 0.5);
  EXPECT_LT(three.converged.amplification, 1e3);
}

TEST(ThreeWay, ObstaclesFallBackToTwoWayAndSayWhy) {
  Scene scene = bouncing_point();
  scene.sim.duration = 0.2;
  scene.obstacles.push_back(make_box_obstacle(1.0, 0.1, 0.1, 0.2));
  const engines::EngineRun ref = engines::run_engine("ref", scene);
  const analysis::ThreeWay three =
      analysis::three_way(scene, ref.trajectory, ref.trajectory, 1e-10);
  EXPECT_FALSE(three.converged.available);
  EXPECT_NE(three.converged.why_not.find("obstacle"), std::string::npos) << three.converged.why_not;
  EXPECT_EQ(three.ref_vs_converged.samples, 0u);
}

// The diagnosis with a runner of the test's own: an "engine" that is the
// reference with its damping law forced to Kelvin–Voigt behaves like MuJoCo
// on the damping law and nothing else, so exactly that cause must be named,
// with the share the runs show.
// The bouncing point with a compression-only damper, and its runs: the
// reference, and the stand-in "MuJoCo" (the reference with Kelvin–Voigt
// damping), each through `runner`, which records the Δt of every run.
struct DampingStandIn {
  Scene scene = bouncing_point();
  std::vector<double> steps;
  analysis::EngineRunner runner;
  engines::EngineSpec spec;
  engines::EngineRun ref, kv;
  analysis::ThreeWay three;

  DampingStandIn() {
    scene.contact.c = 20.0;
    scene.contact.damping = DampingLaw::Compression;
    runner = [this](const std::string& engine, const Scene& s) {
      steps.push_back(s.sim.dt);
      Scene t = s;
      if (engine != "ref") t.contact.damping = DampingLaw::KelvinVoigt;
      engines::EngineRun run = engines::run_engine("ref", t);
      run.engine = engine;
      return run;
    };
    spec.kind = "mujoco";
    spec.set("mapping", "calibrated");
    ref = runner("ref", scene);
    kv = runner(spec.name(), scene);
    three = analysis::three_way(scene, ref.trajectory, kv.trajectory, 1e-10);
    steps.clear();
  }
  DampingStandIn(const DampingStandIn&) = delete;  // the runner points to this one
  DampingStandIn& operator=(const DampingStandIn&) = delete;
  analysis::Diagnosis diagnose(bool full) {
    return analysis::diagnose(scene, spec, ref, kv, three, runner, {full, 1});
  }
};

TEST(Diagnosis, NamesOnlyTheCauseThatTheReRunsRemove) {
  DampingStandIn stand_in;
  const analysis::Diagnosis d = stand_in.diagnose(false);
  ASSERT_FALSE(d.agrees);
  ASSERT_FALSE(d.findings.empty());
  EXPECT_EQ(d.findings[0].cause, "damping_law");
  EXPECT_TRUE(d.findings[0].named);
  // Both sides run the same law then: the same trajectory, bit for bit.
  EXPECT_EQ(d.findings[0].after, 0.0);
  EXPECT_EQ(d.findings[0].share, 1.0);
  EXPECT_EQ(d.findings[0].fix, "--set contact.damping=kelvin_voigt");
  for (size_t i = 1; i < d.findings.size(); ++i) {
    EXPECT_FALSE(d.findings[i].named) << d.findings[i].cause << " " << d.findings[i].share;
  }
}

TEST(Diagnosis, AgreeingEnginesAreNotReRun) {
  const Scene scene = bouncing_point();
  int runs = 0;
  const analysis::EngineRunner runner = [&runs](const std::string&, const Scene& s) {
    ++runs;
    return engines::run_engine("ref", s);
  };
  const engines::EngineRun ref = engines::run_engine("ref", scene);
  engines::EngineSpec spec;
  spec.kind = "mujoco";
  const analysis::ThreeWay three =
      analysis::three_way(scene, ref.trajectory, ref.trajectory, 1e-10);
  const analysis::Diagnosis d =
      analysis::diagnose(scene, spec, ref, ref, three, runner, {false, 1});
  EXPECT_TRUE(d.agrees);
  EXPECT_TRUE(d.findings.empty());
  EXPECT_EQ(runs, 0);
}

// The two tiers with the damping-law stand-in of the test above, whose
// first tier explains the whole difference: the re-run at Δt/10 is made
// only when asked (full), and otherwise listed as not re-run with the
// share that explained the difference.
TEST(Diagnosis, TheFineStepReRunIsMadeOnlyWhenTheFirstTierLeavesTheDifferenceUnexplained) {
  DampingStandIn stand_in;
  const std::vector<double>& steps = stand_in.steps;
  const Scene& scene = stand_in.scene;
  const analysis::Diagnosis screened = stand_in.diagnose(false);
  for (const double dt : steps) EXPECT_EQ(dt, scene.sim.dt);
  EXPECT_EQ(screened.not_rerun, std::vector<std::string>{"time_step"});
  EXPECT_NE(screened.not_rerun_why.find("damping_law already takes away 100 %"), std::string::npos)
      << screened.not_rerun_why;
  for (const analysis::Finding& f : screened.findings) EXPECT_NE(f.cause, "time_step");
  const size_t first_tier_runs = steps.size();

  stand_in.steps.clear();
  const analysis::Diagnosis full = stand_in.diagnose(true);
  EXPECT_TRUE(full.not_rerun.empty());
  EXPECT_EQ(full.findings.size(), screened.findings.size() + 1);
  // The first tier's runs again, and the Δt/10 re-run's two.
  ASSERT_EQ(steps.size(), first_tier_runs + 2);
  EXPECT_EQ(std::count(steps.begin(), steps.end(), scene.sim.dt / 10.0), 2);
}

TEST(SlidingPhases, ABoxSlidingToRestIsOnePhaseAndARestingOneNone) {
  Scene scene = parse_scene(
      "scene = \"box\"\n[body]\nmass = 1.0\nwidth = 0.4\nheight = 0.2\n"
      "[contact]\nk = 1e5\nc = 600\nmu = 0.5\nalpha = 100\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.0999\nvx = 1.0\n[sim]\ndt = 1e-4\nduration = 1.0\n",
      "sliding box");
  const engines::EngineRun run = engines::run_engine("ref", scene);
  const auto phases = analysis::sliding_phases(scene, run.trajectory, run.trajectory);
  ASSERT_EQ(phases.size(), 1u);
  // Sliding at μ·g decelerates 1 m/s to rest in 1/(μ·g) = 0.204 s; the phase
  // ends when the slip falls below 1/α = 0.01 m/s, 0.002 s earlier, give or
  // take the 1e-3 s sampling and the landing transient.
  EXPECT_NEAR(phases[0].t0, 0.0, 2e-3);
  EXPECT_NEAR(phases[0].t1, 1.0 / (0.5 * 9.81) - 0.01 / (0.5 * 9.81), 3e-3);
  scene.initial.v = Vec3::Zero();
  const engines::EngineRun rest = engines::run_engine("ref", scene);
  EXPECT_TRUE(analysis::sliding_phases(scene, rest.trajectory, rest.trajectory).empty());
}

}  // namespace
}  // namespace contact2d
