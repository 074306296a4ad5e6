#include "analysis/real_impacts.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "analysis/engine.hpp"
#include "analysis/fit_common.hpp"
#include "analysis/minimise.hpp"
#include "core/cancel.hpp"
#include "core/contacts.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "core/stepper.hpp"
#include "engines/engines.hpp"

namespace contact2d::analysis {

double impact_error(const Vec3& predicted, const Vec3& measured, double inertia, double mass) {
  const double w = std::sqrt(inertia / mass);
  const Vec3 d = predicted - measured;
  const double num = std::sqrt(d.x() * d.x() + d.y() * d.y() + w * w * d.z() * d.z());
  const double den = std::sqrt(measured.x() * measured.x() + measured.y() * measured.y() +
                               w * w * measured.z() * measured.z());
  return num / den;
}

Quartiles quartiles(std::vector<double> v) {
  Quartiles q;
  if (v.empty()) return q;
  std::sort(v.begin(), v.end());
  auto at = [&v](double p) {
    const double x = p * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(std::floor(x));
    const double f = x - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] + f * (v[i + 1] - v[i]) : v[i];
  };
  q.q1 = at(0.25);
  q.median = at(0.5);
  q.q3 = at(0.75);
  return q;
}

namespace {

constexpr double kTwoFrames = 2.0;  // frames a pre-impact state may be above its touch

// The longest contact a replay follows, in undamped half-periods
// π·√(m/k) of the candidate k. Without gravity a Kelvin–Voigt contact
// through a point whose effective mass along the normal is m_n ≤ m lasts
// τ(ζ)·√(m_n/k), and the clamped law's τ(ζ) (benchmarks/impact.hpp) falls
// from π at ζ = 0 to 2 at ζ = 1 and below beyond: the overdamped contact is
// the shorter one, so π·√(m/k) bounds every ζ. Gravity stretches an
// undamped contact to at most a full period (it oscillates about the rest
// depth m·g/k and leaves on the way up); damping can keep the body on the
// ground for good (it comes to rest), so no bound holds for every impact.
// Measured over every replay of the fits of the shipped ellipse impacts and
// of recordings made by the law itself (circles, a box, an ellipse, k =
// 1e3–1e5 N/m): the longest contact that ended took 3.0 half-periods (an
// ellipse rocking through it). Eight leaves more than twice that; a replay
// still touching then is a failed prediction (error 10, counted and said).
constexpr double kReplayHalfPeriods = 8.0;

double replay_window(const PenaltyParams& p, double mass) {
  constexpr double kPi = 3.14159265358979323846;
  return kReplayHalfPeriods * kPi * std::sqrt(mass / std::pow(10.0, p.log_k));
}

// The state at first touch: lifted along +y when it penetrates, carried
// along its free flight when it is above the ground.
struct ImpactTouch {
  State state;
  double lift = 0.0;    // m moved up (0 when it did not penetrate)
  double flight = 0.0;  // s of free flight to touch
};

ImpactTouch first_touch(const Model& model, const RecordedImpact& impact, double frame_rate,
                        const std::string& csv) {
  ContactSet contacts(model);
  ImpactTouch t;
  t.state = impact.before;
  const double g0 = ground_gap(model, t.state.q, contacts);
  if (g0 <= 0.0) {
    t.lift = -g0;
    t.state.q.y() += t.lift;
    return t;
  }
  // Free flight: q(τ) = q0 + v0·τ − ½·g·τ² ŷ; the first τ with gap ≤ 0, by
  // stepping through two frames and bisecting the bracket.
  const double g = model.gravity;
  auto at = [&](double tau) {
    State s = impact.before;
    s.q += tau * impact.before.v;
    s.q.y() -= 0.5 * g * tau * tau;
    s.v.y() -= g * tau;
    return s;
  };
  const double limit = kTwoFrames / frame_rate;
  const int n = 400;
  double prev = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double tau = limit * i / n;
    if (ground_gap(model, at(tau).q, contacts) <= 0.0) {
      double lo = prev, hi = tau;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (lo + hi);
        (ground_gap(model, at(mid).q, contacts) <= 0.0 ? hi : lo) = mid;
      }
      t.state = at(lo);
      t.flight = lo;
      return t;
    }
    prev = tau;
  }
  throw InputError(csv + ":" + std::to_string(impact.line) +
                   ": field 'y0' = " + format_number("%.6g", impact.before.q.y()) +
                   ": the body's lowest point is " + format_number("%.3g", g0) +
                   " m above the ground and does not touch it within two frames (" +
                   format_number("%.3g", limit) +
                   " s) of free flight: this is not the state just before an impact");
}

