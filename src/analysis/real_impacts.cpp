#include "analysis/real_impacts.hpp"

#include <nlopt.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "analysis/engine.hpp"
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
  const double den =
      std::sqrt(measured.x() * measured.x() + measured.y() * measured.y() +
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

constexpr double kOmegaDt = 0.01;      // ω·Δt of the replays
constexpr double kWindow = 0.08;       // s: the longest contact a replay follows
constexpr double kTwoFrames = 2.0;     // frames a pre-impact state may be above its touch

// Height of the body's lowest point above the ground (negative: it penetrates).
double gap(const Model& model, const Vec3& q, ContactSet& contacts) {
  find_contacts(model, q, contacts);
  if (contacts.ground_count() > 0) return -contacts.begin()->depth;
  // Above the ground: lift the body's lowest point by probing how far down
  // it can go — for a smooth or a one-point body that is exact.
  Vec3 low = q;
  double lo = 0.0, hi = std::max(1.0, q.y() + 1.0);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, hi); ++i) {
    const double mid = 0.5 * (lo + hi);
    low.y() = q.y() - mid;
    find_contacts(model, low, contacts);
    (contacts.ground_count() > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The state at first touch: lifted along +y when it penetrates, carried
// along its free flight when it is above the ground.
struct Touch {
  State state;
  double lift = 0.0;    // m moved up (0 when it did not penetrate)
  double flight = 0.0;  // s of free flight to touch
};

Touch first_touch(const Model& model, const RecordedImpact& impact, double frame_rate,
                  const std::string& csv) {
  ContactSet contacts(model);
  Touch t;
  t.state = impact.before;
  const double g0 = gap(model, t.state.q, contacts);
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
    if (gap(model, at(tau).q, contacts) <= 0.0) {
      double lo = prev, hi = tau;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (lo + hi);
        (gap(model, at(mid).q, contacts) <= 0.0 ? hi : lo) = mid;
      }
      t.state = at(lo);
      t.flight = lo;
      return t;
    }
    prev = tau;
  }
  throw InputError(csv + ":" + std::to_string(impact.line) + ": field 'y0' = " +
                   format_number("%.6g", impact.before.q.y()) +
                   ": the body's lowest point is " + format_number("%.3g", g0) +
                   " m above the ground and does not touch it within two frames (" +
                   format_number("%.3g", limit) +
                   " s) of free flight: this is not the state just before an impact");
}

struct PenaltyParams {
  double log_k = 5.0, zeta = 0.3, mu = 0.3, mu_roll = 0.0;
};

Scene penalty_scene(const Scene& body, const PenaltyParams& p, double m_eff) {
  Scene s = body;
  s.contact.k = std::pow(10.0, p.log_k);
  s.contact.c = 2.0 * p.zeta * std::sqrt(s.contact.k * body.mass);
  s.contact.mu = p.mu;
  s.contact.mu_roll = p.mu_roll;
  s.contact.damping = DampingLaw::KelvinVoigt;
  s.sim.integrator = Integrator::SemiImplicitEuler;
  s.sim.dt = kOmegaDt / std::sqrt(s.contact.k / m_eff);
  s.sim.duration = kWindow;
  s.sim.output_dt = s.sim.dt;
  s.obstacles.clear();
  return s;
}

// Runs `stepper` from `start` until the body leaves the ground; the velocity then.
Vec3 replay(Stepper& stepper, const Model& geometry, const State& start, long long max_steps,
            ContactSet& contacts) {
  stepper.reset(start);
  stepper.plan(max_steps);
  bool touched = false;
  for (long long n = 0; n < max_steps; ++n) {
    if (stepper.step() != StepStatus::Ok) return Vec3::Constant(NAN);
    const State& s = stepper.state();
    find_contacts(geometry, s.q, contacts);
    if (contacts.ground_count() > 0) {
      touched = true;
    } else if (touched) {
      return s.v;
    }
  }
  return stepper.state().v;
}

