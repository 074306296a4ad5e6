// contact2d_bench_versions: MuJoCo 3.14 (the engine mujoco3: WebAssembly in
// one Node process, stepped in batches) against native MuJoCo 2.2.2, per
// step, on the four shipped scenes at their Δt, in one run:
//
//   mj_step/SCENE          bare native mj_step (2.2.2) on the scene's model
//   mujoco/SCENE           MujocoStepper::step: 2.2.2 through the Stepper
//                          interface (it also runs the reference's contact
//                          stage on each state, for the divergence monitor)
//   mujoco3/SCENE          Mujoco3Stepper::step: the same for MuJoCo 3, its
//                          batch requests to Node included
//
// Each model is the calibrated one the engine generates (mujoco3: written
// for MuJoCo 3). Node's start (~1 s) is paid once, before timing, and each
// stepper first runs 50,000 steps untimed: the WebAssembly JIT runs the
// first ~20,000 several times slower (docs/mujoco3.md). Steppers replay
// their scene and start over after sim.duration. The goal (issue: ≤ 2×) is
// the ratio mujoco3 / mujoco, printed at the end.
//
//   build-dir/bench/contact2d_bench_versions [--benchmark_min_time=0.5]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3/stepper.hpp"

namespace {

using namespace contact2d;

const char* const kScenes[] = {"point_mass", "box", "tshape", "circle"};

Scene scene_of(const std::string& name) {
  return load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + name + ".toml");
}

void bare_mj_step(benchmark::State& state, const std::string& name) {
  const Scene scene = scene_of(name);
  const mujoco::GeneratedModel g = mujoco::generate_mjcf(scene, mujoco::MjcfOptions{});
  const mujoco::ModelPtr m = mujoco::load_model(g.xml, name);
  const mujoco::DataPtr d = mujoco::make_data(m.get());
  const long long steps = step_count(scene.sim);
  mj_resetDataKeyframe(m.get(), d.get(), 0);
  long long i = 0;
  for (auto _ : state) {
    mj_step(m.get(), d.get());
    if (++i == steps) {
      i = 0;
      mj_resetDataKeyframe(m.get(), d.get(), 0);
    }
  }
}

// A stepper replaying its scene, warmed up once and kept across the
// benchmark's repeated calls.
void stepper_step(benchmark::State& state, Stepper* stepper, const Scene& scene) {
  const long long steps = step_count(scene.sim);
  const State start = initial_state(scene);
  long long i = 0;
  stepper->reset(start);
  stepper->plan(steps);
  for (auto _ : state) {
    stepper->step();
    if (++i == steps) {
      i = 0;
      stepper->reset(start);
      stepper->plan(steps);
    }
  }
}

std::map<std::string, std::unique_ptr<Stepper>>& steppers() {
  static std::map<std::string, std::unique_ptr<Stepper>> all;
  return all;
}

void warm_up(Stepper& stepper, const Scene& scene) {
  const long long steps = step_count(scene.sim);
  for (long long done = 0; done < 50000;) {
    stepper.reset(initial_state(scene));
    stepper.plan(steps);
    for (long long i = 0; i < steps && done < 50000; ++i, ++done) stepper.step();
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string missing = mujoco3::missing();
  if (!missing.empty()) {
    std::fprintf(stderr, "contact2d_bench_versions: %s\n", missing.c_str());
    return 2;
  }
  static std::map<std::string, Scene> scenes;
  for (const char* name : kScenes) {
    const Scene scene = scene_of(name);
    scenes[name] = scene;
    auto two = std::make_unique<mujoco::MujocoStepper>(scene, mujoco::MjcfOptions{});
    auto three = std::make_unique<mujoco3::Mujoco3Stepper>(scene, mujoco::MjcfOptions{});
    warm_up(*two, scene);
    warm_up(*three, scene);
    steppers()[std::string("mujoco/") + name] = std::move(two);
    steppers()[std::string("mujoco3/") + name] = std::move(three);
  }
  for (const char* name : kScenes) {
    const std::string n = name;
    benchmark::RegisterBenchmark(("mj_step/" + n).c_str(), bare_mj_step, n);
    for (const char* kind : {"mujoco", "mujoco3"}) {
      const std::string key = std::string(kind) + "/" + n;
      benchmark::RegisterBenchmark(key.c_str(), stepper_step, steppers()[key].get(), scenes[n]);
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  // Wall clock: mujoco3's work is done in the Node process, not on this
  // process's CPU time.
  class Collect : public benchmark::ConsoleReporter {
   public:
    void ReportRuns(const std::vector<Run>& runs) override {
      for (const Run& r : runs)
        if (r.run_type == Run::RT_Iteration) wall[r.benchmark_name()] = r.GetAdjustedRealTime();
      ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, double> wall;  // ns per step
  } reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nper step, wall clock (mujoco3 runs in Node: its CPU is not this process's)\n");
  std::printf("%-11s %12s %12s %12s %16s %16s\n", "scene", "mj_step", "mujoco", "mujoco3",
              "mujoco3/mujoco", "mujoco3/mj_step");
  for (const char* name : kScenes) {
    const std::string n = name;
    const double bare = reporter.wall["mj_step/" + n], two = reporter.wall["mujoco/" + n],
                 three = reporter.wall["mujoco3/" + n];
    if (bare <= 0.0 || two <= 0.0 || three <= 0.0) continue;
    std::printf("%-11s %10.2fus %10.2fus %10.2fus %15.2fx %15.2fx\n", name, bare / 1e3, two / 1e3,
                three / 1e3, three / two, three / bare);
  }
  steppers().clear();
  return 0;
}
