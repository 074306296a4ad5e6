// The report's seam to the engines and analyses (report/runs.hpp): the only
// file of the report that runs anything.
#include "report/runs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "analysis/comparison.hpp"
#include "analysis/engine.hpp"
#include "analysis/plots.hpp"
#include "analysis/real_impacts.hpp"
#include "analysis/stability.hpp"
#include "analysis/sweep.hpp"
#include "analysis/tables.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/divergence.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "engines/engines.hpp"
#include "game/pitch.hpp"
#include "game/replay.hpp"
#include "game/session.hpp"
#include "io/atlas_spec.hpp"
#include "io/atomic_file.hpp"
#include "io/child_process.hpp"
#include "io/csv.hpp"
#include "io/exit_status.hpp"
#include "io/plot.hpp"
#include "io/recording.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "report/bench_json.hpp"
#ifdef CONTACT2D_WITH_WINDOW
#include "game/comparison_video.hpp"
#endif

namespace contact2d::report {
namespace {

std::optional<double> finite(double x) {
  return std::isfinite(x) ? std::optional<double>(x) : std::nullopt;
}

std::string status_text(analysis::RunStatus status) {
  switch (status) {
    case analysis::RunStatus::Ok: return "ok";
    case analysis::RunStatus::Diverged: return "diverged";
    case analysis::RunStatus::Failed: return "failed";
  }
  return "failed";
}

// The reference and MuJoCo on the scene; throws std::runtime_error naming
// the engine when either diverges (the report shows converged runs only).
std::pair<engines::EngineRun, engines::EngineRun> run_both(const engines::EngineSpec& mujoco,
                                                           const Scene& scene,
                                                           const std::string& source) {
  std::pair<engines::EngineRun, engines::EngineRun> runs{engines::run_engine("ref", scene),
                                                         engines::run_engine(mujoco, scene)};
  for (const engines::EngineRun* run : {&runs.first, &runs.second}) {
    if (run->trajectory.divergence) {
      throw std::runtime_error(source + ": " + (run == &runs.first ? "ref" : "MuJoCo") + ": " +
                               run->divergence_message);
    }
  }
  return runs;
}

// MuJoCo (2.2.2: "mujoco", 3.14: "mujoco3") under a mapping and geometry.
engines::EngineSpec mujoco_spec(const std::string& kind, const std::string& mapping,
                                const std::string& geometry, const std::string& source) {
  engines::EngineSpec spec;
  spec.kind = kind;
  spec.set("mapping", mapping);
  spec.set("geometry", geometry);
  spec.source = source;
  return spec;
}

// A comparison's row from the reference's and MuJoCo's runs.
ComparisonRow comparison_row(const Scene& scene, const engines::EngineRun& ref,
                             const engines::EngineRun& mujoco) {
  namespace mj = contact2d::mujoco;
  const analysis::TrajectoryError e = analysis::error_between(ref.trajectory, mujoco.trajectory);
  ComparisonRow c;
  c.mujoco_integrator = mj::mujoco_integrator(scene.sim.integrator);
  c.shape = std::string(shape_name(scene.shape));
  c.dt = scene.sim.dt;
  c.duration = scene.sim.duration;
  c.max_pos = e.max_pos;
  c.rms_pos = e.rms_pos;
  c.max_angle = e.max_angle;
  c.max_vel = e.max_vel;
  c.end_pos = e.end_pos;
  c.impratio = mujoco.impratio;
  c.ref_seconds = ref.seconds;
  c.mujoco_seconds = mujoco.seconds;
  return c;
}

// MuJoCo 3.14's run of the scene; throws std::runtime_error when it diverges.
engines::EngineRun run_mujoco3(const engines::EngineSpec& spec, const Scene& scene,
                               const std::string& source) {
  engines::EngineRun run = engines::run_engine(spec, scene);
  if (run.trajectory.divergence)
    throw std::runtime_error(source + ": MuJoCo 3.14: " + run.divergence_message);
  return run;
}

}  // namespace

bool mujoco_built() { return engines::mujoco_available(); }

std::string mujoco3_missing() { return mujoco3::missing(); }

namespace {

// compare --plot: x, y, θ of both engines and their distance.
void plot_ref_vs_mujoco(const std::string& plot_png, const Scene& scene, const std::string& mapping,
                        const engines::EngineRun& ref, const engines::EngineRun& mujoco) {
  if (plot_png.empty()) return;
  namespace mj = contact2d::mujoco;
  const mj::MjcfOptions options = mj::mjcf_options(mapping, "corners", "");
  const std::string title = std::string(shape_name(scene.shape)) + ": ref vs MuJoCo, " +
                            engines::integrator_label("mujoco", scene.sim.integrator) +
                            ", Δt = " + format_number(scene.sim.dt) + " s, " +
                            std::string(mj::mapping_name(options.mapping)) + " mapping, " +
                            std::string(damping_law_title(scene.contact.damping)) + " damping";
  plot_comparison(plot_png, title, ref.trajectory, mujoco.trajectory, "ref", "MuJoCo");
}

}  // namespace

ComparisonRow compare_engines(const Scene& scene, const std::string& source,
                              const std::string& mapping, const std::string& geometry,
                              const std::string& plot_png) {
  const auto [ref, mujoco] =
      run_both(mujoco_spec("mujoco", mapping, geometry, source), scene, source);
  plot_ref_vs_mujoco(plot_png, scene, mapping, ref, mujoco);
  return comparison_row(scene, ref, mujoco);
}

VersionsComparison compare_versions(const Scene& scene, const std::string& source,
                                    const std::string& mapping, const std::string& geometry,
                                    const std::string& plot_png) {
  const auto [ref, v2] = run_both(mujoco_spec("mujoco", mapping, geometry, source), scene, source);
  plot_ref_vs_mujoco(plot_png, scene, mapping, ref, v2);
  const engines::EngineRun v3 =
      run_mujoco3(mujoco_spec("mujoco3", mapping, geometry, source), scene, source);
  VersionsComparison out;
  out.v2 = comparison_row(scene, ref, v2);
  out.v3 = comparison_row(scene, ref, v3);
  out.apart = analysis::error_between(v2.trajectory, v3.trajectory).max_pos;
  return out;
}

ThreeWayCase compare_three_way(const Scene& scene, const std::string& source,
                               const std::string& law, double tol, ThreeWayRuns* keep,
                               bool mujoco3) {
  engines::EngineSpec spec;
  spec.kind = "mujoco";
  spec.source = source;
  auto [ref, mujoco] = run_both(spec, scene, source);
  analysis::ThreeWay three = analysis::three_way(scene, ref.trajectory, mujoco.trajectory, tol);
  // Its re-runs on this thread: the report runs its cases on a pool of its own.
  const analysis::Diagnosis d =
      analysis::diagnose(scene, spec, ref, mujoco, three, analysis::registry_runner(), {false, 1});
  ThreeWayCase c;
  c.scene = std::string(shape_name(scene.shape));
  c.law = law;
  c.converged = three.converged.available;
  c.ref_vs_converged = three.ref_vs_converged.max_pos;
  c.mujoco_vs_converged = three.mujoco_vs_converged.max_pos;
  c.ref_vs_mujoco = three.ref_vs_mujoco.max_pos;
  c.amplification = three.converged.amplification;
  c.agrees = d.agrees;
  for (const analysis::Finding& f : d.findings)
    if (f.named) c.causes.push_back({f.cause, f.share, f.fix});
  c.not_rerun = d.not_rerun;
  Trajectory v3;
  if (mujoco3) {
    v3 = run_mujoco3(mujoco_spec("mujoco3", "calibrated", "corners", source), scene, source)
             .trajectory;
    c.ref_vs_v3 = analysis::error_between(ref.trajectory, v3).max_pos;
    c.v2_vs_v3 = analysis::error_between(mujoco.trajectory, v3).max_pos;
  }
  if (keep) {
    keep->mujoco3 = std::move(v3);
    keep->scene = scene;
    keep->reference = std::move(ref.trajectory);
    keep->mujoco = std::move(mujoco.trajectory);
    keep->converged_available = three.converged.available;
    keep->converged = std::move(three.converged.trajectory);
  }
  return c;
}

std::string animate_three_way(const ThreeWayRuns& runs, const std::string& video, ThreeWayCase& c,
                              bool mujoco3) {
#ifdef CONTACT2D_WITH_WINDOW
  try {
    const std::string engine = mujoco3 ? "MuJoCo 3.14" : "MuJoCo";
    game::ComparisonVideoInput in;
    in.scene = &runs.scene;
    in.reference = &runs.reference;
    in.second = mujoco3 ? &runs.mujoco3 : &runs.mujoco;
    in.converged = runs.converged_available ? &runs.converged : nullptr;
    in.title = c.scene + " (" + c.law + "): ref vs " + engine + ", " +
               engines::integrator_label("mujoco", runs.scene.sim.integrator) + ", calibrated";
    in.reference_label = "ref";
    in.second_label = engine;
    game::write_comparison_video(video, in, 20, 640, 360);
    (mujoco3 ? c.animation_v3 : c.animation) = std::filesystem::path(video).filename().string();
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
#else
  (void)runs;
  (void)video;
  (void)c;
  (void)mujoco3;
  return "this contact2d was built without the game's window (GLFW, OpenGL)";
#endif
}

ReplayComparison replay_on_both(const std::string& replay_path, const std::string& plot_png) {
  const game::Pitch pitch = game::default_pitch();
  const game::Replay replay = game::read_replay(replay_path);
  ReplayComparison out;
  out.ran = true;
  out.replay = replay_path;
  out.radius = pitch.scene.radius;
  const game::ReplayRun ref = game::run_replay(pitch, replay, "ref");
  const game::ReplayRun mj = game::run_replay(pitch, replay, "mujoco");
  for (const game::ReplayRun* r : {&ref, &mj})
    out.engines.push_back({r->engine, std::string(game::outcome_name(r->outcome)), r->json});
  out.part_1cm = game::parting_time(ref, mj, 0.01);
  out.part_radius = game::parting_time(ref, mj, out.radius);
  Trajectory a, b;
  a.samples = ref.samples;
  b.samples = mj.samples;
  plot_comparison(plot_png, "the goal replay: the ball on both engines", a, b, "ref", "MuJoCo");
  out.plot = std::filesystem::path(plot_png).filename().string();
  // The recorded video beside the plot (a report written elsewhere than the
  // snapshot gets a copy).
  const std::filesystem::path dir = std::filesystem::path(plot_png).parent_path();
  for (const char* name : {"goal.gif", "goal.mp4"}) {
    const std::filesystem::path shipped = std::filesystem::path("validation/report") / name;
    std::error_code ec;
    if (!std::filesystem::exists(shipped, ec)) continue;
    if (!std::filesystem::equivalent(shipped, dir / name, ec))
      std::filesystem::copy_file(shipped, dir / name,
                                 std::filesystem::copy_options::overwrite_existing, ec);
    if (!ec) (std::string(name) == "goal.gif" ? out.gif : out.mp4) = name;
  }
  return out;
}

void write_model(const Scene& scene, const std::string& source, const std::string& mapping,
                 const std::string& path) {
  AtomicFile out(path);
  const auto model = contact2d::mujoco::generate_mjcf(
      scene, contact2d::mujoco::mjcf_options(mapping, "corners", source));
  std::fputs(model.xml.c_str(), out.get());
  out.commit();
}

SceneSweep sweep_scene(const Scene& scene, const std::string& name, const SweepRequest& request,
                       const std::string& plot_png) {
  SceneSweep out;
  out.name = name;
  out.scene = std::string(shape_name(scene.shape));
  if (request.study) {
    const std::vector<double> tols{1e-3, 1e-4,  1e-5,  1e-6,  1e-7, 1e-8,
                                   1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
    // One thread, as `contact2d sweep --study-csv`: the study times every run.
    const analysis::ReferenceStudy study = analysis::study_reference(scene, tols, 1e-14, 1);
    for (const analysis::ToleranceRow& row : study.rows) {
      out.study.push_back(
          {row.tol, row.failure.empty(), row.error.max_pos, row.seconds, row.stats.events});
    }
    out.amplification = study.amplification;
  }
  analysis::SweepConfig config;
  if (!request.integrators.empty())
    config.integrators = analysis::parse_integrators(request.integrators);
  if (!request.mujoco_dts.empty()) config.other_dts = request.mujoco_dts;
  if (!request.mujoco_integrators.empty())
    config.other_integrators = analysis::parse_integrators(request.mujoco_integrators);
  config.engines = request.engines;
  config.repeats = request.repeats;
  config.threads = request.threads;
  const analysis::SweepResult result = analysis::run_sweep(scene, config);
  for (const analysis::SweepRow& row : result.rows) {
    SweepRun run;
    run.engine = row.engine;
    run.integrator = std::string(integrator_name(row.integrator));
    run.dt = row.dt;
    run.status = status_text(row.status);
    run.max_pos = row.error.max_pos;
    if (row.self_error) run.self_max_pos = row.self_error->max_pos;
    run.seconds = row.repeats > 0 ? row.seconds : 0.0;
    out.runs.push_back(run);
  }
  for (const analysis::ToleranceRow& row : result.dense_curve) {
    SweepRun run;
    run.engine = "ref";
    run.integrator = "dopri5_events";
    run.tol = row.tol;
    run.status = row.failure.empty() ? "ok" : "failed";
    run.max_pos = row.error.max_pos;
    run.seconds = row.seconds;
    out.runs.push_back(run);
  }
  for (const analysis::OrderFit& f : result.orders) {
    OrderRow o;
    o.engine = f.engine;
    o.integrator = std::string(integrator_name(f.integrator));
    o.against = f.against;
    o.nominal = f.nominal;
    o.observed = f.order;
    o.observed_stderr = f.order_stderr;
    o.points = f.points;
    o.dt_min = f.dt_min;
    o.dt_max = f.dt_max;
    o.note = f.note;
    out.orders.push_back(o);
  }
  if (!plot_png.empty()) analysis::plot_sweep(plot_png, result);
  return out;
}

StabilityMap stability_map(const Scene& scene, const std::string& name,
                           const StabilityRequest& request, const std::string& plot_png) {
  analysis::StabilityConfig config;
  if (!request.ks.empty()) config.ks = request.ks;
  config.engines = request.engines;
  config.zeta = request.zeta;
  config.threads = request.threads;
  const analysis::StabilityResult result = analysis::run_stability(scene, config);
  StabilityMap map;
  map.name = name;
  map.scene = result.scene_name;
  for (const analysis::StabilityRow& r : result.rows) {
    StabilityRow row;
    row.engine = r.engine;
    row.integrator = std::string(integrator_name(r.integrator));
    row.k = r.k;
    row.c = r.c;
    row.zeta = r.zeta;
    row.theory = finite(r.theory);
    row.verdict = analysis::verdict_name(r.verdict);
    row.dt_stable = r.dt_stable;
    row.dt_unstable = r.dt_unstable;
    row.dt_min = r.dt_min;
    row.dt_max = result.dt_max;
    row.omega_dt_stable = r.omega * r.dt_stable;
    row.penetration = finite(r.penetration);
    row.penetration_small_step = finite(r.penetration_small_step);
    row.reference_penetration = finite(r.reference_penetration);
    row.failure = r.failure;
    row.note = r.note;
    map.rows.push_back(row);
  }
  if (!plot_png.empty()) analysis::plot_stability(plot_png, result);
  return map;
}

EngineOutcome simulate_outcome(const std::string& path, const std::string& engine) {
  Scene scene;
  engines::EngineRun run;
  try {
    scene = load_scene(path);
    engines::EngineSpec spec = engines::parse_engine(engine);
    spec.source = path;
    run = engines::run_engine(spec, scene);
  } catch (const InputError& e) {
    return {kExitBadInput, "contact2d: " + std::string(e.what()) + "\n"};
  }
  std::string text;
  for (const std::string& w : run.warnings)
    text += "contact2d: " + engine + " warning: " + w + "\n";
  if (run.trajectory.divergence) {
    text += "contact2d: " + path + ": " + run.divergence_message + "\n";
    return {kExitDiverged, text};
  }
  // As `contact2d simulate` without --allow-nonphysical (core/run.hpp).
  if (const std::string reason = nonphysical(run.trajectory, scene); !reason.empty()) {
    text += "contact2d: " + path + ": not physics: " + reason +
            ". Pass --allow-nonphysical to keep the run.\n";
    return {kExitDiverged, text};
  }
  return {kExitOk, analysis::run_summary(scene, engine, run) + "\n"};
}

double named_share() { return analysis::kNamedShare; }

void add_friction_parts(const Scene& scene, const std::string& mapping, GoalCase& g, bool mujoco3) {
  const analysis::FrictionParts parts = analysis::friction_parts(scene, mapping, mujoco3);
  g.friction_shape = parts.shape;
  g.friction_push = parts.push;
  g.friction_rest = parts.rest;
  g.v3_rest = parts.rest_v3;
}

RandomCase compare_random_scene(const RandomScene& r, const std::string& mapping, RandomCase* v3) {
  Scene frictionless = r.scene;
  frictionless.contact.mu = 0.0;
  const std::string source = "random scene " + r.name;
  // With friction, friction_parts's own runs: its total is compare's
  // distance (the same reference and MuJoCo runs).
  const analysis::FrictionParts parts = analysis::friction_parts(r.scene, mapping, v3 != nullptr);
  if (!parts.ok) throw std::runtime_error(source + ": an engine diverged with friction");
  ComparisonRow without;
  if (v3) {
    const VersionsComparison both = compare_versions(frictionless, source, mapping, "corners");
    without = both.v2;
    *v3 = {r.name,
           without.shape,
           r.mass,
           r.scene.contact.k,
           r.scene.contact.c,
           r.scene.contact.mu,
           both.v3.max_pos,
           both.v3.max_angle,
           parts.total_v3,
           parts.shape,
           parts.push,
           parts.rest_v3,
           std::max(both.apart, parts.apart_v3)};
  } else {
    without = compare_engines(frictionless, source, mapping, "corners");
  }
  return {r.name,
          without.shape,
          r.mass,
          r.scene.contact.k,
          r.scene.contact.c,
          r.scene.contact.mu,
          without.max_pos,
          without.max_angle,
          parts.total,
          parts.shape,
          parts.push,
          parts.rest};
}

bool points_turn(const Scene& scene) {
  const RigidBody body = make_model(scene).body;
  return body.rotates && body.points_rotate;
}

analysis::ClosedFormTable closed_form_rows(unsigned threads) {
  return analysis::closed_form_table(threads);
}

std::vector<analysis::FrictionRow> friction_rows(unsigned threads) {
  return analysis::friction_table(threads);
}

std::vector<analysis::FrictionScene> friction_scene_list() { return analysis::friction_scenes(); }

analysis::VersionTable version_rows(const std::vector<analysis::NamedScene>& scenes,
                                    unsigned threads) {
  return analysis::version_table(scenes, threads);
}

void run_atlas(const std::string& spec_path, const std::string& out_dir, AtlasRun& run) {
  const AtlasSpec spec = load_atlas_spec(spec_path);
  analysis::AtlasRunOptions options;
  options.threads = analysis::default_threads();
  const analysis::AtlasRunStats stats = analysis::run_atlas(spec, out_dir, options);
  run.data = analysis::read_atlas_shards({out_dir});
  run.summary = analysis::summarize_atlas(run.data);
  run.info = {spec_path,          stats.points,          options.threads,
              stats.wall_seconds, stats.cpu_per_point(), stats.points_per_core()};
}

void draw_atlas(AtlasRun& run, const std::string& plot_dir, const std::string& png_prefix) {
  analysis::draw_atlas_heatmaps(run.data, run.summary, plot_dir, png_prefix);
}

Bench run_bench(const std::string& executable, const std::string& min_time) {
  // Only what the report reads: the reference's default tanh path, mj_step
  // and the libm floors section 6 sets against the budgets (not the other
  // tanh path's timings, which docs/speed.md reads from a full run). Its
  // JSON goes to a temporary of this process in $TMPDIR (an AtomicFile never
  // committed: removed on return and on an interrupt), and the bench runs
  // through the one process launcher, registered so that an interrupt stops
  // it before the file is removed.
  const char* tmp = std::getenv("TMPDIR");
  const AtomicFile json(std::string(tmp && *tmp ? tmp : "/tmp") + "/contact2d-bench.json");
  ChildEnding end;
  try {
    ChildProcess bench({executable, "--benchmark_min_time=" + min_time,
                        "--benchmark_filter=^(ref|mj_step)/|^floor/(libm_|step_)",
                        "--benchmark_out=" + json.temp_path(), "--benchmark_out_format=json"},
                       {}, /*writes_output=*/true);
    end = bench.finish();
  } catch (const ChildProcessError& e) {
    throw std::runtime_error(executable + ": " + e.what());
  }
  if (end.status != 0) throw std::runtime_error(executable + " failed (" + end.description + ")");
  std::ifstream in(json.temp_path());
  std::ostringstream text;
  text << in.rdbuf();
  Bench bench = parse_bench_json(text.str());
  const size_t slash = executable.rfind('/');
  bench.command = (slash == std::string::npos ? executable : executable.substr(slash + 1)) +
                  " --benchmark_min_time=" + min_time;
  return bench;
}

RealImpactsData real_impacts_run(const std::string& recording, const std::string& out_dir,
                                 bool mujoco) {
  RealImpactsData d;
  d.recording = recording;
  const Recording rec = read_recording(recording);
  analysis::ImpactFitOptions options;
  options.threads = 1;
  if (mujoco) options.engines = analysis::default_fit_engines();
  d.fit = analysis::fit_impacts(rec, options);
  const std::string prefix = out_dir + "/real_impacts.";
  analysis::plot_impact_predictions(prefix + "predictions.png", d.fit, "seeded");
  analysis::plot_impact_errors(prefix + "errors.png", d.fit, "seeded");
  analysis::plot_k_profile(prefix + "k_profile.png", d.fit);
  d.pictures = {"real_impacts.predictions.png", "real_impacts.errors.png",
                "real_impacts.k_profile.png"};
  return d;
}

}  // namespace contact2d::report
