// Real trajectories: a recording of measured trajectories (io/recording.hpp,
// kind "trajectories") in, the contact law's k, ζ (c) and μ out, and the
// reference, the registry's other engines and the recording's peer engine
// (PyBullet for the square) measured on trajectories the fit did not see
// (docs/real-trajectories.md).
//
// The replay of one trajectory. Its first sample is the start: when the body
// penetrates the ground there it is moved up along +y until its lowest
// point just touches (θ and the velocities kept), as for the impacts. The
// engine runs from there for `window` s (0.4 s), and its pose is read at
// every recorded sample time in the window (Δt divides the frame period, so
// the sample times are step times).
//
// The error of one trajectory, the fit's one metric: the largest,
// over the samples of the window, of the RMS distance between the body's
// four reference points predicted and recorded — a box's corners, an
// ellipse's or a circle's axis ends (±a, 0), (0, ±b) — matched up to the
// turn that maps the outline onto itself (a quarter turn for a square or a
// circle, a half turn otherwise). In metres, it combines position and
// angle:
//   e(t)² = |Δc|² + ρ²·2·(1 − cos Δθ'),
// Δc the centre's offset, Δθ' the angle difference reduced to the outline's
// symmetry (|Δθ'| ≤ a quarter or an eighth of a turn), ρ² the mean squared
// distance of the points from the centre ((w² + h²)/4 for a box, (a² + b²)/2
// for an ellipse). A point mass's is the centre's distance. Secondary: the
// largest centre distance |Δc| and the largest |Δθ'| over the same samples.
// A model's figure is the median over the held-out trajectories, with the
// interquartile range.
//
// The models:
//   penalty  the reference's law (analysis/fit_common.hpp): Kelvin–Voigt
//            normal force, c = 2ζ·√(k·m), tanh friction μ (the scene's
//            default α = 100 s/m); semi-implicit Euler at ω·Δt ≤ omega_dt
//            (0.05; ω = √(k/m_eff), m_eff the body's smallest effective
//            mass), Δt the largest such step that divides the frame period.
//            The training trajectories' median error is minimised over
//            (log10 k, ζ, μ) in [3, 6.5] × [0, 1.5] × [0, 2]: a 3 × 3 × 3
//            grid (log10 k 4, 5, 6; ζ 0.1, 0.3, 0.6; μ 0.05, 0.15, 0.4)
//            picks the start, NLopt's BOBYQA refines it. The same fit
//            replayed at ω·Δt / 5 measures the integrator's share
//   other engines (TrajectoryFitOptions::engines: MuJoCo 2.2.2 and 3.14)
//            with the penalty fit's k, c, μ through their default
//            (calibrated) mapping, nothing refitted
//   peer     the recording's peer replay (peer_csv: PyBullet's for the
//            square), read, not run: its own parameters, not fitted here
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/fit_common.hpp"
#include "analysis/real_impacts.hpp"
#include "io/recording.hpp"

namespace contact2d::analysis {

struct TrajectoryFitOptions {
  std::uint64_t seed = 2026;  // the seeded split's shuffle
  unsigned threads = 0;       // as parallel_for: 0 = the machine's cores
  // Engines the held-out trajectories are replayed on with the penalty
  // fit's parameters (registry names); empty: none.
  std::vector<std::string> engines;
  double window = 0.4;       // s of each trajectory replayed and compared
  double omega_dt = 0.05;    // the largest ω·Δt of the replays
  int max_evaluations = 60;  // of the objective, per start of the fit
  // One line of progress (what is being done, how far); may be empty.
  std::function<void(const std::string&)> progress;
};

// The errors of one replayed trajectory, each the largest over the samples.
struct PoseError {
  double points = 0.0;   // m: RMS distance of the reference points (the metric)
  double centre = 0.0;   // m: distance of the centres
  double angle = 0.0;    // rad: angle difference modulo the outline's symmetry
  bool stopped = false;  // the replay stopped (a step failed): counted 1 m and the largest angle
};

struct TrajectoryModel {
  std::string name;                 // "penalty", or the peer's name ("PyBullet")
  std::string engine;               // "ref", an engine of the registry, or "peer"
  std::string split;                // "seeded" or "chronological"
  Quartiles points, centre, angle;  // over the held-out trajectories
  std::vector<std::pair<std::string, double>> parameters;  // empty for the peer
  double train_median = 0.0;      // the fitted objective on the training half
  int evaluations = 0;            // objective evaluations of the fit
  double dt = 0.0;                // s: the replay's step (0 for the peer)
  int failed = 0;                 // held-out replays that stopped (PoseError::stopped)
  std::vector<PoseError> errors;  // per held-out trajectory, in `test` order
};

struct TrajectorySplit {
  std::string split;
  std::vector<size_t> train, test;  // indices into Recording::trajectories
  std::vector<TrajectoryModel> models;
  // The replays of the penalty fit on every pair of engines (the reference
  // first), apart by the metric between them: its median over the held-out
  // trajectories.
  using Distance = SplitFit::Distance;  // a, b, median
  std::vector<Distance> engine_distances;
  // How well k is determined: the grid's best training median at each of
  // its k (ζ and μ over the grid's 3 × 3 values).
  std::vector<std::pair<double, double>> k_grid;
  // The integrator's share: the penalty fit replayed on the held-out
  // trajectories at a fifth of the step (ω·Δt = omega_dt / 5).
  struct StepCheck {
    double omega_dt = 0.0, dt = 0.0;
    double median = 0.0;  // the metric's held-out median at that step
    double apart = 0.0;   // the two replays apart: the metric between them, median
  };
  StepCheck step_check;
};

struct TrajectoryFit {
  std::string recording;
  std::string peer;  // the peer's name, empty without one
  size_t trajectories = 0;
  size_t samples = 0;        // per trajectory in the window (the fewest)
  int lifted = 0;            // first samples moved up to touch
  double median_lift = 0.0;  // m, over the lifted ones
  double mass = 0.0, inertia = 0.0;
  double window = 0.0, omega_dt = 0.0;
  std::vector<TrajectorySplit> splits;  // seeded, then chronological
  double seconds = 0.0;                 // wall time of the whole fit
};

// The scene a replay of `recording` runs with law `p`: the recorded body,
// the penalty law (analysis/fit_common.hpp) and semi-implicit Euler at the
// largest Δt ≤ omega_dt/ω that divides the frame period, for `window` s.
Scene trajectory_replay_scene(const Recording& recording, const PenaltyParams& p, double omega_dt,
                              double window);

// Checks the recording (one line naming the file, row and field when a
// trajectory or its peer cannot be compared) and fits and measures every
// model on both splits.
TrajectoryFit fit_trajectories(const Recording& recording, const TrajectoryFitOptions& options);

// `contact2d fit --json` for trajectories: one object whose `models` list
// holds one entry per model, engine and split (name, engine, split, median,
// iqr, q1, q3, parameters), as for impacts, with the secondary columns.
std::string trajectory_fit_json(const TrajectoryFit& fit);
// The table `contact2d fit` prints.
std::string trajectory_fit_text(const TrajectoryFit& fit);

}  // namespace contact2d::analysis
