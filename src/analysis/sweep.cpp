#include "analysis/sweep.hpp"
#include "core/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>

namespace contact2d::analysis {
namespace {

struct Job {
  enum Kind { Reference, LooseReference, Dense, Run } kind = Run;
  size_t row = 0;
  double cost = 0.0;  // rough, for ordering: longest first
};

}  // namespace

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y,
                     double* stderr_out) {
  const size_t n = x.size();
  double mx = 0.0, my = 0.0;
  for (size_t i = 0; i < n; ++i) {
    mx += std::log(x[i]);
    my += std::log(y[i]);
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double dx = std::log(x[i]) - mx, dy = std::log(y[i]) - my;
    sxx += dx * dx;
    sxy += dx * dy;
  }
  const double slope = sxy / sxx;
  if (stderr_out) {
    double rss = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double r = std::log(y[i]) - my - slope * (std::log(x[i]) - mx);
      rss += r * r;
    }
    *stderr_out = n > 2 ? std::sqrt(rss / static_cast<double>(n - 2) / sxx) : 0.0;
  }
  return slope;
}

std::string order_note(const Scene& scene, const std::string& engine, Integrator integrator,
                       double order, const std::string& against) {
  const double nominal = nominal_order(integrator);
  if (order >= nominal - 0.3) return "";
  const ContactParams& p = scene.contact;
  if (engine != "ref" && against == "reference") {
    const engines::EngineInfo* info = engines::find_engine(engine);
    return "levels off at the distance between " +
           (info != nullptr ? std::string(info->title) : engine) +
           "'s contact model and the penalty law, which no step removes";
  }
  if (engine != "ref") {
    return "its contacts also switch on and off inside a step, which holds every fixed-step "
           "method to low order";
  }
  std::string note;
  if (integrator == Integrator::RK4 && p.c > 0.0) {
    note =
        "the normal force jumps by c·|v_n| when a point enters contact (damping starts with "
        "the contact): a fixed step across the jump errs by O(Δt) in velocity per impact, so "
        "the method is first order";
  } else if (integrator == Integrator::RK4) {
    note =
        "the force is continuous but its slope jumps at contact entry and exit (the k·d kink): "
        "O(Δt²) per event, second order";
  } else {
    note = "pre-asymptotic";
  }
  if (p.mu > 0.0 && p.alpha * p.mu * scene.sim.gravity > 100.0) {
    note += "; stiff tanh friction (μ·g·α = " +
            format_number("%.3g", p.mu * scene.sim.gravity * p.alpha) +
            " 1/s) and stick–slip transitions need Δt ≪ 1/(μ·g·α) before the asymptotic rate shows";
  }
  if (shape_features(scene.shape).rolls && p.mu_roll > 0.0) {
    note +=
        "; the regularised sign of rolling resistance, tanh(α·R·ω), turns on sharply as the "
        "disc stops";
  }
  return note;
}

