#include "mujoco/adapter.hpp"

#include <chrono>

#include "core/divergence.hpp"
#include "mujoco/model.hpp"

namespace contact2d::mujoco {
namespace {

struct PlanarReader {
  double x0 = 0.0;
  double y0 = 0.0;
  bool hinge = false;

  explicit PlanarReader(const mjModel* m)
      : x0(m->body_pos[3]), y0(m->body_pos[5]), hinge(m->nq == 3) {}

  State read(const mjData* d) const {
    State s;
    s.q = Vec3(x0 + d->qpos[0], y0 + d->qpos[1], hinge ? d->qpos[2] : 0.0);
    s.v = Vec3(d->qvel[0], d->qvel[1], hinge ? d->qvel[2] : 0.0);
    return s;
  }
};

bool bad_numbers(const mjData* d) {
  return d->warning[mjWARN_BADQPOS].number > 0 || d->warning[mjWARN_BADQVEL].number > 0 ||
         d->warning[mjWARN_BADQACC].number > 0;
}

// Steps and samples; returns the divergence that stopped the run, if any.
std::optional<Divergence> step_all(const Scene& scene, const mjModel* m, mjData* d,
                                   Trajectory& out) {
  const PlanarReader reader(m);
  const Model model = make_model(scene);
  const State initial = reader.read(d);
  const DivergenceMonitor monitor(model, initial);
  const long long steps = step_count(scene.sim);
  const long long stride = sample_stride(scene.sim);
  out.samples.reserve(static_cast<size_t>(steps / stride + 2));
  out.samples.push_back({0.0, initial});
  for (long long i = 1; i <= steps; ++i) {
    const double t = static_cast<double>(i) * scene.sim.dt;
    mj_step(m, d);
    const State s = reader.read(d);
    if (bad_numbers(d)) return Divergence{DivergenceKind::NonFinite, t, NAN, 0.0};
    if (auto divergence = monitor.check(s, t)) return divergence;
    if (i % stride == 0 || i == steps) out.samples.push_back({t, s});
  }
  return std::nullopt;
}

}  // namespace

MujocoRun run_mujoco_xml(const Scene& scene, const std::string& xml, const std::string& origin) {
  MujocoRun run;
  const ModelPtr model = load_model(xml, origin);
  const DataPtr data = make_data(model.get());
  mj_resetDataKeyframe(model.get(), data.get(), 0);
  {
    WarningCapture capture(run.warnings);
    const auto start = std::chrono::steady_clock::now();
    run.trajectory.divergence = step_all(scene, model.get(), data.get(), run.trajectory);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  // Counters of warnings whose text was already captured add the count.
  for (const std::string& w : warning_counters(data.get()))
    run.warnings.push_back("mjData.warning: " + w);
  return run;
}

MujocoRun run_mujoco(const Scene& scene, const MjcfOptions& options) {
  const GeneratedModel generated = generate_mjcf(scene, options);
  MujocoRun run = run_mujoco_xml(scene, generated.xml, generated_origin(options.source));
  run.settings = generated.settings;
  return run;
}

}  // namespace contact2d::mujoco
