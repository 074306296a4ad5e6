#include "analysis/real_trajectories.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>

#include "analysis/engine.hpp"
#include "analysis/fit_common.hpp"
#include "analysis/minimise.hpp"
#include "core/cancel.hpp"
#include "core/contacts.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/stepper.hpp"
#include "engines/engines.hpp"

namespace contact2d::analysis {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFailedDistance = 1.0;  // m: a replay that stops counts this far off
constexpr double kTimeTolerance = 1e-9;  // s: sample times that agree
// The fit's box, (log10 k, ζ, μ), and the grid that picks BOBYQA's start.
constexpr double kLogK[2] = {3.0, 6.5};
constexpr double kZetaMax = 1.5, kMuMax = 2.0;
constexpr double kGridLogK[3] = {4.0, 5.0, 6.0};
constexpr double kGridZeta[3] = {0.1, 0.3, 0.6};
constexpr double kGridMu[3] = {0.05, 0.15, 0.4};
// The step check's step: a fifth of the fit's (the error of semi-implicit
// Euler is first order in Δt, so the replays' distance at Δt/5 is 4/5 of
// the fit's own integration error).
constexpr double kFiner = 5.0;

// The body's reference points as the metric sees them: the mean squared
// distance ρ² of the four points from the centre and the turn that maps
// the outline onto itself (0: a point mass, which does not turn).
struct Outline {
  double rho2 = 0.0;
  double turn = 0.0;
};

Outline outline_of(const Recording& rec) {
  const Scene& b = rec.body;
  switch (b.shape) {
    case Shape::Box:
      return {(b.width * b.width + b.height * b.height) / 4.0,
              b.width == b.height ? kPi / 2.0 : kPi};
    case Shape::Ellipse: return {(b.a * b.a + b.b * b.b) / 2.0, b.a == b.b ? kPi / 2.0 : kPi};
    case Shape::Circle: return {b.radius * b.radius, kPi / 2.0};
    case Shape::PointMass: return {0.0, 0.0};
    default:
      throw InputError(rec.path + ": body.shape = \"" + std::string(shape_name(b.shape)) +
                       "\": a trajectories fit takes box, ellipse, circle or point_mass");
  }
}

PoseError pose_error(const Outline& o, const Vec3& predicted, const Vec3& recorded) {
  PoseError e;
  const double dx = predicted.x() - recorded.x(), dy = predicted.y() - recorded.y();
  e.centre = std::sqrt(dx * dx + dy * dy);
  double dth = 0.0;
  if (o.turn > 0.0) {
    dth = predicted.z() - recorded.z();
    dth -= o.turn * std::round(dth / o.turn);
  }
  e.angle = std::abs(dth);
  e.points = std::sqrt(e.centre * e.centre + o.rho2 * 2.0 * (1.0 - std::cos(dth)));
  return e;
}

void take_largest(PoseError& into, const PoseError& e) {
  into.points = std::max(into.points, e.points);
  into.centre = std::max(into.centre, e.centre);
  into.angle = std::max(into.angle, e.angle);
}

using Poses = std::vector<Vec3>;  // poses at the samples of one trajectory (empty: stopped)

// What every replay of one recording needs.
struct Problem {
  const Recording* rec = nullptr;
  Outline outline;
  std::vector<size_t> samples;  // per trajectory: samples in the window
  std::vector<State> starts;    // per trajectory: the first sample, lifted to touch
  std::vector<Poses> recorded;  // per trajectory: its poses in the window
  unsigned threads = 1;
};

// Runs `stepper` from trajectory i's start; its poses at the recording's
// sample times, or none when a step fails.
Poses replay(Stepper& stepper, const Problem& pb, size_t i, double dt) {
  throw_if_cancelled();  // Python's Ctrl-C (core/cancel.hpp): at every trajectory
  const RecordedTrajectory& tr = pb.rec->trajectories[i];
  const size_t n = pb.samples[i];
  const auto step_of = [&](size_t s) { return std::llround((tr.t[s] - tr.t[0]) / dt); };
  stepper.reset(pb.starts[i]);
  stepper.plan(step_of(n - 1));
  Poses poses;
  long long at = 0;
  for (size_t s = 0; s < n; ++s) {
    for (const long long target = step_of(s); at < target; ++at)
      if (stepper.step() != StepStatus::Ok) return {};
    poses.push_back(stepper.state().q);
  }
  return poses;
}

// The largest errors of `predicted` against `recorded`, sample by sample; a
// replay that stopped counts kFailedDistance and the largest angle.
PoseError largest_error(const Outline& o, const Poses& predicted, const Poses& recorded) {
  if (predicted.empty() || recorded.empty())
    return {kFailedDistance, kFailedDistance, o.turn / 2.0, true};
  PoseError largest;
  for (size_t s = 0; s < std::min(predicted.size(), recorded.size()); ++s)
    take_largest(largest, pose_error(o, predicted[s], recorded[s]));
  return largest;
}

// Replays trajectories `which` on a stepper made by `make` per thread.
std::vector<Poses> replay_all(const Problem& pb, const std::vector<size_t>& which, double dt,
                              const std::function<std::unique_ptr<Stepper>()>& make) {
  std::vector<Poses> out(which.size());
  const unsigned chunks = std::max(1u, std::min<unsigned>(pb.threads, which.size()));
  parallel_for(chunks, chunks, [&](size_t c) {
    const std::unique_ptr<Stepper> stepper = make();
    for (size_t j = c; j < which.size(); j += chunks) out[j] = replay(*stepper, pb, which[j], dt);
  });
  return out;
}

std::vector<Poses> replay_ref(const Problem& pb, const Scene& scene,
                              const std::vector<size_t>& which) {
  return replay_all(pb, which, scene.sim.dt,
                    [&scene] { return std::make_unique<ReferenceStepper>(scene); });
}

// The errors of replays of trajectories `which` against the recording.
std::vector<PoseError> errors_of(const Problem& pb, const std::vector<size_t>& which,
                                 const std::vector<Poses>& replays) {
  std::vector<PoseError> out(which.size());
  for (size_t j = 0; j < which.size(); ++j)
    out[j] = largest_error(pb.outline, replays[j], pb.recorded[which[j]]);
  return out;
}

double median_points(const std::vector<PoseError>& errors) {
  std::vector<double> v(errors.size());
  for (size_t i = 0; i < errors.size(); ++i) v[i] = errors[i].points;
  return quartiles(v).median;
}

void summarise(TrajectoryModel& m) {
  std::vector<double> points, centre, angle;
  points.reserve(m.errors.size());
  centre.reserve(m.errors.size());
  angle.reserve(m.errors.size());
  for (const PoseError& e : m.errors) {
    points.push_back(e.points);
    centre.push_back(e.centre);
    angle.push_back(e.angle);
    if (e.stopped) ++m.failed;
  }
  m.points = quartiles(points);
  m.centre = quartiles(centre);
  m.angle = quartiles(angle);
}

// The samples of trajectory `tr` within the window from its first.
size_t samples_in_window(const RecordedTrajectory& tr, double window, const std::string& csv) {
  size_t n = 1;
  while (n < tr.t.size() && tr.t[n] - tr.t[0] <= window + kTimeTolerance) ++n;
  if (n < 2)
    throw InputError(csv + ":" + std::to_string(tr.line) +
                     ": field 'traj' = " + std::to_string(tr.id) + ": one sample in the first " +
                     format_number("%g", window) +
                     " s: a trajectory needs at least two to be compared");
  return n;
}

// The peer's poses at the recorded samples of every trajectory, its sample
// times checked against the recording's over the window.
std::vector<Poses> match_peer(const Recording& rec, const std::vector<size_t>& samples) {
  std::map<int, const RecordedTrajectory*> by_id;
  for (const RecordedTrajectory& p : rec.peer_trajectories) by_id[p.id] = &p;
  std::vector<Poses> out;
  for (size_t i = 0; i < rec.trajectories.size(); ++i) {
    const RecordedTrajectory& tr = rec.trajectories[i];
    const auto found = by_id.find(tr.id);
    if (found == by_id.end())
      throw InputError(rec.peer_csv +
                       ": no trajectory with field 'traj' = " + std::to_string(tr.id) +
                       " (the recording's, at " + rec.csv + ":" + std::to_string(tr.line) +
                       "): the peer must replay every recorded trajectory");
    const RecordedTrajectory& p = *found->second;
    out.emplace_back();
    for (size_t s = 0; s < samples[i]; ++s) {
      if (s >= p.t.size())
        throw InputError(rec.peer_csv + ":" + std::to_string(p.lines.back()) +
                         ": field 't': trajectory " + std::to_string(p.id) + " ends after " +
                         std::to_string(p.t.size()) + " samples, the recording compares " +
                         std::to_string(samples[i]));
      if (std::abs((p.t[s] - p.t[0]) - (tr.t[s] - tr.t[0])) > kTimeTolerance)
        throw InputError(rec.peer_csv + ":" + std::to_string(p.lines[s]) + ": field 't' = " +
                         format_number("%.9g", p.t[s]) + ": the recording's sample " +
                         std::to_string(s + 1) + " of trajectory " + std::to_string(tr.id) +
                         " is at " + format_number("%.9g", tr.t[s]) + " (" + rec.csv + ":" +
                         std::to_string(tr.lines[s]) + "): the peer must sample the same times");
      out.back().push_back(p.states[s].q);
    }
  }
  return out;
}

// One fit: the recording, the options, what every replay needs and the
// result, with one function per step.
struct Fitter {
  const Recording& rec;
  const TrajectoryFitOptions& options;
  Problem pb;
  TrajectoryFit out;