// How a replay ended: the body left the ground, a step was not finite, or
// it still touched the ground after `max_steps`.
enum class ReplayEnd { Left, Diverged, StillTouching };

// Predictions of one model on a set of impacts: v̂ per impact, NaN where
// the replay did not end with the body leaving the ground (then an error of
// 10, impact_errors), and how many did not, for each reason.
struct Replays {
  std::vector<Vec3> v;
  int diverged = 0, still_touching = 0;
  double window = 0.0;  // s: the longest contact followed
};

// Runs `stepper` from `start` until the body leaves the ground (the velocity
// then is `v`), for at most `max_steps`.
ReplayEnd replay_impact(Stepper& stepper, const Model& geometry, const State& start,
                        long long max_steps, ContactSet& contacts, Vec3& v) {
  throw_if_cancelled();  // Python's Ctrl-C (core/cancel.hpp): at every impact
  v = Vec3::Constant(NAN);
  stepper.reset(start);
  stepper.plan(max_steps);
  bool touched = false;
  for (long long n = 0; n < max_steps; ++n) {
    if (stepper.step() != StepStatus::Ok) return ReplayEnd::Diverged;
    const State& s = stepper.state();
    find_contacts(geometry, s.q, contacts);
    if (contacts.ground_count() > 0) {
      touched = true;
    } else if (touched) {
      v = s.v;
      return ReplayEnd::Left;
    }
  }
  return ReplayEnd::StillTouching;
}

// The impacts `which` replayed on steppers made by `make` (one per thread).
Replays replay_impacts(const std::function<std::unique_ptr<Stepper>()>& make, const Model& geometry,
                       const std::vector<ImpactTouch>& touches, const std::vector<size_t>& which,
                       long long max_steps, unsigned threads) {
  Replays out;
  out.v.resize(which.size());
  std::vector<ReplayEnd> ends(which.size(), ReplayEnd::Left);
  const unsigned chunks = std::max(1u, threads);
  parallel_for(chunks, chunks, [&](size_t c) {
    const std::unique_ptr<Stepper> stepper = make();
    ContactSet contacts(geometry);
    for (size_t i = c; i < which.size(); i += chunks)
      ends[i] =
          replay_impact(*stepper, geometry, touches[which[i]].state, max_steps, contacts, out.v[i]);
  });
  for (const ReplayEnd end : ends) {
    out.diverged += end == ReplayEnd::Diverged ? 1 : 0;
    out.still_touching += end == ReplayEnd::StillTouching ? 1 : 0;
  }
  return out;
}

struct ImpactProblem {
  const Scene* body = nullptr;
  const std::vector<ImpactTouch>* touches = nullptr;
  const std::vector<RecordedImpact>* impacts = nullptr;
  double m_eff = 0.0;
  unsigned threads = 1;
  double omega_dt = 0.02;  // ImpactFitOptions::omega_dt
};

// The penalty law at `p` as the replays run it: its window is
// replay_window's.
Scene replay_scene(const ImpactProblem& pb, const PenaltyParams& p) {
  return penalty_scene(*pb.body, p, pb.m_eff, pb.omega_dt, replay_window(p, pb.body->mass));
}

