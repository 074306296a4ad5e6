// Running atlas points (analysis/atlas.hpp): one point through the
// reference, MuJoCo and the converged solution, and a spec's shard over a
// pool of threads into its directory (analysis/atlas_shard.hpp).
#include <time.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>

#include "analysis/atlas.hpp"
#include "analysis/atlas_shard.hpp"
#include "analysis/engine.hpp"
#include "analysis/reference.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/format.hpp"
#include "engines/engines.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {
namespace {

double thread_cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// MuJoCo 2.2.2's model loading (mj_loadXML: XML parse and compile) is not
// documented as thread safe, so models are created one at a time; stepping
// a model in its own mjData is (every thread has its own).
std::mutex& model_mutex() {
  static std::mutex m;
  return m;
}

engines::EngineRun run_one(const engines::EngineSpec& spec, const Scene& scene) {
  std::unique_ptr<Stepper> stepper;
  if (spec.kind == "ref") {
    stepper = engines::make_stepper(spec, scene);
  } else {
    const std::lock_guard<std::mutex> lock(model_mutex());
    stepper = engines::make_stepper(spec, scene);
  }
  engines::EngineRun run;
  run.engine = spec.name();
  const auto start = std::chrono::steady_clock::now();
  run.trajectory = simulate(*stepper, scene.sim);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.trajectory.divergence)
    run.divergence_message = stepper->explain(*run.trajectory.divergence, scene);
  return run;
}

}  // namespace

AtlasResult run_atlas_point(const AtlasPoint& point, double converged_tol) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_seconds();
  AtlasResult r;
  r.index = point.index;
  std::vector<std::string> errors, divergences;
  std::optional<engines::EngineRun> ref, mujoco;
  engines::EngineSpec ref_spec;
  engines::EngineSpec mj_spec;
  mj_spec.kind = point.engine;
  mj_spec.set("mapping", point.mapping);
  mj_spec.source = "atlas point " + std::to_string(point.index);
  for (const auto* spec : {&ref_spec, &mj_spec}) {
    const bool is_ref = spec == &ref_spec;
    std::optional<engines::EngineRun>& slot = is_ref ? ref : mujoco;
    const double cpu = thread_cpu_seconds();
    try {
      slot = run_one(*spec, point.scene);
      if (slot->trajectory.divergence) {
        divergences.push_back(spec->kind +
                              " diverged: " + atlas_one_line(slot->divergence_message));
      }
    } catch (const std::exception& e) {
      errors.push_back(spec->kind + ": " + atlas_one_line(e.what()));
      slot.reset();
    }
    (is_ref ? r.ref_seconds : r.mujoco_seconds) = thread_cpu_seconds() - cpu;
  }
  const double cpu_converged = thread_cpu_seconds();
  const DenseTrajectory converged = converged_reference(point.scene, converged_tol);
  std::optional<DenseTrajectory> coarser;
  if (converged.ok()) coarser = converged_reference(point.scene, 10.0 * converged_tol);
  r.converged_seconds = thread_cpu_seconds() - cpu_converged;
  if (!converged.ok())
    errors.push_back("converged solution: " + atlas_one_line(converged.failure()));
  const bool ref_ok = ref && !ref->trajectory.divergence;
  const bool mj_ok = mujoco && !mujoco->trajectory.divergence;
  if (converged.ok()) {
    if (coarser->ok())
      r.converged_own_error =
          error_between(converged, *coarser, output_times(point.scene.sim)).max_pos;
    if (ref_ok) {
      const TrajectoryError e = error_against(ref->trajectory, converged);
      r.ref_conv_pos = e.max_pos;
      r.ref_conv_angle = e.max_angle;
    }
    if (mj_ok) {
      const TrajectoryError e = error_against(mujoco->trajectory, converged);
      r.mujoco_conv_pos = e.max_pos;
      r.mujoco_conv_angle = e.max_angle;
    }
  }
  if (ref_ok && mj_ok) {
    const TrajectoryError e = error_between(ref->trajectory, mujoco->trajectory);
    r.ref_mujoco_pos = e.max_pos;
    r.ref_mujoco_angle = e.max_angle;
  }
  std::vector<std::string> all = errors;
  all.insert(all.end(), divergences.begin(), divergences.end());
  r.status = !errors.empty() ? "error" : !divergences.empty() ? "diverged" : "ok";
  for (const std::string& m : all) r.message += (r.message.empty() ? "" : "; ") + m;
  r.cpu_seconds = thread_cpu_seconds() - cpu0;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

AtlasRunStats run_atlas(const AtlasSpec& spec, const std::string& out_dir,
                        const AtlasRunOptions& options) {
  const long long total = atlas_point_count(spec);
  const std::vector<long long> indices = shard_points(options.shard, total);
  // Every point is checked before anything is written or run.
  for (long long i : indices) atlas_point(spec, i);

  AtlasShardWriter writer(out_dir);
  AtlasRunStats stats;
  stats.points = static_cast<long long>(indices.size());
  size_t done = 0;
  std::mutex mutex;
  const auto start = std::chrono::steady_clock::now();
  parallel_for(indices.size(), options.threads, [&](size_t i) {
    const AtlasPoint point = atlas_point(spec, indices[i]);
    const AtlasResult result = run_atlas_point(point, spec.converged_tol);
    const std::lock_guard<std::mutex> lock(mutex);
    writer.add(i, atlas_csv_row(point, result), atlas_times_row(result));
    ++done;
    stats.cpu_seconds += result.cpu_seconds;
    if (result.status == "ok") ++stats.ok;
    if (result.status == "diverged") ++stats.diverged;
    if (result.status == "error") ++stats.errors;
    if (options.progress)
      options.progress(done, indices.size(),
                       "point " + std::to_string(point.index) + " " + point.body + " " +
                           point.mapping + " k " + format_number(point.k, 3) + " ζ " +
                           format_number(point.zeta, 3));
  });
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writer.finish(atlas_manifest(spec.origin, spec.digest, total, options.shard, stats.points));
  return stats;
}

}  // namespace contact2d::analysis