struct Problem {
  const Scene* body = nullptr;
  const std::vector<Touch>* touches = nullptr;
  const std::vector<RecordedImpact>* impacts = nullptr;
  double m_eff = 0.0;
  unsigned threads = 1;
};

// Predictions of the penalty law on impacts `which`, on the reference.
std::vector<Vec3> predict_ref(const Problem& pb, const PenaltyParams& p,
                              const std::vector<size_t>& which) {
  const Scene scene = penalty_scene(*pb.body, p, pb.m_eff);
  const long long steps = step_count(scene.sim);
  std::vector<Vec3> out(which.size());
  const unsigned chunks = std::max(1u, pb.threads);
  parallel_for(chunks, chunks, [&](size_t c) {
    ReferenceStepper stepper(scene);
    ContactSet contacts(stepper.model());
    for (size_t i = c; i < which.size(); i += chunks)
      out[i] = replay(stepper, stepper.model(), (*pb.touches)[which[i]].state, steps, contacts);
  });
  return out;
}

std::vector<double> errors_of(const std::vector<Vec3>& predicted, const std::vector<size_t>& which,
                              const std::vector<RecordedImpact>& impacts, double inertia,
                              double mass) {
  std::vector<double> e(which.size());
  for (size_t i = 0; i < which.size(); ++i) {
    const double v = impact_error(predicted[i], impacts[which[i]].after.v, inertia, mass);
    e[i] = std::isfinite(v) ? v : 10.0;  // a failed replay counts as far off
  }
  return e;
}

// NLopt's BOBYQA on f over the box [lo, hi] from x; returns evaluations.
struct Minimised {
  std::vector<double> x;
  double f = 0.0;
  int evaluations = 0;
};