std::vector<OrderFit> fit_orders(const Scene& scene, const std::vector<SweepRow>& rows,
                                 double reference_error, double length_scale) {
  const double ceiling = 0.1 * length_scale;
  const double floor = std::max(10.0 * reference_error, 1e-12 * std::max(1.0, length_scale));
  std::vector<OrderFit> fits;
  std::vector<std::pair<std::string, Integrator>> keys;
  for (const SweepRow& row : rows) {
    const auto key = std::make_pair(row.engine, row.integrator);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  for (const auto& [engine, integrator] : keys) {
    for (const std::string against : {"reference", "own finest"}) {
      if (against == std::string("own finest") && engine == "ref") continue;
      double dt_finest = INFINITY;
      for (const SweepRow& row : rows) {
        if (row.engine == engine && row.integrator == integrator && row.status == RunStatus::Ok) {
          dt_finest = std::min(dt_finest, row.dt);
        }
      }
      std::vector<std::pair<double, double>> points;  // (dt, error)
      for (const SweepRow& row : rows) {
        if (row.engine != engine || row.integrator != integrator || row.status != RunStatus::Ok)
          continue;
        double err = row.error.max_pos;
        if (against == std::string("own finest")) {
          // Distances to the finest run shrink artificially next to it.
          if (!row.self_error || row.dt < 1.99 * dt_finest) continue;
          err = row.self_error->max_pos;
        }
        if (err > floor && err < ceiling) points.emplace_back(row.dt, err);
      }
      std::sort(points.begin(), points.end());
      OrderFit fit;
      fit.engine = engine;
      fit.integrator = integrator;
      fit.against = against;
      fit.nominal = nominal_order(integrator);
      fit.points = static_cast<int>(points.size());
      if (points.size() >= 3) {
        std::vector<double> x, y;
        for (const auto& [dt, err] : points) {
          x.push_back(dt);
          y.push_back(err);
        }
        fit.order = log_log_slope(x, y, &fit.order_stderr);
        fit.dt_min = x.front();
        fit.dt_max = x.back();
        fit.note = order_note(scene, engine, integrator, *fit.order, against);
      } else if (engine != "ref" && against == std::string("reference")) {
        fit.note = "no slope: every run is at least " + format_number("%.1g", ceiling) +
                   " m (10 % of the scene's length scale) from the reference, the distance between "
                   "the models";
      } else {
        fit.note = "fewer than 3 runs with an error between " + format_number("%.1g", floor) +
                   " m (the floor) and " + format_number("%.1g", ceiling) +
                   " m (10 % of the scene's length scale)";
      }
      fits.push_back(fit);
    }
  }
  return fits;
}

namespace {

// Refuses a configuration the sweep cannot run (std::invalid_argument,
// naming the option).
void check_sweep_config(const Scene& scene, const SweepConfig& config) {
  if (config.engines.empty()) throw std::invalid_argument("--engines: the list is empty");
  if (config.integrators.empty()) throw std::invalid_argument("--integrators: the list is empty");
  if (config.dts.empty()) throw std::invalid_argument("--dts: the list is empty");
  std::vector<double> all_dts = config.dts;
  if (config.other_dts)
    all_dts.insert(all_dts.end(), config.other_dts->begin(), config.other_dts->end());
  for (double dt : all_dts) {
    if (!(dt > 0.0) || !std::isfinite(dt) || dt > scene.sim.duration ||
        scene.sim.duration / dt > 1e9) {
      throw std::invalid_argument(
          "--dts: " +
          (std::isfinite(dt) ? format_number("%g", dt) : std::string("a non-finite value")) +
          " is not a step in (0, sim.duration] with at most 1e9 steps");
    }
  }
  if (!(config.reference_tol >= 1e-15 && config.reference_tol <= 1e-3)) {
    throw std::invalid_argument("--tol: must be in [1e-15, 1e-3]");
  }
}

// One row per engine, integrator it offers and Δt (an engine other than
// ref takes the other_ lists where they are given).
std::vector<SweepRow> sweep_rows(const SweepConfig& config) {
  std::vector<SweepRow> rows;
  for (const std::string& engine : config.engines) {
    const std::vector<Integrator>& integrators = (engine != "ref" && config.other_integrators)
                                                     ? *config.other_integrators
                                                     : config.integrators;
    for (Integrator integrator : integrators) {
      if (!engines::engine_offers(engine, integrator)) continue;
      const std::vector<double>& dts =
          (engine != "ref" && config.other_dts) ? *config.other_dts : config.dts;
      for (double dt : dts) {
        SweepRow row;
        row.engine = engine;
        row.integrator = integrator;
        row.dt = dt;
        rows.push_back(row);
      }
    }
  }
  return rows;
}

// The jobs, longest first so that the two threads finish together: cost ∝
// steps × force evaluations per step (an engine other than ref costs ~50×
// more).
std::vector<Job> sweep_jobs(const Scene& scene, const SweepConfig& config,
                            const std::vector<SweepRow>& rows) {
  std::vector<Job> jobs;
  jobs.push_back({Job::Reference, 0, INFINITY});
  jobs.push_back({Job::LooseReference, 0, INFINITY});
  for (size_t i = 0; i < config.dense_tols.size(); ++i) jobs.push_back({Job::Dense, i, 1e9});
  for (size_t i = 0; i < rows.size(); ++i) {
    const double evals = rows[i].integrator == Integrator::RK4             ? 4.0
                         : rows[i].integrator == Integrator::ImplicitEuler ? 10.0
                                                                           : 1.0;
    const double engine_cost = rows[i].engine == "ref" ? 1.0 : 50.0;
    jobs.push_back({Job::Run, i, engine_cost * evals * scene.sim.duration / rows[i].dt});
  }
  std::stable_sort(jobs.begin(), jobs.end(),
                   [](const Job& a, const Job& b) { return a.cost > b.cost; });
  return jobs;
}

// Runs one row (best of `repeats` wall-clock times; the first run's
// trajectory is kept in `trajectory`). A run that diverges or throws marks
// the row, never the sweep.
void run_sweep_row(SweepRow& row, Trajectory& trajectory, const Scene& scene,
                   const SweepConfig& config, int repeats, const EngineRunner& runner) {
  Scene s = scene;
  s.sim.integrator = row.integrator;
  s.sim.dt = row.dt;
  try {
    double best = INFINITY;
    for (int r = 0; r < repeats; ++r) {
      EngineRun run = runner(row.engine, s);
      best = std::min(best, run.seconds);
      row.repeats = r + 1;
      if (r == 0) {
        trajectory = std::move(run.trajectory);
        row.warnings = std::move(run.warnings);
        row.divergence = trajectory.divergence;
        if (row.divergence) {
          row.status = RunStatus::Diverged;
          // A runner of the tests' own may leave the message empty.
          row.message = run.divergence_message.empty() ? describe(*row.divergence, s)
                                                       : run.divergence_message;
          break;
        }
      }
      if (run.seconds > config.single_run_seconds) break;
    }
    row.seconds = best;
  } catch (const std::exception& e) {
    row.status = RunStatus::Failed;
    row.message = e.what();
  }
}

// The errors of the finished runs: the reference's own (against the run at
// 10× its tolerance), the adaptive runs', every row's against the reference
// and against its engine/integrator's finest run; the length scale and the
// observed orders.
void measure_sweep(SweepResult& result, const Scene& scene, const TimedReference& loose,
                   const std::vector<DenseTrajectory>& dense_runs,
                   const std::vector<Trajectory>& trajectories) {
  std::vector<SweepRow>& rows = result.rows;
  const DenseTrajectory& reference = result.reference.trajectory;
  if (!reference.ok()) {
    throw std::runtime_error("the converged reference failed: " + reference.failure());
  }
  result.reference_loose_seconds = loose.seconds;
  result.reference_error =
      loose.trajectory.ok()
          ? error_between(loose.trajectory, reference, output_times(scene.sim)).max_pos
          : INFINITY;

  const std::vector<double> times = output_times(scene.sim);
  for (size_t i = 0; i < dense_runs.size(); ++i) {
    if (result.dense_curve[i].failure.empty()) {
      result.dense_curve[i].error = error_between(dense_runs[i], reference, times);
    }
  }

  // Errors against the reference, and against each engine/integrator's finest run.
  std::map<std::pair<std::string, Integrator>, size_t> finest;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].status != RunStatus::Ok) continue;
    rows[i].error = error_against(trajectories[i], reference);
    const auto key = std::make_pair(rows[i].engine, rows[i].integrator);
    auto it = finest.find(key);
    if (it == finest.end() || rows[i].dt < rows[it->second].dt) finest[key] = i;
  }
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].status != RunStatus::Ok) continue;
    const size_t f = finest.at({rows[i].engine, rows[i].integrator});
    if (f != i) rows[i].self_error = error_between(trajectories[i], trajectories[f]);
  }
  // Length scale: the body's size or the COM's largest displacement.
  const State start = reference.at(0.0);
  result.length_scale = body_extent(make_body(scene));
  for (double t : output_times(scene.sim)) {
    result.length_scale =
        std::max(result.length_scale, (reference.at(t).q.head<2>() - start.q.head<2>()).norm());
  }
  result.orders = fit_orders(scene, rows, result.reference_error, result.length_scale);
}

}  // namespace

