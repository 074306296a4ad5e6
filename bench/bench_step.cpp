// contact2d_bench: the cost of one reference step (core step(), the
// integrator alone, no divergence check, no output) against one mj_step of
// the same scene's generated model (models/<scene>.calibrated.xml) with the
// matching MuJoCo integrator, at the scene's Δt.
//
// Both replay their scene from its initial state (MuJoCo: keyframe 0) and
// start over after sim.duration, so each timing averages the same mix of
// flight, impacts and resting contact. Google Benchmark picks the iteration
// counts; the table at the end divides the two per-step times.
//
//   build-dir/bench/contact2d_bench [--benchmark_min_time=0.2]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/integrators.hpp"
#include "core/simulate.hpp"
#include "io/scene_file.hpp"

#ifdef CONTACT2D_WITH_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace {

using namespace contact2d;

const char* const kScenes[] = {"point_mass", "box", "tshape", "circle"};

struct Case {
  std::string scene;
  Integrator integrator;
};

std::string case_name(const Case& c) {
  return c.scene + "/" + std::string(integrator_name(c.integrator));
}

void reference_step(benchmark::State& state, const Case& c) {
  Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + c.scene + ".toml");
  const Model model = make_model(scene);
  const State initial = initial_state(scene);
  const long long steps = step_count(scene.sim);
  State s = initial;
  long long i = 0;
  for (auto _ : state) {
    step(model, c.integrator, scene.sim.dt, s);
    if (++i == steps) {
      i = 0;
      s = initial;
    }
    benchmark::DoNotOptimize(s);
  }
  state.SetLabel("ref");
}

#ifdef CONTACT2D_WITH_MUJOCO
int mujoco_integrator(Integrator integrator) {
  switch (integrator) {
    case Integrator::RK4: return mjINT_RK4;
    case Integrator::ImplicitEuler: return mjINT_IMPLICIT;
    default: return mjINT_EULER;  // MuJoCo's Euler is semi-implicit
  }
}

void mujoco_step(benchmark::State& state, const Case& c) {
  const std::string path = std::string(CONTACT2D_MODELS_DIR) + "/" + c.scene + ".calibrated.xml";
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  if (!m) {
    state.SkipWithError(("cannot load " + path + ": " + error).c_str());
    return;
  }
  m->opt.integrator = mujoco_integrator(c.integrator);
  mjData* d = mj_makeData(m);
  const Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + c.scene + ".toml");
  const long long steps = step_count(scene.sim);
  mj_resetDataKeyframe(m, d, 0);
  long long i = 0;
  for (auto _ : state) {
    mj_step(m, d);
    if (++i == steps) {
      i = 0;
      mj_resetDataKeyframe(m, d, 0);
    }
  }
  state.SetLabel("mujoco");
  mj_deleteData(d);
  mj_deleteModel(m);
}
#endif

// Collects the per-step real time of every run for the ratio table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred || run.iterations == 0) continue;
      const double n = static_cast<double>(run.iterations);
      times_[run.benchmark_name()] = {run.real_accumulated_time / n * 1e9,
                                      run.cpu_accumulated_time / n * 1e9};
    }
  }
  struct Times {
    double real_ns = 0.0;
    double cpu_ns = 0.0;
  };
  const std::map<std::string, Times>& times() const { return times_; }

 private:
  std::map<std::string, Times> times_;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases;
  for (const char* scene : kScenes) {
    for (Integrator integrator :
         {Integrator::SemiImplicitEuler, Integrator::RK4, Integrator::ImplicitEuler}) {
      cases.push_back({scene, integrator});
    }
  }
  for (const Case& c : cases) {
    benchmark::RegisterBenchmark(("ref/" + case_name(c)).c_str(), reference_step, c);
#ifdef CONTACT2D_WITH_MUJOCO
    benchmark::RegisterBenchmark(("mj_step/" + case_name(c)).c_str(), mujoco_step, c);
#endif
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  std::printf(
      "\nper step at each scene's dt; MuJoCo: models/<scene>.calibrated.xml (its Euler is "
      "semi-implicit).\n"
      "ratio = mj_step / reference step, on CPU time (robust to other load on the machine) and "
      "wall clock\n");
  std::printf("%-11s %-20s %10s %10s %9s %9s %9s\n", "scene", "integrator", "ref cpu", "mj cpu",
              "ratio", "ref wall", "mj wall");
  for (const Case& c : cases) {
    const auto ref = reporter.times().find("ref/" + case_name(c));
    const auto mj = reporter.times().find("mj_step/" + case_name(c));
    if (ref == reporter.times().end()) continue;
    const std::string integrator(integrator_name(c.integrator));
    if (mj == reporter.times().end()) {
      std::printf("%-11s %-20s %8.1fns %10s %9s %7.1fns %9s\n", c.scene.c_str(), integrator.c_str(),
                  ref->second.cpu_ns, "-", "-", ref->second.real_ns, "-");
    } else {
      std::printf("%-11s %-20s %8.1fns %8.0fns %8.0fx %7.1fns %7.0fns\n", c.scene.c_str(),
                  integrator.c_str(), ref->second.cpu_ns, mj->second.cpu_ns,
                  mj->second.cpu_ns / ref->second.cpu_ns, ref->second.real_ns, mj->second.real_ns);
    }
  }
  return 0;
}