Minimised minimise(const std::function<double(const std::vector<double>&)>& f,
                   std::vector<double> x, const std::vector<double>& lo,
                   const std::vector<double>& hi, const std::vector<double>& step, int max_eval) {
  struct Data {
    const std::function<double(const std::vector<double>&)>* f;
    int evaluations;
  } data{&f, 0};
  const unsigned n = static_cast<unsigned>(x.size());
  nlopt_opt opt = nlopt_create(NLOPT_LN_BOBYQA, n);
  nlopt_set_lower_bounds(opt, lo.data());
  nlopt_set_upper_bounds(opt, hi.data());
  nlopt_set_initial_step(opt, step.data());
  nlopt_set_xtol_rel(opt, 1e-4);
  nlopt_set_ftol_abs(opt, 1e-6);
  nlopt_set_maxeval(opt, max_eval);
  nlopt_set_min_objective(
      opt,
      [](unsigned dim, const double* xs, double*, void* d) {
        auto* data = static_cast<Data*>(d);
        ++data->evaluations;
        return (*data->f)(std::vector<double>(xs, xs + dim));
      },
      &data);
  double value = 0.0;
  const nlopt_result result = nlopt_optimize(opt, x.data(), &value);
  nlopt_destroy(opt);
  if (result < 0 && result != NLOPT_ROUNDOFF_LIMITED)
    throw std::runtime_error("fit: NLopt's BOBYQA failed (code " + std::to_string(result) + ")");
  return {x, value, data.evaluations};
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

void set_quartiles(ModelFit& fit) {
  const Quartiles q = quartiles(fit.errors);
  fit.q1 = q.q1;
  fit.median = q.median;
  fit.q3 = q.q3;
}

std::vector<double> percentiles(std::vector<double> v) {
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

ImpactFit fit_impacts(const Recording& rec, const ImpactFitOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  if (rec.kind != "impacts")
    throw InputError(rec.path + ": kind = \"" + rec.kind + "\": fit_impacts needs \"impacts\"");
  auto say = [&options](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  ImpactFit out;
  out.recording = rec.path;
  for (const RecordedImpact& impact : rec.impacts) {
    const bool flagged = impact.flags.find('1') != std::string::npos;
    if (flagged && !options.all_impacts) {
      ++out.flagged_left_out;
      continue;
    }
    out.impacts.push_back(impact);
  }
  if (out.impacts.size() < 4)
    throw InputError(rec.csv + ": " + std::to_string(out.impacts.size()) +
                     " impacts to fit: at least 4 are needed (2 to train, 2 to test)");
  const Model geometry = make_model(rec.body);
  const double m = geometry.body.mass;
  const double inertia = geometry.body.inertia;
  if (!(inertia > 0.0))
    throw InputError(rec.path + ": body.shape = \"" + std::string(shape_name(rec.body.shape)) +
                     "\": fit needs a body that turns (an inertia about its centre)");
  out.mass = m;
  out.inertia = inertia;
  std::vector<Touch> touches;
  std::vector<double> lifts;
  for (const RecordedImpact& impact : out.impacts) {
    touches.push_back(first_touch(geometry, impact, rec.frame_rate, rec.csv));
    if (touches.back().lift > 0.0) lifts.push_back(touches.back().lift);
  }
  out.lifted = static_cast<int>(lifts.size());
  out.median_lift = quartiles(lifts).median;
  std::vector<Vec2> levers;
  for (const Touch& t : touches) levers.push_back(lowest_lever(geometry, t.state));

  Problem pb;
  pb.body = &rec.body;
  pb.touches = &touches;
  pb.impacts = &out.impacts;
  pb.m_eff = min_effective_mass(geometry.body);
  pb.threads = options.threads == 0 ? default_threads() : options.threads;

  const size_t n = out.impacts.size();
  std::vector<size_t> shuffled(n);
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::uint64_t state = options.seed;
  for (size_t i = n - 1; i > 0; --i)
    std::swap(shuffled[i], shuffled[static_cast<size_t>(next_uniform(state) * (i + 1))]);
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);

  for (const std::string split : {"seeded", "chronological"}) {
    SplitFit sf;
    sf.split = split;
    const std::vector<size_t>& all = split == "seeded" ? shuffled : order;
    sf.train.assign(all.begin(), all.begin() + static_cast<long>(n / 2));
    sf.test.assign(all.begin() + static_cast<long>(n / 2), all.end());
    if (split == "seeded") std::sort(sf.test.begin(), sf.test.end());
    auto objective_on = [&](const std::vector<size_t>& set) {
      return [&pb, &set, &out, inertia, m](const PenaltyParams& p) {
        return quartiles(errors_of(predict_ref(pb, p, set), set, out.impacts, inertia, m)).median;
      };
    };
    // Penalty models: with and without rolling resistance.
    PenaltyParams best;
    for (const bool rolling : {true, false}) {
      const std::string name = rolling ? "penalty" : "penalty_no_rolling";
      say("fit: " + split + " split, " + name + " on " + std::to_string(sf.train.size()) +
          " impacts (NLopt BOBYQA)");
      const auto objective = objective_on(sf.train);
      auto f = [&](const std::vector<double>& x) {
        return objective({x[0], x[1], x[2], rolling ? x[3] : 0.0});
      };
      // Three starts (little, some and much friction and rolling
      // resistance): the error surface has more than one valley; the best
      // training fit wins.
      std::vector<double> lo = {3.0, 0.0, 0.0}, hi = {9.0, 1.5, 2.0}, step = {0.5, 0.1, 0.1};
      std::vector<std::vector<double>> starts = {{5.0, 0.2, 0.05}, {5.0, 0.2, 0.4}, {7.0, 0.3, 0.0}};
      if (rolling) {
        lo.push_back(0.0);
        hi.push_back(0.03);
        step.push_back(0.001);
        starts[0].push_back(0.003);
        starts[1].push_back(0.01);
        starts[2].push_back(0.0);
      }
      Minimised fit;
      fit.f = INFINITY;
      for (const std::vector<double>& x0 : starts) {
        const Minimised tried = minimise(f, x0, lo, hi, step, 300);
        fit.evaluations += tried.evaluations;
        if (tried.f < fit.f) {
          fit.x = tried.x;
          fit.f = tried.f;
        }
      }
      const PenaltyParams p{fit.x[0], fit.x[1], fit.x[2], rolling ? fit.x[3] : 0.0};
      ModelFit mf;
      mf.name = name;
      mf.engine = "ref";
      mf.split = split;
      mf.train_median = fit.f;
      mf.evaluations = fit.evaluations;
      const double k = std::pow(10.0, p.log_k);
      mf.parameters = {{"k", k},
                       {"zeta", p.zeta},
                       {"c", 2.0 * p.zeta * std::sqrt(k * m)},
                       {"mu", p.mu},
                       {"mu_roll", p.mu_roll}};
      mf.predicted = predict_ref(pb, p, sf.test);
      mf.errors = errors_of(mf.predicted, sf.test, out.impacts, inertia, m);
      set_quartiles(mf);
      if (rolling) {
        best = p;
        // Bootstrap: refits on training sets drawn with replacement.
        std::vector<std::vector<double>> draws(5);
        std::uint64_t boot = options.seed ^ 0xb007ull;
        for (int b = 0; b < options.bootstrap; ++b) {
          say("fit: " + split + " split, bootstrap " + std::to_string(b + 1) + "/" +
              std::to_string(options.bootstrap));
          std::vector<size_t> resample(sf.train.size());
          for (size_t& i : resample)
            i = sf.train[static_cast<size_t>(next_uniform(boot) * sf.train.size())];
          const auto obj = objective_on(resample);
          const Minimised refit = minimise(
              [&](const std::vector<double>& x) { return obj({x[0], x[1], x[2], x[3]}); },
              fit.x, lo, hi, {0.2, 0.05, 0.05, 0.0005}, 150);
          const double kb = std::pow(10.0, refit.x[0]);
          draws[0].push_back(kb);
          draws[1].push_back(refit.x[1]);
          draws[2].push_back(2.0 * refit.x[1] * std::sqrt(kb * m));
          draws[3].push_back(refit.x[2]);
          draws[4].push_back(refit.x[3]);
        }
        if (options.bootstrap > 1) {
          for (const std::vector<double>& d : draws) {
            const std::vector<double> p16 = percentiles(d);
            mf.spread.push_back({p16[0], p16[1]});
          }
        }
        // k's profile (seeded split only): ζ, μ, μ_roll refitted at each k.
        if (split == "seeded") {
          for (double lk = 3.0; lk <= 9.0 + 1e-9; lk += 1.0) {
            say("fit: k profile, k = 1e" + std::to_string(static_cast<int>(lk)) + " N/m");
            const Minimised at = minimise(
                [&](const std::vector<double>& x) { return objective({lk, x[0], x[1], x[2]}); },
                {fit.x[1], fit.x[2], fit.x[3]}, {0.0, 0.0, 0.0}, {1.5, 2.0, 0.03},
                {0.05, 0.05, 0.0005}, 120);
            sf.k_profile.push_back({std::pow(10.0, lk), at.f});
          }
        }
      }
      sf.models.push_back(std::move(mf));
    }
    // The other engines with the penalty fit (through their default mapping).
    if (!options.engines.empty()) {
      const Scene scene = penalty_scene(rec.body, best, pb.m_eff);
      const long long steps = step_count(scene.sim);
      for (const std::string& engine : options.engines) {
        const engines::EngineSpec spec = engines::parse_engine(engine, "--engines");
        say("fit: " + split + " split, replaying " + std::to_string(sf.test.size()) +
            " held-out impacts on " + engine);
        ModelFit mf;
        mf.name = "penalty";
        mf.engine = engine;
        mf.split = split;
        mf.parameters = sf.models[0].parameters;
        mf.predicted.resize(sf.test.size());
        parallel_for(pb.threads, pb.threads, [&](size_t c) {
          std::unique_ptr<Stepper> stepper = engines::make_stepper(spec, scene);
          ContactSet contacts(geometry);
          for (size_t i = c; i < sf.test.size(); i += pb.threads)
            mf.predicted[i] = replay(*stepper, geometry, touches[sf.test[i]].state, steps, contacts);
        });
        mf.errors = errors_of(mf.predicted, sf.test, out.impacts, inertia, m);
        set_quartiles(mf);
        sf.models.push_back(std::move(mf));
      }
      // Every pair among the reference's penalty fit and the engines.
      std::vector<const ModelFit*> replayed = {&sf.models[0]};
      for (const ModelFit& mf : sf.models)
        if (mf.engine != "ref" && mf.engine != "baseline") replayed.push_back(&mf);
      for (size_t a = 0; a < replayed.size(); ++a) {
        for (size_t b = a + 1; b < replayed.size(); ++b) {
          std::vector<double> d;
          for (size_t i = 0; i < sf.test.size(); ++i)
            d.push_back(impact_error(replayed[b]->predicted[i], replayed[a]->predicted[i], inertia,
                                     m));
          sf.engine_distances.push_back(
              {replayed[a]->engine, replayed[b]->engine, quartiles(d).median});
        }
      }
    }
    // Baselines.
    {
      ModelFit mf;
      mf.name = "constant";
      mf.engine = "baseline";
      mf.split = split;
      Vec3 sum = Vec3::Zero();
      for (size_t i : sf.train) sum += out.impacts[i].after.v;
      const Vec3 v = sum / static_cast<double>(sf.train.size());
      mf.parameters = {{"vx", v.x()}, {"vy", v.y()}, {"omega", v.z()}};
      mf.predicted.assign(sf.test.size(), v);
      mf.errors = errors_of(mf.predicted, sf.test, out.impacts, inertia, m);
      set_quartiles(mf);
      sf.models.push_back(std::move(mf));
    }
    {
      say("fit: " + split + " split, Newton restitution with Coulomb friction");
      auto predict = [&](double e, double mu, const std::vector<size_t>& set) {
        std::vector<Vec3> p;
        for (size_t i : set) p.push_back(newton_coulomb(touches[i].state, levers[i], e, mu, m, inertia));
        return p;
      };
      const Minimised fit = minimise(
          [&](const std::vector<double>& x) {
            return quartiles(errors_of(predict(x[0], x[1], sf.train), sf.train, out.impacts,
                                       inertia, m))
                .median;
          },
          {0.5, 0.3}, {0.0, 0.0}, {1.0, 2.0}, {0.1, 0.1}, 400);
      ModelFit mf;
      mf.name = "newton_coulomb";
      mf.engine = "baseline";
      mf.split = split;
      mf.train_median = fit.f;
      mf.evaluations = fit.evaluations;
      mf.parameters = {{"restitution", fit.x[0]}, {"mu", fit.x[1]}};
      mf.predicted = predict(fit.x[0], fit.x[1], sf.test);
      mf.errors = errors_of(mf.predicted, sf.test, out.impacts, inertia, m);
      set_quartiles(mf);
      sf.models.push_back(std::move(mf));
    }
    {
      ModelFit mf;
      mf.name = "irb_bound";
      mf.engine = "baseline";
      mf.split = split;
      for (size_t i : sf.test)
        mf.predicted.push_back(
            best_impulse(touches[i].state, levers[i], out.impacts[i].after.v, m, inertia));
      mf.errors = errors_of(mf.predicted, sf.test, out.impacts, inertia, m);
      set_quartiles(mf);
      sf.models.push_back(std::move(mf));
    }
    out.splits.push_back(std::move(sf));
  }
  out.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace contact2d::analysis