SweepResult run_sweep(const Scene& scene, const SweepConfig& config, const EngineRunner& runner) {
  check_sweep_config(scene, config);

  SweepResult result;
  result.scene_name = std::string(shape_name(scene.shape));
  result.duration = scene.sim.duration;
  result.threads = config.threads == 0 ? default_threads() : config.threads;
  result.repeats = std::max(1, config.repeats);
  result.single_run_seconds = config.single_run_seconds;

  result.rows = sweep_rows(config);
  std::vector<SweepRow>& rows = result.rows;
  std::vector<Trajectory> trajectories(rows.size());
  result.dense_curve.resize(config.dense_tols.size());
  std::vector<DenseTrajectory> dense_runs(config.dense_tols.size());
  const std::vector<Job> jobs = sweep_jobs(scene, config, rows);

  TimedReference loose;
  std::mutex progress_mutex;
  size_t done = 0;
  parallel_for(jobs.size(), config.threads, [&](size_t j) {
    const Job& job = jobs[j];
    std::string what;
    if (job.kind == Job::Reference) {
      result.reference = timed_reference(scene, config.reference_tol);
      what = "converged reference";
    } else if (job.kind == Job::LooseReference) {
      loose = timed_reference(scene, 10.0 * config.reference_tol, 1);
      what = "reference check";
    } else if (job.kind == Job::Dense) {
      TimedReference run = timed_reference(scene, config.dense_tols[job.row]);
      ToleranceRow& row = result.dense_curve[job.row];
      row.tol = run.tol;
      row.seconds = run.seconds;
      row.stats = run.trajectory.stats();
      row.failure = run.trajectory.failure();
      dense_runs[job.row] = std::move(run.trajectory);
      what = "adaptive tol=" + format_number("%g", config.dense_tols[job.row]);
    } else {
      SweepRow& row = rows[job.row];
      what = row.engine + " " + std::string(integrator_name(row.integrator)) +
             " dt=" + format_number("%g", row.dt);
      run_sweep_row(row, trajectories[job.row], scene, config, result.repeats, runner);
    }
    if (config.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      config.progress(++done, jobs.size(), what);
    }
  });

  measure_sweep(result, scene, loose, dense_runs, trajectories);
  return result;
}

}  // namespace contact2d::analysis