  void say(const std::string& line) const {
    if (options.progress) options.progress(line);
  }

  // The samples in the window, the starts (lifted to touch when they
  // penetrate) and the recorded poses of every trajectory.
  void prepare() {
    const Model geometry = make_model(rec.body);
    out.mass = geometry.body.mass;
    out.inertia = geometry.body.inertia;
    pb.rec = &rec;
    pb.outline = outline_of(rec);
    pb.threads = options.threads == 0 ? default_threads() : options.threads;
    ContactSet contacts(geometry);
    std::vector<double> lifts;
    for (const RecordedTrajectory& tr : rec.trajectories) {
      pb.samples.push_back(samples_in_window(tr, options.window, rec.csv));
      State start = tr.states.front();
      const double gap = ground_gap(geometry, start.q, contacts);
      if (gap < 0.0) {
        start.q.y() -= gap;
        lifts.push_back(-gap);
      }
      pb.starts.push_back(start);
      pb.recorded.emplace_back(pb.samples.back());
      for (size_t s = 0; s < pb.samples.back(); ++s) pb.recorded.back()[s] = tr.states[s].q;
    }
    out.samples = *std::min_element(pb.samples.begin(), pb.samples.end());
    out.lifted = static_cast<int>(lifts.size());
    out.median_lift = quartiles(lifts).median;
  }

