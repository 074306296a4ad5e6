// contact2d_bench: the cost of one reference step (ReferenceStepper::step():
// the integrator and the contact stage of the new state, no divergence
// check, no output) against one bare mj_step of the same scene's generated
// model (models/<scene>.calibrated.xml) with the matching MuJoCo integrator,
// at the scene's Δt. MuJoCo is stepped directly, not through MujocoStepper,
// so that its figure is MuJoCo's own cost and not the reference's contact
// stage run on its state for the divergence monitor.
//
// Both replay their scene from its initial state (MuJoCo: keyframe 0) and
// start over after sim.duration, so each timing averages the same mix of
// flight, impacts and resting contact. Google Benchmark picks the iteration
// counts; the table at the end divides the two per-step times.
//
//   build-dir/bench/contact2d_bench [--benchmark_min_time=0.2]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "core/integrators.hpp"
#include "core/run.hpp"
#include "core/vector_math.hpp"
#include "io/scene_file.hpp"

#ifdef CONTACT2D_WITH_MUJOCO
#include <mujoco/mujoco.h>

#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#endif

namespace {

using namespace contact2d;

// Scene files under validation/scenes, without ".toml".
const char* const kScenes[] = {"point_mass", "box", "tshape", "circle", "game/pitch"};

struct Case {
  std::string scene;
  Integrator integrator;
};

std::string case_name(const Case& c) {
  return c.scene + "/" + std::string(integrator_name(c.integrator));
}

// The reference step on a given tanh path (core/vector_math.hpp): "ref" is
// the path the program would choose (contact2d's bounded tanh unless the
// environment asks for another), "ref_other" glibc's scalar tanh (the
// bounded one when the program chose glibc's), measured in the same run:
// the step before and after the bounded tanh, side by side.
void reference_step(benchmark::State& state, const Case& c, TanhPath path) {
  const TanhPath before = set_tanh_path(path);
  Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + c.scene + ".toml");
  scene.sim.integrator = c.integrator;
  ReferenceStepper stepper(scene);
  const State initial = initial_state(scene);
  const long long steps = step_count(scene.sim);
  long long i = 0;
  for (auto _ : state) {
    stepper.step();
    if (++i == steps) {
      i = 0;
      stepper.reset(initial);
    }
    benchmark::DoNotOptimize(stepper.state());
  }
  state.SetLabel(tanh_path_name(tanh_path()));
  set_tanh_path(before);
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
  const Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + c.scene + ".toml");
  mujoco::ModelPtr model;
  try {
    if (std::ifstream(path).good()) {
      char error[1000] = "";
      model.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
      if (!model) throw std::runtime_error("cannot load " + path + ": " + error);
    } else {  // the calibrated model as `contact2d generate` writes it
      model = mujoco::load_model(
          mujoco::generate_mjcf(scene, mujoco::mjcf_options("calibrated", "", c.scene)).xml,
          c.scene);
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  mjModel* m = model.get();
  m->opt.integrator = mujoco_integrator(c.integrator);
  mjData* d = mj_makeData(m);
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
}
#endif

// The floor under a step: a step is one chain of dependent operations (the
// next state needs this one), so its cost is the latency of that chain. The
// accurate libm calls on it are measured here the same way, each call
// feeding the next: one sincos per force evaluation of a rotating body, one
// tanh per touching point that slips slower than 22/α (one more for a
// rolling contact spinning slower than 22/(α·R)). "step/free_flight" is a
// body without contact points in flight: the call, the gravity update and
// the harness, nothing else.
void libm_sincos(benchmark::State& state) {
  double x = 0.3;
  for (auto _ : state) {
    x = 0.3 + 1e-3 * (std::sin(x) + std::cos(x));  // GCC fuses the pair into one sincos
    benchmark::DoNotOptimize(x);
  }
}

void libm_tanh(benchmark::State& state) {
  double x = 0.3;
  for (auto _ : state) {
    x = 0.1 + 0.5 * std::tanh(x);
    benchmark::DoNotOptimize(x);
  }
}

// The same chain through contact2d's bounded_tanh (its rational branch:
// the chain settles at x ≈ 0.19, a slowly slipping contact's range).
void bounded_tanh_chain(benchmark::State& state) {
  double x = 0.3;
  for (auto _ : state) {
    x = 0.1 + 0.5 * bounded_tanh(x);
    benchmark::DoNotOptimize(x);
  }
}

// Four values through tanh_batch on the vector path (one SLEEF call), the
// next four fed by the last result: the latency a force stage pays for it.
void vector_tanh4(benchmark::State& state) {
  if (!vector_tanh_available()) {
    state.SkipWithError("no AVX2 or no SLEEF in this build");
    return;
  }
  double x = 0.3;
  for (auto _ : state) {
    double y[4] = {x, 0.5 * x, 0.25 * x, -x};
    tanh_vector(y, 4);
    x = 0.1 + 0.5 * y[0];
    benchmark::DoNotOptimize(x);
  }
}

void free_flight_step(benchmark::State& state) {
  const Model model;  // default body: 1 kg, no contact points
  State s;
  StepWorkspace ws(model);
  long long i = 0;
  for (auto _ : state) {
    step(model, Integrator::SemiImplicitEuler, 1e-4, s, ws);
    if (++i == 20000) {
      i = 0;
      s = State{};
    }
    benchmark::DoNotOptimize(s);
  }
}

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
  const TanhPath chosen = tanh_path();
  const TanhPath other = chosen == TanhPath::Scalar ? TanhPath::Bounded : TanhPath::Scalar;
  for (const Case& c : cases) {
    benchmark::RegisterBenchmark(("ref/" + case_name(c)).c_str(), reference_step, c, chosen);
    benchmark::RegisterBenchmark(("ref_other/" + case_name(c)).c_str(), reference_step, c, other);
#ifdef CONTACT2D_WITH_MUJOCO
    benchmark::RegisterBenchmark(("mj_step/" + case_name(c)).c_str(), mujoco_step, c);
#endif
  }
  benchmark::RegisterBenchmark("floor/libm_sincos", libm_sincos);
  benchmark::RegisterBenchmark("floor/libm_tanh", libm_tanh);
  benchmark::RegisterBenchmark("floor/bounded_tanh", bounded_tanh_chain);
  benchmark::RegisterBenchmark("floor/vector_tanh4", vector_tanh4);
  benchmark::RegisterBenchmark("floor/step_free_flight", free_flight_step);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  std::printf(
      "\nper step at each scene's dt; MuJoCo: models/<scene>.calibrated.xml (its Euler is "
      "semi-implicit).\n"
      "ratio = mj_step / reference step, on CPU time (robust to other load on the machine) and "
      "wall clock\n");
  std::printf("ref: tanh path %s; other: %s\n", tanh_path_name(chosen), tanh_path_name(other));
  std::printf("%-11s %-20s %9s %9s %9s %7s %7s %9s %9s\n", "scene", "integrator", "ref cpu",
              "other", "mj cpu", "ratio", "other", "ref wall", "mj wall");
  const auto cpu = [&](const std::string& name) {
    const auto it = reporter.times().find(name);
    return it == reporter.times().end() ? -1.0 : it->second.cpu_ns;
  };
  const auto wall = [&](const std::string& name) {
    const auto it = reporter.times().find(name);
    return it == reporter.times().end() ? -1.0 : it->second.real_ns;
  };
  for (const Case& c : cases) {
    const double ref = cpu("ref/" + case_name(c));
    if (ref < 0.0) continue;
    const double other_ns = cpu("ref_other/" + case_name(c));
    const double mj = cpu("mj_step/" + case_name(c));
    const std::string integrator(integrator_name(c.integrator));
    std::printf("%-11s %-20s %7.1fns %7.1fns %7.0fns %6.0fx %6.0fx %7.1fns %7.0fns\n",
                c.scene.c_str(), integrator.c_str(), ref, other_ns, mj, mj > 0 ? mj / ref : 0.0,
                mj > 0 && other_ns > 0 ? mj / other_ns : 0.0, wall("ref/" + case_name(c)),
                wall("mj_step/" + case_name(c)));
  }
  const auto floor_ns = [&](const char* name) {
    const auto it = reporter.times().find(std::string("floor/") + name);
    return it == reporter.times().end() ? -1.0 : it->second.cpu_ns;
  };
  std::printf(
      "\nfloor (CPU, each call feeding the next): sincos %.1fns, glibc tanh %.1fns, bounded_tanh "
      "%.1fns, tanh_batch of 4 on the vector path %.1fns, a step with no contact points %.1fns\n",
      floor_ns("libm_sincos"), floor_ns("libm_tanh"), floor_ns("bounded_tanh"),
      floor_ns("vector_tanh4"), floor_ns("step_free_flight"));
  return 0;
}
