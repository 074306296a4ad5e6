// contact2d_condim: what the generated model's condim (only what the scene
// needs: 1 without friction, 3 with sliding friction only, 6 with rolling or
// torsional friction) changes against condim 6 everywhere, on each built-in
// scene with its friction and frictionless (μ = μ_roll = μ_torsion = 0):
//
//   - the error against the reference: max and RMS position error of the
//     COM over the run (analysis::error_between, the error of `contact2d
//     compare`), reference and MuJoCo each on the scene's integrator and Δt;
//   - the cost of one bare mj_step of that model, replaying the scene from
//     keyframe 0 for sim.duration: the thread's CPU time of the whole run
//     divided by its steps, the smallest of --repeats runs (this machine is
//     shared; the smallest is the least disturbed), the two models' runs
//     taken in turns.
//
// --csv DIR writes each MuJoCo trajectory, DIR/<scene>.<friction>.condim<N>.csv
// (t, x, y, θ, vx, vy, ω at 17 digits), to compare runs of two versions of
// the generator sample by sample.
//
//   build-dir/bench/contact2d_condim [--mapping NAME] [--repeats N] [--csv DIR]
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <initializer_list>
#include <string>
#include <tuple>
#include <utility>

#include "analysis/trajectory_error.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/stepper.hpp"

namespace {

using namespace contact2d;

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// ns of CPU per mj_step of two models over whole replays of the scene: the
// smallest of `repeats` replays each, taken in turns (A, B, A, B, ...) so
// that a change in the machine's load falls on both.
std::pair<double, double> mj_step_ns(const std::string& xml_a, const std::string& xml_b,
                                     long long steps, int repeats) {
  const mujoco::ModelPtr models[2] = {mujoco::load_model(xml_a, "condim measurement"),
                                      mujoco::load_model(xml_b, "condim measurement")};
  const mujoco::DataPtr data[2] = {mujoco::make_data(models[0].get()),
                                   mujoco::make_data(models[1].get())};
  double best[2] = {1e300, 1e300};
  for (int r = 0; r < repeats; ++r) {
    for (int k = 0; k < 2; ++k) {
      mj_resetDataKeyframe(models[k].get(), data[k].get(), 0);
      const double start = thread_cpu_seconds();
      for (long long i = 0; i < steps; ++i) mj_step(models[k].get(), data[k].get());
      best[k] = std::min(best[k], (thread_cpu_seconds() - start) / static_cast<double>(steps));
    }
  }
  return {best[0] * 1e9, best[1] * 1e9};
}

struct Row {
  int condim = 0;
  std::string xml;
  analysis::TrajectoryError error;
  double ns = 0.0;
};

void write_csv(const std::string& path, const Trajectory& run) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) {
    std::fprintf(stderr, "contact2d_condim: cannot write %s\n", path.c_str());
    return;
  }
  std::fprintf(out, "t,x,y,theta,vx,vy,omega\n");
  for (const Sample& s : run.samples) {
    std::fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t, s.state.q.x(),
                 s.state.q.y(), s.state.q.z(), s.state.v.x(), s.state.v.y(), s.state.v.z());
  }
  std::fclose(out);
}

Row measure(const Scene& scene, const Trajectory& reference, mujoco::MjcfOptions options,
            int condim, const std::string& csv) {
  options.condim = condim;
  const mujoco::GeneratedModel generated = mujoco::generate_mjcf(scene, options);
  mujoco::MujocoStepper stepper(scene, generated.xml, mujoco::generated_origin(options.source));
  Row row;
  row.condim = condim != 0 ? condim : mujoco::contact_condim(scene.contact);
  const Trajectory run = simulate(stepper, scene.sim);
  if (!csv.empty()) write_csv(csv + ".condim" + std::to_string(row.condim) + ".csv", run);
  row.error = analysis::error_between(reference, run);
  row.xml = generated.xml;
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mapping = "calibrated";
  int repeats = 5;
  std::string csv_dir;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--mapping") == 0) {
      mapping = argv[i + 1];
    } else if (std::strcmp(argv[i], "--csv") == 0) {
      csv_dir = argv[i + 1];
    } else if (std::strcmp(argv[i], "--repeats") == 0) {
      repeats = std::max(1, std::atoi(argv[i + 1]));
    } else {
      std::fprintf(stderr, "usage: contact2d_condim [--mapping NAME] [--repeats N] [--csv DIR]\n");
      return 2;
    }
  }
  std::printf("mapping %s; mj_step: CPU ns per step, smallest of %d replays of the scene\n",
              mapping.c_str(), repeats);
  std::printf("%-11s %-12s %6s %15s %15s %9s %15s %15s %9s %8s\n", "scene", "friction", "condim",
              "max_pos_err", "rms_pos_err", "ns/step", "max_pos(c6)", "rms_pos(c6)", "ns(c6)",
              "time");
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    const std::string source = std::string("validation/scenes/") + name + ".toml";
    const Scene with_friction = load_scene(std::string(CONTACT2D_SOURCE_DIR) + "/" + source);
    Scene frictionless = with_friction;
    frictionless.contact.mu = 0.0;
    frictionless.contact.mu_roll = 0.0;
    frictionless.contact.mu_torsion = 0.0;
    for (const Scene* scene : std::initializer_list<const Scene*>{&with_friction, &frictionless}) {
      const mujoco::MjcfOptions options = mujoco::mjcf_options(mapping, "", source);
      const Trajectory reference = simulate(*scene);
      const std::string csv =
          csv_dir.empty() ? ""
                          : csv_dir + "/" + name + (scene == &frictionless ? ".none" : ".scene");
      Row rule = measure(*scene, reference, options, 0, csv);
      Row six = measure(*scene, reference, options, 6, csv);
      std::tie(rule.ns, six.ns) = mj_step_ns(rule.xml, six.xml, step_count(scene->sim), repeats);
      std::printf("%-11s %-12s %6d %15.10g %15.10g %9.0f %15.10g %15.10g %9.0f %7.2fx\n", name,
                  scene == &frictionless ? "none" : "scene's", rule.condim, rule.error.max_pos,
                  rule.error.rms_pos, rule.ns, six.error.max_pos, six.error.rms_pos, six.ns,
                  rule.ns / six.ns);
    }
  }
  std::printf(
      "\ncondim: as generated (1 without friction, 3 sliding only, 6 rolling or torsional); "
      "(c6): the same model with condim 6; time = ns/step as generated / with condim 6\n");
  return 0;
}
