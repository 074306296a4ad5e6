// Real impacts: a recording of measured impacts (io/recording.hpp) in, the
// contact law's parameters out, and every model measured on impacts it was
// not fitted to (docs/real-impacts.md).
//
// The replay of one impact. The state just before the impact is moved up
// along the ground's normal (+y) until the body just touches when its
// lowest point already penetrates (a quarter of the ellipse's frames do:
// the camera samples at 250 Hz, about 10 mm of fall per frame); a state
// above the ground falls freely to first touch inside the replay. The
// engine then runs from there until the body leaves the ground (its lowest
// point back above y = 0 after having been below), and the velocity at that
// step is the prediction v̂ = (v̂x, v̂y, ω̂); a body still on the ground
// after 8 undamped half-periods π·√(m/k) is a failed prediction (error 10,
// ModelFit::unseparated_replays).
//
// The error of one impact, the one metric of this page:
//   e = ‖W·(v̂ − v)‖ / ‖W·v‖,   W = diag(1, 1, √(I/m)),
// v the recorded velocity just after the impact: the spin enters in the
// same units as the speeds (√(I/m)·ω is the speed of a point at the radius
// of gyration). A model's figure is the median of e over the held-out
// impacts, with its interquartile range.
//
// The models, each fitted on the training half and measured on the other:
//   penalty       the reference's law: Kelvin–Voigt normal force
//                 Fn = k·d − c·ḋ, c = 2ζ·√(k·m), tanh friction μ, rolling
//                 resistance μ_roll (core/contact.hpp), semi-implicit Euler
//                 at ω·Δt = 0.02 (ω = √(k/m_eff), m_eff the smallest
//                 effective mass of the body): minimises the training
//                 impacts' median error (the statistic reported) over
//                 (log10 k, ζ, μ, μ_roll) in [3, 9] × [0, 1.5] × [0, 2] ×
//                 [0, 0.03 m] with NLopt's BOBYQA from three starts and
//                 from the fit without rolling resistance, then from the
//                 best point of a 7 × 7 grid of (log10 k, ζ) and of k's
//                 profile when either is better: never worse than a point
//                 the fit evaluated
//   penalty (no rolling resistance)   the same with μ_roll = 0
//   constant      v̂ = the training impacts' mean post-impact velocity
//   newton_coulomb   one impulse P at the lowest point: Newton's
//                 restitution e_n of the normal contact velocity, and the
//                 tangential impulse that stops the slip unless it exceeds
//                 μ·P_n (then ±μ·P_n); fits (e_n, μ) on the same median
//   irb_bound     the best single-point impulse chosen after the fact: for
//                 each held-out impact, the impulse P = (P_t, P_n ≥ 0) at the
//                 lowest point that minimises that impact's own error (a
//                 bound no impulse model at that point can beat, not a
//                 prediction)
//   other engines (ImpactFitOptions::engines: MuJoCo 2.2.2 and 3.14) with
//                 the penalty fit's k, c, μ, μ_roll through their mapping
//                 (calibrated by default; nothing refitted)
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/recording.hpp"

