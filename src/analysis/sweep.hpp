// Error against run time: every engine × integrator × Δt run of a scene,
// measured against the scene's converged reference (core/dense_reference).
//
// For each run: the largest position error over the sampled times, the error
// at the end, the largest angle error, the distance to the same engine and
// integrator at the smallest Δt of the sweep (an engine's own convergence:
// for MuJoCo the error against the reference also holds the difference
// between the two models), and the wall-clock time, the best of several
// repeats. Runs go to a pool of threads, one per core.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/engine.hpp"
#include "analysis/reference.hpp"

namespace contact2d::analysis {

struct SweepConfig {
  std::vector<std::string> engines{"ref"};
  std::vector<Integrator> integrators{std::begin(kAllIntegrators), std::end(kAllIntegrators)};
  std::vector<double> dts{1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5};
  int repeats = 3;                   // best of this many runs …
  double single_run_seconds = 0.25;  // … unless one run takes longer than this
  double reference_tol = 1e-12;
  // Engines other than "ref" run only these steps when given (MuJoCo's step
  // costs ~100× a reference step: its smallest steps dominate a sweep).
  std::optional<std::vector<double>> other_dts;
  // … and only these integrators when given.
  std::optional<std::vector<Integrator>> other_integrators;
  // The adaptive integrator itself at these tolerances, for the work–precision
  // diagram (error against the reference, best-of-3 time).
  std::vector<double> dense_tols{1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  unsigned threads = 0;  // 0: one per core
  // Called from worker threads (serialised) after each configuration.
  std::function<void(size_t done, size_t total, const std::string& what)> progress;
};

enum class RunStatus { Ok, Diverged, Failed };

struct SweepRow {
  std::string engine;
  Integrator integrator = Integrator::SemiImplicitEuler;
  double dt = 0.0;
  RunStatus status = RunStatus::Ok;
  std::string message;  // divergence diagnostic or error text
  std::optional<Divergence> divergence;
  TrajectoryError error;                      // against the converged reference
  std::optional<TrajectoryError> self_error;  // against the smallest Δt (not for that run itself)
  double seconds = 0.0;                       // best wall-clock time
  int repeats = 0;                            // runs it is the best of
  std::vector<std::string> warnings;
};

// Observed order: least-squares slope of log(max position error) against
// log(Δt) over the asymptotic range — the runs that did not diverge, whose
// error is above a floor and below 10 % of the scene's length scale L (the
// body's size or the largest displacement of its COM, whichever is larger:
// beyond that a run is not yet in the asymptotic regime — a different
// bounce, a different tumble). The floor is 10× the reference's own error,
// and at least 1e-12·max(1 m, L): a fixed-step run's rounding random-walks
// to about √n·ε·|y| ≈ 1e-13 m over n = 1e5 steps. Against an engine's own
// finest run, only runs at ≥ 2× its step count (closer ones shrink
// artificially).
struct OrderFit {
  std::string engine;
  Integrator integrator = Integrator::SemiImplicitEuler;
  std::string against;  // "reference" or "own finest"
  double nominal = 0.0;
  std::optional<double> order;  // none with fewer than 3 usable points
  double order_stderr = 0.0;    // standard error of the fitted slope
  int points = 0;
  double dt_min = 0.0;
  double dt_max = 0.0;
  std::string note;  // why the order is below nominal, if it is
};

struct SweepResult {
  std::string scene_name;
  double duration = 0.0;
  TimedReference reference;      // the converged reference the errors are against
  double reference_error = 0.0;  // its own error bound: distance to the run at 10× the tolerance
  double reference_loose_seconds = 0.0;
  double length_scale = 0.0;  // L of the order fit, m
  std::vector<SweepRow> rows;
  std::vector<ToleranceRow> dense_curve;  // the adaptive method at other tolerances
  std::vector<OrderFit> orders;
  unsigned threads = 1;
  int repeats = 0;
  double single_run_seconds = 0.0;
};

// Throws std::invalid_argument for an empty or invalid list.
SweepResult run_sweep(const Scene& scene, const SweepConfig& config,
                      const EngineRunner& runner = registry_runner());

// Fits the observed orders of a finished sweep (run_sweep calls it).
std::vector<OrderFit> fit_orders(const Scene& scene, const std::vector<SweepRow>& rows,
                                 double reference_error, double length_scale);

// Least-squares slope of log(y) against log(x); `stderr_out`, when given,
// receives its standard error (residual spread over the spread of log x).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y,
                     double* stderr_out = nullptr);

// Why an observed order falls below nominal, from the scene's features.
std::string order_note(const Scene& scene, const std::string& engine, Integrator integrator,
                       double order, const std::string& against);

}  // namespace contact2d::analysis