  Scene scene(const PenaltyParams& p, double omega_dt) const {
    return trajectory_replay_scene(rec, p, omega_dt, options.window);
  }

  // The fitted law and its replays of the held-out trajectories.
  struct Fitted {
    PenaltyParams law;
    std::vector<Poses> replays;
  };

  // The reference: (log10 k, ζ, μ) on the training median; its held-out
  // errors are the split's first model.
  Fitted fit_reference(TrajectorySplit& sf) const {
    say("fit: " + sf.split + " split, penalty on " + std::to_string(sf.train.size()) +
        " trajectories (NLopt BOBYQA)");
    const auto objective = [&](const std::vector<double>& x) {
      const Scene s = scene({x[0], x[1], x[2], 0.0}, options.omega_dt);
      return median_points(errors_of(pb, sf.train, replay_ref(pb, s, sf.train)));
    };
    // A coarse grid picks the start (the error surface is rough: every
    // trajectory's largest error jumps where a bounce changes), BOBYQA
    // refines from its best point.
    Minimised fit;
    fit.f = INFINITY;
    for (const double log_k : kGridLogK) {
      double best_at_k = INFINITY;
      for (const double zeta : kGridZeta)
        for (const double mu : kGridMu) {
          const double e = objective({log_k, zeta, mu});
          ++fit.evaluations;
          best_at_k = std::min(best_at_k, e);
          if (e < fit.f) {
            fit.x = {log_k, zeta, mu};
            fit.f = e;
          }
        }
      sf.k_grid.push_back({std::pow(10.0, log_k), best_at_k});
    }
    say("fit: " + sf.split + " split, BOBYQA from the grid's best (log10 k " +
        format_number("%g", fit.x[0]) + ", zeta " + format_number("%g", fit.x[1]) + ", mu " +
        format_number("%g", fit.x[2]) + ": " + format_number("%.4f", fit.f) + " m)");
    const Minimised refined =
        minimise(objective, fit.x, {kLogK[0], 0.0, 0.0}, {kLogK[1], kZetaMax, kMuMax},
                 {0.25, 0.05, 0.03}, options.max_evaluations);
    fit.evaluations += refined.evaluations;
    if (refined.f < fit.f) {
      fit.x = refined.x;
      fit.f = refined.f;
    }
    const PenaltyParams best{fit.x[0], fit.x[1], fit.x[2], 0.0};
    const Scene s = scene(best, options.omega_dt);
    TrajectoryModel ref;
    ref.name = "penalty";
    ref.engine = "ref";
    ref.split = sf.split;
    ref.train_median = fit.f;
    ref.evaluations = fit.evaluations;
    ref.parameters = {{"k", s.contact.k}, {"zeta", best.zeta}, {"c", s.contact.c}, {"mu", best.mu}};
    ref.dt = s.sim.dt;
    Fitted fitted{best, replay_ref(pb, s, sf.test)};
    ref.errors = errors_of(pb, sf.test, fitted.replays);
    summarise(ref);
    sf.models.push_back(std::move(ref));
    return fitted;
  }