namespace contact2d::analysis {

struct ImpactFitOptions {
  std::uint64_t seed = 2026;  // the seeded split's shuffle
  int bootstrap = 8;          // refits on resampled training sets (0: none)
  unsigned threads = 0;       // as parallel_for: 0 = the machine's cores
  // Engines the held-out impacts are replayed on with the penalty fit's
  // parameters (registry names); empty: none.
  std::vector<std::string> engines;
  bool all_impacts = false;  // also the impacts the recording flags
  // k's profile on both splits (7 refits of ζ, μ, μ_roll at log10 k = 3 … 9),
  // the fit then started again from its best point when that is better.
  bool k_profile = true;
  // ω·Δt of the replays (ω = √(k/m_eff)): semi-implicit Euler's restitution
  // is off by at most 0.16·ω·Δt relative (tests/core/test_ellipse.cpp), 0.3 %.
  double omega_dt = 0.02;
  // One line of progress (what is being done, how far); may be empty.
  std::function<void(const std::string&)> progress;
};

struct ModelFit {
  std::string name;                         // "penalty", "constant", …
  std::string engine;                       // "ref", an engine of the registry, or "baseline"
  std::string split;                        // "seeded" or "chronological"
  double median = 0.0, q1 = 0.0, q3 = 0.0;  // of the held-out errors
  std::vector<std::pair<std::string, double>> parameters;
  // Bootstrap spread of each parameter (the 16th and 84th percentiles of
  // the refits), same order as `parameters`; empty without a bootstrap.
  std::vector<std::pair<double, double>> spread;
  double train_median = 0.0;  // the fitted objective on the training half
  int evaluations = 0;        // objective evaluations of the fit
  // Held-out replays that did not finish (a step not finite): each counts
  // as an error of 10 in `errors` and is said, never left out silently.
  int failed_replays = 0;
  // Held-out replays still touching the ground when their window ended
  // (replay_window, below): each counts as an error of 10 too, and is said.
  int unseparated_replays = 0;
  // s: the longest contact a replay of this model followed, 8 undamped
  // half-periods π·√(m/k) at its k (0 for the baselines, which replay nothing).
  double replay_window = 0.0;
  std::vector<double> errors;   // per held-out impact, in `test` order
  std::vector<Vec3> predicted;  // v̂ per held-out impact
  double iqr() const { return q3 - q1; }
};

struct SplitFit {
  std::string split;
  std::vector<size_t> train, test;  // indices into ImpactFit::impacts
  std::vector<ModelFit> models;
  // ‖W·(v̂_a − v̂_b)‖/‖W·v‖ per held-out impact, median, between every pair
  // of engines that replayed the penalty fit (the reference first).
  struct Distance {
    std::string a, b;
    double median = 0.0;
  };
  std::vector<Distance> engine_distances;
  // k's profile: the training mean error with log10 k fixed at each point of
  // the grid and ζ, μ, μ_roll refitted (how well k is determined).
  std::vector<std::pair<double, double>> k_profile;
  // What no impulse at the lowest point captures: least squares over the
  // held-out impacts of the measured spin change, Δω = spin_slope·Δω_point
  // + spin_intercept, Δω_point = m·(r_x·Δv_y − r_y·Δv_x)/I the change a
  // point impulse at the lowest point r (at first touch) would make with
  // the measured change of velocity Δv.
  double spin_slope = 0.0, spin_intercept = 0.0;
};

struct ImpactFit {
  std::string recording;
  std::vector<RecordedImpact> impacts;  // the ones used (unflagged unless all_impacts)
  int flagged_left_out = 0;
  int lifted = 0;            // pre-impact states moved up to first touch
  double median_lift = 0.0;  // m, over the lifted ones
  double inertia = 0.0, mass = 0.0;
  std::vector<SplitFit> splits;  // seeded, then chronological
  double seconds = 0.0;          // wall time of the whole fit
};

// The engines a fit replays by default: every engine of the registry that
// is built in and whose contacts are soft constraints (MuJoCo's kind).
std::vector<std::string> default_fit_engines();

// Checks the recording (one line naming the row and field when an impact
// cannot be replayed) and fits every model on both splits.
ImpactFit fit_impacts(const Recording& recording, const ImpactFitOptions& options);

// The one metric: ‖W·(predicted − measured)‖/‖W·measured‖, W = diag(1, 1, √(I/m)).
double impact_error(const Vec3& predicted, const Vec3& measured, double inertia, double mass);

// Median and quartiles (linear interpolation between order statistics).
struct Quartiles {
  double q1 = 0.0, median = 0.0, q3 = 0.0;
};
Quartiles quartiles(std::vector<double> values);

}  // namespace contact2d::analysis

namespace contact2d::analysis {

// `contact2d fit --json`: one object; its `models` list holds one entry per
// model, engine and split (name, engine, split, median, iqr, q1, q3,
// parameters, spread), beside the counts, the k profile and the engine
// distances (analysis/real_impacts_text.cpp).
std::string impact_fit_json(const ImpactFit& fit);
// The table `contact2d fit` prints.
std::string impact_fit_text(const ImpactFit& fit);

}  // namespace contact2d::analysis

namespace contact2d::analysis {

// The pictures of the report's real_impacts.md (gnuplot; each an atomic
// file): for one split, measured against predicted vx, vy and ω after the
// impact (the penalty law on the reference, Newton + Coulomb, the best
// impulse after the fact); the distribution of every model's held-out
// errors; the seeded split's profile of k. Throw as plot_sweep does.
void plot_impact_predictions(const std::string& png_path, const ImpactFit& fit,
                             const std::string& split);
void plot_impact_errors(const std::string& png_path, const ImpactFit& fit,
                        const std::string& split);
void plot_k_profile(const std::string& png_path, const ImpactFit& fit);

}  // namespace contact2d::analysis