// Predictions of the penalty law on impacts `which`, on the reference.
Replays predict_impacts(const ImpactProblem& pb, const PenaltyParams& p,
                        const std::vector<size_t>& which) {
  const Scene scene = replay_scene(pb, p);
  const Model geometry = make_model(scene);
  Replays out = replay_impacts([&scene] { return std::make_unique<ReferenceStepper>(scene); },
                               geometry, *pb.touches, which, step_count(scene.sim), pb.threads);
  out.window = scene.sim.duration;
  return out;
}

std::vector<double> impact_errors(const std::vector<Vec3>& predicted,
                                  const std::vector<size_t>& which,
                                  const std::vector<RecordedImpact>& impacts, double inertia,
                                  double mass) {
  std::vector<double> e(which.size());
  for (size_t i = 0; i < which.size(); ++i) {
    const double v = impact_error(predicted[i], impacts[which[i]].after.v, inertia, mass);
    e[i] = std::isfinite(v) ? v : 10.0;  // a failed replay counts as far off
  }
  return e;
}

// ---------------------------------------------------------------- impulses

// One impulse P = (P_t, P_n) at lever r on the ground (n = +y, t = +x).
Vec3 apply_impulse(const State& s, const Vec2& r, double pt, double pn, double m, double inertia) {
  const double torque = r.x() * pn - r.y() * pt;
  return {s.v.x() + pt / m, s.v.y() + pn / m, s.v.z() + torque / inertia};
}

Vec2 lowest_lever(const Model& model, const State& s) {
  ContactSet contacts(model);
  State low = s;
  low.q.y() -= 1e-9;  // just into the ground: the touching point
  find_contacts(model, low.q, contacts);
  if (contacts.ground_count() == 0) return Vec2(0.0, -body_extent(model.body));
  return contacts.begin()->r();
}

// Newton's restitution e with Coulomb's bound μ on the tangential impulse.
Vec3 newton_coulomb(const State& s, const Vec2& r, double e, double mu, double m, double inertia) {
  const double vt = s.v.x() - s.v.z() * r.y();
  const double vn = s.v.y() + s.v.z() * r.x();
  if (vn >= 0.0) return s.v;  // separating: no impulse
  // Δv_c = K·P in (t, n): K = [1/m + ry²/I, −rx·ry/I; −rx·ry/I, 1/m + rx²/I].
  const double ktt = 1.0 / m + r.y() * r.y() / inertia;
  const double knn = 1.0 / m + r.x() * r.x() / inertia;
  const double ktn = -r.x() * r.y() / inertia;
  const double target_t = -vt, target_n = -(1.0 + e) * vn;
  const double det = ktt * knn - ktn * ktn;
  double pt = (knn * target_t - ktn * target_n) / det;
  double pn = (ktt * target_n - ktn * target_t) / det;
  if (std::abs(pt) > mu * pn) {  // slides: P_t = −sgn(v_t)·μ·P_n
    const double sgn = vt > 0.0 ? -1.0 : 1.0;
    pn = target_n / (knn + ktn * sgn * mu);
    pt = sgn * mu * pn;
  }
  return apply_impulse(s, r, pt, std::max(pn, 0.0), m, inertia);
}

// The impulse at r that minimises ‖W·(v⁺ − v)‖ with P_n ≥ 0 (linear least squares).
Vec3 best_impulse(const State& s, const Vec2& r, const Vec3& measured, double m, double inertia) {
  const double w = std::sqrt(inertia / m);
  // Columns: the change of W·v per unit P_t and per unit P_n.
  const Vec3 at(1.0 / m, 0.0, w * (-r.y()) / inertia);
  const Vec3 an(0.0, 1.0 / m, w * r.x() / inertia);
  const Vec3 b(measured.x() - s.v.x(), measured.y() - s.v.y(), w * (measured.z() - s.v.z()));
  const double a11 = at.dot(at), a12 = at.dot(an), a22 = an.dot(an);
  const double b1 = at.dot(b), b2 = an.dot(b);
  const double det = a11 * a22 - a12 * a12;
  double pt = (a22 * b1 - a12 * b2) / det;
  double pn = (a11 * b2 - a12 * b1) / det;
  if (pn < 0.0) {
    pn = 0.0;
    pt = b1 / a11;
  }
  return apply_impulse(s, r, pt, pn, m, inertia);
}

