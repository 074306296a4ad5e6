// The sweep: what it measures, the observed orders it fits, and how it
// reports runs that diverge or fail.
#include <gtest/gtest.h>

#include <sched.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "analysis/sweep.hpp"
#include "analysis/tables.hpp"
#include "io/scene_file.hpp"

namespace contact2d::analysis {
namespace {

Scene built_in(const char* name) {
  return load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + name + ".toml");
}

const OrderFit& fit_of(const SweepResult& r, Integrator integrator,
                       const std::string& engine = "ref",
                       const std::string& against = "reference") {
  for (const OrderFit& f : r.orders) {
    if (f.integrator == integrator && f.engine == engine && f.against == against) return f;
  }
  throw std::runtime_error("no fit");
}

TEST(LogLogSlope, RecoversAPowerLaw) {
  const std::vector<double> x{1e-4, 2e-4, 5e-4, 1e-3};
  std::vector<double> y;
  for (double v : x) y.push_back(3.0 * v * v * v);
  double se = 1.0;
  EXPECT_NEAR(log_log_slope(x, y, &se), 3.0, 1e-12);
  EXPECT_LT(se, 1e-12);
  y[1] *= 2.0;  // scatter shows up in the standard error
  log_log_slope(x, y, &se);
  EXPECT_GT(se, 0.1);
}

TEST(ParallelFor, RunsEveryIndexOnceAndRethrows) {
  std::vector<std::atomic<int>> hits(1000);
  parallel_for(hits.size(), 2, [&](size_t i) { ++hits[i]; });
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
  std::atomic<int> ran{0};
  EXPECT_THROW(parallel_for(50, 2,
                            [&](size_t i) {
                              ++ran;
                              if (i == 7) throw std::runtime_error("task 7");
                            }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 50);  // the other tasks still ran
}

// The default thread count follows the CPU set the scheduler gives the
// caller (taskset, a Slurm job's cgroup), not the machine's core count: with
// this thread narrowed to one CPU it is 1, and back to what it was after.
TEST(ParallelFor, DefaultThreadsFollowTheCpuSetWeMayRunOn) {
  cpu_set_t before;
  CPU_ZERO(&before);
  ASSERT_EQ(sched_getaffinity(0, sizeof(before), &before), 0);
  const unsigned all = default_threads();
  EXPECT_EQ(all, static_cast<unsigned>(CPU_COUNT(&before)));
  int first = 0;
  while (!CPU_ISSET(first, &before)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);
  const unsigned narrowed = default_threads();
  ASSERT_EQ(sched_setaffinity(0, sizeof(before), &before), 0);
  EXPECT_EQ(narrowed, 1U);
  EXPECT_EQ(default_threads(), all);
}

// Every row's error is the distance of that run's own samples to the
// reference: recomputing one row directly must give the same numbers
// (bit for bit: the same deterministic run and the same comparison).
TEST(Sweep, ErrorsAreTheRunsDistanceToTheReference) {
  Scene scene = built_in("point_mass");
  scene.sim.duration = 1.0;
  SweepConfig config;
  config.integrators = {Integrator::SemiImplicitEuler, Integrator::RK4};
  config.dts = {4e-4, 2e-4, 1e-4};
  config.repeats = 1;
  config.dense_tols = {1e-6};
  const SweepResult r = run_sweep(scene, config);
  ASSERT_EQ(r.rows.size(), 6u);
  EXPECT_LT(r.reference_error, 1e-9);  // measured 1.1e-10 m
  for (const SweepRow& row : r.rows) {
    ASSERT_EQ(row.status, RunStatus::Ok) << row.message;
    EXPECT_TRUE(std::isfinite(row.error.max_pos));
    EXPECT_GE(row.error.max_pos, row.error.end_pos);
    EXPECT_EQ(row.error.end_time, 1.0);
    EXPECT_GT(row.seconds, 0.0);
    EXPECT_EQ(row.repeats, 1);
  }
  Scene s = scene;
  s.sim.integrator = Integrator::RK4;
  s.sim.dt = 2e-4;
  const TrajectoryError direct = error_against(simulate(s), r.reference.trajectory);
  const SweepRow& row = r.rows[4];
  ASSERT_EQ(row.integrator, Integrator::RK4);
  ASSERT_EQ(row.dt, 2e-4);
  EXPECT_EQ(row.error.max_pos, direct.max_pos);
  EXPECT_EQ(row.error.end_pos, direct.end_pos);
  // The finest run of each integrator has no own-finest distance; the others do.
  EXPECT_FALSE(r.rows[2].self_error);
  EXPECT_TRUE(r.rows[0].self_error);
  ASSERT_EQ(r.dense_curve.size(), 1u);
  EXPECT_TRUE(r.dense_curve[0].failure.empty());
}

// The rolling disc has no impact (it starts at its resting penetration with
// the damper off, one event in 3.5 s) and smooth tanh friction, so every
// method shows its nominal order. Measured: 1.00 ± 1e-5 for the three Euler
// methods, 4.6 ± 0.1 for RK4 (dt 1e-3..2e-4; at 1e-4 RK4 reaches the
// rounding floor). Bands: ±0.1 for the Euler methods (10⁴ standard errors,
// yet it fails for any method that is not first order); RK4 ≥ 3.5, which
// fails if anything cost it its order (impacts give ≈ 1).
TEST(Sweep, SmoothSceneShowsNominalOrders) {
  const Scene scene = built_in("circle");
  SweepConfig config;
  config.dts = {1e-3, 5e-4, 2e-4, 1e-4};
  config.repeats = 1;
  config.dense_tols = {};
  const SweepResult r = run_sweep(scene, config);
  for (Integrator integrator :
       {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::ImplicitEuler}) {
    const OrderFit& f = fit_of(r, integrator);
    ASSERT_TRUE(f.order) << integrator_name(integrator) << ": " << f.note;
    EXPECT_NEAR(*f.order, 1.0, 0.1) << integrator_name(integrator);
    EXPECT_TRUE(f.note.empty()) << f.note;
  }
  const OrderFit& rk4 = fit_of(r, Integrator::RK4);
  ASSERT_TRUE(rk4.order) << rk4.note;
  EXPECT_GT(*rk4.order, 3.5);
}

// Impacts cost RK4 its order, by how smooth the force is at contact entry:
// with damping the force jumps by c·|v| (an O(Δt) velocity error per impact:
// first order); without damping only its slope jumps (O(Δt²): second order).
// Point mass bouncing for 2 s, μ = 0, seven steps 1e-3..1e-5. Measured:
// 0.92 ± 0.3 with c = 20 and 2.2 ± 0.3 with c = 0; the error constant
// depends erratically on where each impact falls inside its step, hence the
// spread. Bands of about two standard errors: below 1.6 with damping, 1.6..2.8
// without; a method that kept its fourth order fails both.
TEST(Sweep, ImpactsCostRK4ItsOrder) {
  Scene scene = built_in("point_mass");
  scene.contact.mu = 0.0;
  SweepConfig config;
  config.integrators = {Integrator::RK4};
  config.repeats = 1;
  config.dense_tols = {};
  const SweepResult damped = run_sweep(scene, config);
  const OrderFit& f1 = fit_of(damped, Integrator::RK4);
  ASSERT_TRUE(f1.order) << f1.note;
  EXPECT_LT(*f1.order, 1.6);
  EXPECT_NE(f1.note.find("jumps"), std::string::npos) << f1.note;

  scene.contact.c = 0.0;
  const SweepResult undamped = run_sweep(scene, config);
  const OrderFit& f2 = fit_of(undamped, Integrator::RK4);
  ASSERT_TRUE(f2.order) << f2.note;
  EXPECT_GT(*f2.order, 1.6);
  EXPECT_LT(*f2.order, 2.8);
  EXPECT_NE(f2.note.find("second order"), std::string::npos) << f2.note;
}

// A diverged run is reported with the divergence rule's diagnostic and kept
// out of the error columns and the fit; an engine that cannot run is a
// failed row. No "nan" or "inf" reaches the table or the CSV.
TEST(Sweep, DivergedAndFailedRunsAreReportedNotMeasured) {
  Scene scene = built_in("point_mass");
  scene.contact.k = 1e6;  // ω = 1000: explicit Euler at ω·Δt = 1 with ζ = 0.01 blows up
  scene.sim.duration = 1.0;
  SweepConfig config;
  config.engines = {"ref", "other"};
  config.integrators = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler};
  config.dts = {1e-3, 1e-4};
  config.repeats = 1;
  config.dense_tols = {1e-5};
  const EngineRunner runner = [](const std::string& engine, const Scene& s) -> EngineRun {
    if (engine == "other") throw std::runtime_error("other engine: not installed");
    return engines::run_engine("ref", s);
  };
  const SweepResult r = run_sweep(scene, config, runner);
  ASSERT_EQ(r.rows.size(), 6u);  // "other" offers no explicit Euler (like MuJoCo)
  const SweepRow& blown = r.rows[0];
  ASSERT_EQ(blown.status, RunStatus::Diverged);
  EXPECT_NE(blown.message.find("diverged"), std::string::npos) << blown.message;
  EXPECT_EQ(r.rows[4].status, RunStatus::Failed);
  EXPECT_NE(r.rows[4].message.find("not installed"), std::string::npos);

  std::ostringstream table;
  print_sweep(table, r);
  EXPECT_EQ(table.str().find("nan"), std::string::npos) << table.str();
  EXPECT_EQ(table.str().find("inf"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("diverged at t"), std::string::npos);
  char* buffer = nullptr;
  size_t size = 0;
  std::FILE* mem = open_memstream(&buffer, &size);
  write_sweep_csv(mem, r);
  write_orders_csv(mem, r);
  std::fclose(mem);
  const std::string csv(buffer, size);
  std::free(buffer);
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("inf"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",diverged,"), std::string::npos);
}

TEST(Sweep, RejectsBadLists) {
  const Scene scene = built_in("point_mass");
  SweepConfig config;
  config.dts = {};
  EXPECT_THROW(run_sweep(scene, config), std::invalid_argument);
  config.dts = {1e-4, 5.0};  // longer than the 2 s run
  EXPECT_THROW(run_sweep(scene, config), std::invalid_argument);
  config.dts = {1e-4};
  config.integrators = {};
  EXPECT_THROW(run_sweep(scene, config), std::invalid_argument);
  EXPECT_THROW(parse_integrators({"rk4", "leapfrog"}), std::invalid_argument);
  EXPECT_EQ(parse_integrators({"rk4", "rk4", "implicit_euler"}).size(), 2u);
}

}  // namespace
}  // namespace contact2d::analysis