  // The integrator's share: the fit at a fifth of the step.
  void check_step(TrajectorySplit& sf, const Fitted& fitted) const {
    say("fit: " + sf.split +
        " split, the fit replayed at omega dt = " + format_number("%g", options.omega_dt / kFiner));
    const Scene fine = scene(fitted.law, options.omega_dt / kFiner);
    const std::vector<Poses> fine_replays = replay_ref(pb, fine, sf.test);
    const std::vector<Poses>& replays = fitted.replays;
    std::vector<double> errors(sf.test.size()), apart(sf.test.size());
    for (size_t j = 0; j < sf.test.size(); ++j) {
      errors[j] = largest_error(pb.outline, fine_replays[j], pb.recorded[sf.test[j]]).points;
      apart[j] = largest_error(pb.outline, fine_replays[j], replays[j]).points;
    }
    sf.step_check = {options.omega_dt / kFiner, fine.sim.dt, quartiles(errors).median,
                     quartiles(apart).median};
  }

  // The other engines with the reference's fit (their default mapping),
  // and how far apart each pair of engines' replays are.
  void replay_engines(TrajectorySplit& sf, const Fitted& fitted) const {
    if (options.engines.empty()) return;
    const Scene s = scene(fitted.law, options.omega_dt);
    std::vector<std::pair<std::string, std::vector<Poses>>> replayed = {{"ref", fitted.replays}};
    const TrajectoryModel ref = sf.models.front();
    for (const std::string& engine : options.engines) {
      const engines::EngineSpec spec = engines::parse_engine(engine, "--engines");
      say("fit: " + sf.split + " split, replaying " + std::to_string(sf.test.size()) +
          " held-out trajectories on " + engine);
      replayed.push_back({engine, replay_all(pb, sf.test, s.sim.dt,
                                             [&] { return engines::make_stepper(spec, s); })});
      TrajectoryModel m;
      m.name = "penalty";
      m.engine = engine;
      m.split = sf.split;
      m.parameters = ref.parameters;
      m.dt = ref.dt;
      m.errors = errors_of(pb, sf.test, replayed.back().second);
      summarise(m);
      sf.models.push_back(std::move(m));
    }
    for (size_t a = 0; a < replayed.size(); ++a) {
      for (size_t b = a + 1; b < replayed.size(); ++b) {
        std::vector<double> apart(sf.test.size());
        for (size_t j = 0; j < sf.test.size(); ++j)
          apart[j] = largest_error(pb.outline, replayed[b].second[j], replayed[a].second[j]).points;
        sf.engine_distances.push_back(
            {replayed[a].first, replayed[b].first, quartiles(apart).median});
      }
    }
  }
};

}  // namespace