std::vector<double> impact_percentiles(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  auto at = [&v](double p) {
    const double x = p * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(std::floor(x));
    return i + 1 < v.size() ? v[i] + (x - static_cast<double>(i)) * (v[i + 1] - v[i]) : v[i];
  };
  return {at(0.16), at(0.84)};
}

}  // namespace

std::vector<std::string> default_fit_engines() {
  std::vector<std::string> out;
  for (const engines::EngineInfo* info : engines::engine_list())
    if (info->soft_constraints && info->make) out.emplace_back(info->kind);
  return out;
}

namespace {

// What every model of a fit reads: the impacts at first touch, their levers,
// the replay problem and the options.
struct ImpactFitter {
  const Recording& rec;
  const ImpactFitOptions& options;
  ImpactFit& out;
  Model geometry;
  double m = 0.0, inertia = 0.0;
  std::vector<ImpactTouch> touches;
  std::vector<Vec2> levers;
  ImpactProblem pb;

  void say(const std::string& line) const {
    if (options.progress) options.progress(line);
  }
  std::vector<double> errors(const std::vector<Vec3>& predicted,
                             const std::vector<size_t>& set) const {
    return impact_errors(predicted, set, out.impacts, inertia, m);
  }
  double train_median(const PenaltyParams& p, const std::vector<size_t>& set) const {
    return quartiles(errors(predict_impacts(pb, p, set).v, set)).median;
  }
  ModelFit model(const std::string& name, const std::string& engine, const SplitFit& sf,
                 std::vector<Vec3> predicted) const {
    ModelFit mf;
    mf.name = name;
    mf.engine = engine;
    mf.split = sf.split;
    mf.predicted = std::move(predicted);
    mf.errors = errors(mf.predicted, sf.test);
    for (const Vec3& p : mf.predicted) mf.failed_replays += p.allFinite() ? 0 : 1;
    const Quartiles q = quartiles(mf.errors);
    mf.q1 = q.q1;
    mf.median = q.median;
    mf.q3 = q.q3;
    return mf;
  }
  // A model replayed on an engine: its failed replays by reason.
  ModelFit model(const std::string& name, const std::string& engine, const SplitFit& sf,
                 Replays replays) const {
    ModelFit mf = model(name, engine, sf, std::move(replays.v));
    mf.failed_replays = replays.diverged;
    mf.unseparated_replays = replays.still_touching;
    mf.replay_window = replays.window;
    return mf;
  }
  std::vector<std::pair<std::string, double>> penalty_parameters(const PenaltyParams& p) const {
    const double k = std::pow(10.0, p.log_k);
    return {{"k", k},
            {"zeta", p.zeta},
            {"c", 2.0 * p.zeta * std::sqrt(k * m)},
            {"mu", p.mu},
            // A body without rolling resistance (a box) has none to fit:
            // its replays never read μ_roll (penalty_scene), so the search's
            // value there is wherever BOBYQA left a flat direction.
            {"mu_roll", shape_features(rec.body.shape).resists_rolling ? p.mu_roll : 0.0}};
  }
};

// The box of (log10 k, ζ, μ[, μ_roll]) and three starts (little, some and
// much friction and rolling resistance): the error surface has more than
// one valley; the best training fit wins.
struct ImpactSearch {
  std::vector<double> lo = {3.0, 0.0, 0.0}, hi = {9.0, 1.5, 2.0}, step = {0.5, 0.1, 0.1};
  std::vector<std::vector<double>> starts = {{5.0, 0.2, 0.05}, {5.0, 0.2, 0.4}, {7.0, 0.3, 0.0}};
  explicit ImpactSearch(bool rolling) {
    if (!rolling) return;
    lo.push_back(0.0);
    hi.push_back(0.03);
    step.push_back(0.001);
    starts[0].push_back(0.003);
    starts[1].push_back(0.01);
    starts[2].push_back(0.0);
  }
};

PenaltyParams params_of(const std::vector<double>& x) {
  return {x[0], x[1], x[2], x.size() > 3 ? x[3] : 0.0};
}

// The best point a fit has evaluated so far, and what it cost.
struct PenaltySearch {
  Minimised best;
  // Keeps `x` (its objective `f`) when it is better than the best so far.
  void offer(const std::vector<double>& x, double f) {
    if (best.x.empty() || f < best.f) {
      best.x = x;
      best.f = f;
    }
  }
  void add(const Minimised& m) {
    best.evaluations += m.evaluations;
    offer(m.x, m.f);
  }
};

// BOBYQA from `x0` (its objective `f0`) over the search's box; the better of
// the two is offered.
void descend(PenaltySearch& ps, const std::function<double(const std::vector<double>&)>& objective,
             const ImpactSearch& search, const std::vector<double>& x0, double f0) {
  ps.offer(x0, f0);
  ps.add(minimise(objective, x0, search.lo, search.hi, search.step, 300));
}

// The training median is flat in log10 k over decades, and the ζ that fits
// best moves with k: BOBYQA stops in that plateau far from a valley
// elsewhere (on recordings made by the law itself, up to 16 times above the
// best point of k's profile). A coarse grid of (log10 k, ζ) through the best
// point so far (μ and μ_roll held), 7 × 7 points; BOBYQA again from the
// grid's best when it is better.
void k_grid(PenaltySearch& ps, const std::function<double(const std::vector<double>&)>& objective,
            const ImpactSearch& search) {
  std::vector<double> at_best;
  double f_best = INFINITY;
  for (int lk = 3; lk <= 9; ++lk) {
    for (const double zeta : {0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 1.2}) {
      std::vector<double> x = ps.best.x;
      x[0] = lk;
      x[1] = zeta;
      const double f = objective(x);
      ++ps.best.evaluations;
      if (f < f_best) {
        f_best = f;
        at_best = x;
      }
    }
  }
  if (f_best < ps.best.f) descend(ps, objective, search, at_best, f_best);
}

// The penalty law fitted on the training half: BOBYQA from the search's
// starts and from `more` (each with its objective: points evaluated
// already, such as the fit without rolling resistance, μ_roll = 0), then
// along k's grid; the best point evaluated.
Minimised fit_penalty(const ImpactFitter& f, const SplitFit& sf, bool rolling,
                      const std::vector<std::pair<std::vector<double>, double>>& more) {
  const std::string name = rolling ? "penalty" : "penalty_no_rolling";
  f.say("fit: " + sf.split + " split, " + name + " on " + std::to_string(sf.train.size()) +
        " impacts (NLopt BOBYQA, " + std::to_string(3 + more.size()) +
        " starts and a grid of k and zeta)");
  const ImpactSearch search(rolling);
  auto objective = [&](const std::vector<double>& x) {
    return f.train_median(params_of(x), sf.train);
  };
  PenaltySearch ps;
  for (const std::vector<double>& x0 : search.starts)
    ps.add(minimise(objective, x0, search.lo, search.hi, search.step, 300));
  for (const auto& [x0, f0] : more) descend(ps, objective, search, x0, f0);
  k_grid(ps, objective, search);
  return ps.best;
}

// The fit at `best` measured on the held-out half.
ModelFit penalty_model(const ImpactFitter& f, const SplitFit& sf, bool rolling,
                       const Minimised& best) {
  const PenaltyParams p = params_of(best.x);
  ModelFit mf = f.model(rolling ? "penalty" : "penalty_no_rolling", "ref", sf,
                        predict_impacts(f.pb, p, sf.test));
  mf.train_median = best.f;
  mf.evaluations = best.evaluations;
  mf.parameters = f.penalty_parameters(p);
  return mf;
}

// Refits on training sets drawn with replacement, each from the fit with
// the search's full first step; the 16th–84th percentile of each parameter.
void bootstrap(const ImpactFitter& f, const SplitFit& sf, const Minimised& fit, ModelFit& mf) {
  if (f.options.bootstrap < 2) return;
  const ImpactSearch search(true);
  std::vector<std::vector<double>> draws(mf.parameters.size());
  std::uint64_t state = f.options.seed ^ 0xb007ull;
  for (int b = 0; b < f.options.bootstrap; ++b) {
    f.say("fit: " + sf.split + " split, bootstrap " + std::to_string(b + 1) + "/" +
          std::to_string(f.options.bootstrap));
    std::vector<size_t> resample(sf.train.size());
    const double n = static_cast<double>(sf.train.size());
    for (size_t& i : resample) i = sf.train[static_cast<size_t>(next_uniform(state) * n)];
    const Minimised refit = minimise(
        [&](const std::vector<double>& x) { return f.train_median(params_of(x), resample); }, fit.x,
        search.lo, search.hi, search.step, 150);
    const auto values = f.penalty_parameters(params_of(refit.x));
    for (size_t j = 0; j < values.size(); ++j) draws[j].push_back(values[j].second);
  }
  for (const std::vector<double>& d : draws) {
    const std::vector<double> p = impact_percentiles(d);
    mf.spread.emplace_back(p[0], p[1]);
  }
}

// The training median with log10 k held at 3, 4, …, 9 and ζ, μ, μ_roll
// refitted, each from the fit; the fit then moves to the profile's best
// point and BOBYQA runs from there when that point is the better one, so
// the fit is never worse than a point of its own profile.
void k_profile(const ImpactFitter& f, SplitFit& sf, Minimised& fit) {
  std::vector<double> at_best;
  double f_best = INFINITY;
  for (int lk = 3; lk <= 9; ++lk) {
    f.say("fit: k profile, k = 1e" + std::to_string(lk) + " N/m");
    const Minimised at = minimise(
        [&](const std::vector<double>& x) {
          return f.train_median({static_cast<double>(lk), x[0], x[1], x[2]}, sf.train);
        },
        {fit.x[1], fit.x[2], fit.x[3]}, {0.0, 0.0, 0.0}, {1.5, 2.0, 0.03}, {0.05, 0.05, 0.0005},
        120);
    sf.k_profile.emplace_back(std::pow(10.0, lk), at.f);
    if (at.f < f_best) {
      f_best = at.f;
      at_best = {static_cast<double>(lk), at.x[0], at.x[1], at.x[2]};
    }
  }
  if (!(f_best < fit.f)) return;
  f.say("fit: " + sf.split + " split, penalty again from k's profile at k = 1e" +
        format_number("%.0f", at_best[0]) + " N/m");
  PenaltySearch ps;
  ps.best = fit;
  descend(
      ps, [&](const std::vector<double>& x) { return f.train_median(params_of(x), sf.train); },
      ImpactSearch(true), at_best, f_best);
  fit = ps.best;
}

// The penalty fit replayed on every engine of the options, and the
// distances between every pair of them (the reference's first).
void replay_engines(const ImpactFitter& f, SplitFit& sf, const PenaltyParams& best) {
  if (f.options.engines.empty()) return;
  // The same scene, window included, as the reference's replays.
  const Scene scene = replay_scene(f.pb, best);
  const std::vector<std::pair<std::string, double>> parameters = sf.models[0].parameters;
  for (const std::string& engine : f.options.engines) {
    const engines::EngineSpec spec = engines::parse_engine(engine, "--engines");
    f.say("fit: " + sf.split + " split, replaying " + std::to_string(sf.test.size()) +
          " held-out impacts on " + engine);
    Replays replays = replay_impacts([&] { return engines::make_stepper(spec, scene); }, f.geometry,
                                     f.touches, sf.test, step_count(scene.sim), f.pb.threads);
    replays.window = scene.sim.duration;
    ModelFit mf = f.model("penalty", engine, sf, std::move(replays));
    mf.parameters = parameters;
    sf.models.push_back(std::move(mf));
  }
  std::vector<const ModelFit*> replayed = {&sf.models[0]};
  for (const ModelFit& mf : sf.models)
    if (mf.engine != "ref" && mf.engine != "baseline") replayed.push_back(&mf);
  for (size_t a = 0; a < replayed.size(); ++a) {
    for (size_t b = a + 1; b < replayed.size(); ++b) {
      std::vector<double> d(sf.test.size());
      for (size_t i = 0; i < sf.test.size(); ++i)
        d[i] = impact_error(replayed[b]->predicted[i], replayed[a]->predicted[i], f.inertia, f.m);
      sf.engine_distances.push_back(
          {replayed[a]->engine, replayed[b]->engine, quartiles(d).median});
    }
  }
}

// The constant predictor, Newton + Coulomb, and the best impulse after the fact.
void baselines(const ImpactFitter& f, SplitFit& sf) {
  Vec3 sum = Vec3::Zero();
  for (size_t i : sf.train) sum += f.out.impacts[i].after.v;
  const Vec3 mean = sum / static_cast<double>(sf.train.size());
  ModelFit constant = f.model("constant", "baseline", sf, std::vector<Vec3>(sf.test.size(), mean));
  constant.parameters = {{"vx", mean.x()}, {"vy", mean.y()}, {"omega", mean.z()}};
  sf.models.push_back(std::move(constant));

  f.say("fit: " + sf.split + " split, Newton restitution with Coulomb friction");
  auto predict = [&f](double e, double mu, const std::vector<size_t>& set) {
    std::vector<Vec3> p(set.size());
    for (size_t i = 0; i < set.size(); ++i)
      p[i] = newton_coulomb(f.touches[set[i]].state, f.levers[set[i]], e, mu, f.m, f.inertia);
    return p;
  };
  const Minimised fit = minimise(
      [&](const std::vector<double>& x) {
        return quartiles(f.errors(predict(x[0], x[1], sf.train), sf.train)).median;
      },
      {0.5, 0.3}, {0.0, 0.0}, {1.0, 2.0}, {0.1, 0.1}, 400);
  ModelFit newton = f.model("newton_coulomb", "baseline", sf, predict(fit.x[0], fit.x[1], sf.test));
  newton.train_median = fit.f;
  newton.evaluations = fit.evaluations;
  newton.parameters = {{"restitution", fit.x[0]}, {"mu", fit.x[1]}};
  sf.models.push_back(std::move(newton));

  std::vector<Vec3> bound(sf.test.size());
  for (size_t j = 0; j < sf.test.size(); ++j) {
    const size_t i = sf.test[j];
    bound[j] =
        best_impulse(f.touches[i].state, f.levers[i], f.out.impacts[i].after.v, f.m, f.inertia);
  }
  sf.models.push_back(f.model("irb_bound", "baseline", sf, std::move(bound)));
}

// SplitFit::spin_slope and spin_intercept over the held-out impacts.
void spin_regression(const ImpactFitter& f, SplitFit& sf) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i : sf.test) {
    const RecordedImpact& impact = f.out.impacts[i];
    const Vec3 dv = impact.after.v - impact.before.v;
    const Vec2& r = f.levers[i];
    const double point = f.m * (r.x() * dv.y() - r.y() * dv.x()) / f.inertia;
    sx += point;
    sy += dv.z();
    sxx += point * point;
    sxy += point * dv.z();
  }
  const double n = static_cast<double>(sf.test.size());
  sf.spin_slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  sf.spin_intercept = (sy - sf.spin_slope * sx) / n;
}

// The seeded and the chronological halves of n impacts.
std::vector<SplitFit> splits_of(size_t n, std::uint64_t seed) {
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::vector<SplitFit> out;
  for (Halves& h : fit_splits(seed, order)) {
    out.emplace_back();
    out.back().split = h.split;
    out.back().train = std::move(h.train);
    out.back().test = std::move(h.test);
  }
  return out;
}

}  // namespace

ImpactFit fit_impacts(const Recording& rec, const ImpactFitOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  if (rec.kind != "impacts")
    throw InputError(rec.path + ": kind = \"" + rec.kind + "\": fit_impacts needs \"impacts\"");
  ImpactFit out;
  out.recording = rec.path;
  for (const RecordedImpact& impact : rec.impacts) {
    if (impact.flags.find('1') != std::string::npos && !options.all_impacts) {
      ++out.flagged_left_out;
      continue;
    }
    out.impacts.push_back(impact);
  }
  // In drop order, whatever the rows' order: the chronological split is by
  // drop number (as the trajectories' is by trajectory number), and the
  // seeded one is then the file's rows' order's too.
  std::stable_sort(out.impacts.begin(), out.impacts.end(),
                   [](const RecordedImpact& a, const RecordedImpact& b) { return a.id < b.id; });
  if (out.impacts.size() < 4)
    throw InputError(rec.csv + ": " + std::to_string(out.impacts.size()) +
                     " impacts to fit: at least 4 are needed (2 to train, 2 to test)" +
                     (out.flagged_left_out > 0
                          ? "; " + std::to_string(out.flagged_left_out) +
                                " flagged ones were left out (--all-impacts keeps them)"
                          : std::string()));
  ImpactFitter f{rec, options, out, make_model(rec.body), 0.0, 0.0, {}, {}, {}};
  f.m = f.geometry.body.mass;
  f.inertia = f.geometry.body.inertia;
  if (!(f.inertia > 0.0))
    throw InputError(rec.path + ": body.shape = \"" + std::string(shape_name(rec.body.shape)) +
                     "\": fit needs a body that turns (an inertia about its centre)");
  out.mass = f.m;
  out.inertia = f.inertia;
  std::vector<double> lifts;
  f.touches.reserve(out.impacts.size());
  f.levers.reserve(out.impacts.size());
  for (const RecordedImpact& impact : out.impacts) {
    f.touches.push_back(first_touch(f.geometry, impact, rec.frame_rate, rec.csv));
    if (f.touches.back().lift > 0.0) lifts.push_back(f.touches.back().lift);
    f.levers.push_back(lowest_lever(f.geometry, f.touches.back().state));
  }
  out.lifted = static_cast<int>(lifts.size());
  out.median_lift = quartiles(lifts).median;
  f.pb = {&rec.body,
          &f.touches,
          &out.impacts,
          min_effective_mass(f.geometry.body),
          options.threads == 0 ? default_threads() : options.threads,
          options.omega_dt};
  if (!(options.omega_dt > 0.0 && options.omega_dt <= 0.5))
    throw InputError("omega_dt = " + format_number("%g", options.omega_dt) +
                     ": the replays' omega*dt must be in (0, 0.5]");

  for (SplitFit& sf : splits_of(out.impacts.size(), options.seed)) {
    // Without rolling resistance first: its optimum (μ_roll = 0) is a point
    // of the full fit's box, where the full fit starts too, so the full fit
    // is never worse than its own special case.
    const Minimised no_rolling = fit_penalty(f, sf, false, {});
    std::vector<double> x0 = no_rolling.x;
    x0.push_back(0.0);
    Minimised best = fit_penalty(f, sf, true, {{x0, no_rolling.f}});
    if (options.k_profile) k_profile(f, sf, best);
    sf.models.push_back(penalty_model(f, sf, true, best));
    bootstrap(f, sf, best, sf.models.back());
    sf.models.push_back(penalty_model(f, sf, false, no_rolling));
    replay_engines(f, sf, params_of(best.x));
    baselines(f, sf);
    spin_regression(f, sf);
    out.splits.push_back(std::move(sf));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace contact2d::analysis