Scene trajectory_replay_scene(const Recording& rec, const PenaltyParams& p, double omega_dt,
                              double window) {
  Scene s = penalty_scene(rec.body, p, min_effective_mass(make_body(rec.body)), omega_dt, window);
  const double frame = 1.0 / rec.frame_rate;
  s.sim.dt = frame / std::ceil(frame / s.sim.dt);
  s.sim.output_dt = s.sim.dt;
  return s;
}

TrajectoryFit fit_trajectories(const Recording& rec, const TrajectoryFitOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  if (rec.kind != "trajectories")
    throw InputError(rec.path + ": kind = \"" + rec.kind +
                     "\": fit_trajectories needs \"trajectories\"");
  if (rec.trajectories.size() < 4)
    throw InputError(rec.csv + ": " + std::to_string(rec.trajectories.size()) +
                     " trajectories to fit: at least 4 are needed (2 to train, 2 to test)");
  Fitter f{rec, options, {}, {}};
  f.out.recording = rec.path;
  f.out.peer = rec.peer_trajectories.empty() ? "" : (rec.peer.empty() ? "peer" : rec.peer);
  f.out.window = options.window;
  f.out.omega_dt = options.omega_dt;
  f.out.trajectories = rec.trajectories.size();
  f.prepare();
  // The peer's poses at the same samples, per trajectory.
  const std::vector<Poses> peer =
      rec.peer_trajectories.empty() ? std::vector<Poses>{} : match_peer(rec, f.pb.samples);

  // Chronological: by the trajectory's number (the recording's order of
  // filing; the square's gives no timestamps).
  std::vector<size_t> order(rec.trajectories.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&rec](size_t a, size_t b) { return rec.trajectories[a].id < rec.trajectories[b].id; });
  for (Halves& halves : fit_splits(options.seed, order)) {
    TrajectorySplit sf;
    sf.split = halves.split;
    sf.train = std::move(halves.train);
    sf.test = std::move(halves.test);
    const Fitter::Fitted fitted = f.fit_reference(sf);
    f.check_step(sf, fitted);
    f.replay_engines(sf, fitted);
    if (!peer.empty()) {  // the peer's replays, read from its file
      TrajectoryModel m;
      m.name = f.out.peer;
      m.engine = "peer";
      m.split = sf.split;
      for (const size_t i : sf.test)
        m.errors.push_back(largest_error(f.pb.outline, peer[i], f.pb.recorded[i]));
      summarise(m);
      sf.models.push_back(std::move(m));
    }
    f.out.splits.push_back(std::move(sf));
  }
  f.out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return f.out;
}

}  // namespace contact2d::analysis
