// contact2d fit's parameter recovery: impacts made by the penalty law itself
// at known k, ζ, μ, μ_roll (a plain forward simulation here, from states
// just touching the ground) are fitted back by analysis::fit_impacts. The
// forward model is exact, so the held-out error at the generating
// parameters is 0 and the fit must find a point as good; ζ and μ_roll,
// which the real data determine to a few per cent, must come back close.
// Also: a contact longer than the replays once followed, from a closed
// form; the fit never worse than points it evaluated itself; the metric and
// the quartiles on hand-made numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/real_impacts.hpp"
#include "core/contacts.hpp"
#include "core/ellipse.hpp"
#include "core/rng.hpp"
#include "core/stepper.hpp"

namespace contact2d {
namespace {

TEST(ImpactMetric, WeighsTheSpinByTheRadiusOfGyration) {
  // I/m = 4 m²: W = diag(1, 1, 2). measured (3, 0, 2) → |W v| = √(9 + 16) = 5;
  // predicted (3, 4, 2) differs by (0, 4, 0) → error 4/5.
  EXPECT_DOUBLE_EQ(analysis::impact_error({3, 4, 2}, {3, 0, 2}, 4.0, 1.0), 0.8);
  // A spin error of 1 rad/s counts as 2 m/s.
  EXPECT_DOUBLE_EQ(analysis::impact_error({3, 0, 3}, {3, 0, 2}, 4.0, 1.0), 0.4);
}

TEST(ImpactMetric, QuartilesInterpolateBetweenOrderStatistics) {
  const analysis::Quartiles q = analysis::quartiles({4, 1, 3, 2, 5});
  EXPECT_DOUBLE_EQ(q.q1, 2.0);
  EXPECT_DOUBLE_EQ(q.median, 3.0);
  EXPECT_DOUBLE_EQ(q.q3, 4.0);
  EXPECT_DOUBLE_EQ(analysis::quartiles({1, 2}).median, 1.5);
}

// A fitted model's parameter `name` (NaN when it has none).
double parameter_of(const analysis::ModelFit& fit, const std::string& name) {
  for (const auto& [key, value] : fit.parameters)
    if (key == name) return value;
  return std::nan("");
}

// The fit without bootstrap or k's profile, on one thread: the tests' own.
analysis::ImpactFit quick_fit(const Recording& rec) {
  analysis::ImpactFitOptions options;
  options.bootstrap = 0;
  options.k_profile = false;
  options.threads = 1;
  return analysis::fit_impacts(rec, options);
}

// The real ellipse's body, and impacts from the penalty law at `law`.
Recording synthetic(const ContactParams& law, int n) {
  Recording rec;
  rec.path = rec.csv = "synthetic";
  rec.kind = "impacts";
  rec.frame_rate = 250.0;
  rec.body = default_scene(Shape::Ellipse);
  rec.body.a = 0.035;
  rec.body.b = 0.025;
  rec.body.mass = 0.0364;
  rec.body.inertia = 1.6835e-5;
  Scene scene = rec.body;
  scene.contact = law;
  const Model model = make_model(scene);
  // The fit's step: its ω·Δt with ω = √(k/m_eff).
  scene.sim.dt =
      analysis::ImpactFitOptions{}.omega_dt / std::sqrt(law.k / min_effective_mass(model.body));
  std::uint64_t seed = 7;
  ContactSet contacts(model);
  for (int i = 0; i < n; ++i) {
    RecordedImpact impact;
    impact.id = i;
    impact.line = i + 2;
    const double theta = 6.283185307179586 * next_uniform(seed);
    const Vec2 r = ellipse_lowest_point(scene.a, scene.b, theta);
    impact.before.q = Vec3(0.0, -r.y(), theta);  // just touching
    impact.before.v = Vec3(next_uniform(seed) - 0.5, -2.4 - 0.5 * next_uniform(seed),
                           20.0 * next_uniform(seed) - 10.0);
    ReferenceStepper stepper(scene);
    stepper.reset(impact.before);
    bool touched = false;
    for (int s = 0; s < 1000000; ++s) {
      stepper.step();
      find_contacts(model, stepper.state().q, contacts);
      if (contacts.ground_count() > 0) {
        touched = true;
      } else if (touched) {
        break;
      }
    }
    impact.after = stepper.state();
    rec.impacts.push_back(impact);
  }
  return rec;
}

TEST(ImpactFit, RecoversTheParametersOfImpactsMadeByItsOwnLaw) {
  ContactParams law;
  law.damping = DampingLaw::KelvinVoigt;
  law.k = 1e5;
  const double zeta = 0.25;
  law.c = 2.0 * zeta * std::sqrt(law.k * 0.0364);
  law.mu = 0.2;
  law.mu_roll = 0.003;
  const Recording rec = synthetic(law, 24);
  const analysis::ImpactFit fit = quick_fit(rec);
  ASSERT_EQ(fit.splits.size(), 2u);
  for (const analysis::SplitFit& split : fit.splits) {
    SCOPED_TRACE(split.split);
    const analysis::ModelFit& penalty = split.models.front();
    ASSERT_EQ(penalty.name, "penalty");
    auto parameter = [&penalty](const std::string& name) { return parameter_of(penalty, name); };
    // Measured (24 impacts, 12 held out, ω·Δt = 0.02): held-out medians
    // 0.0045 (seeded) and 0.0076 (chronological) — BOBYQA stops at a relative step of 1e-4 in a
    // valley that is flat in k (k is not checked: any k above ~1e5 fits alike, as on the real
    // impacts); ζ and μ_roll within 1 %. μ is bounded from below only: in an impact whose slip
    // stops before it ends, any μ large enough to stop it gives the same impulse (measured: 0.36
    // and 0.34 for the 0.2 that made the data at this step, 0.22 at ω·Δt = 0.01), while too small a
    // μ leaves the slip too fast. Bounds: a median of 0.02, ζ within 5 %, μ_roll within 15 %, μ at
    // least 80 % of the true one; far from what a wrong law gives (the baselines: 0.21–0.39).
    EXPECT_LT(penalty.median, 0.02);
    EXPECT_NEAR(parameter("zeta"), zeta, 0.05 * zeta);
    EXPECT_NEAR(parameter("mu_roll"), law.mu_roll, 0.15 * law.mu_roll);
    EXPECT_GT(parameter("mu"), 0.8 * law.mu);
    // The baselines cannot reproduce a penalty contact: far above.
    for (const analysis::ModelFit& m : split.models) {
      if (m.engine == "baseline") {
        EXPECT_GT(m.median, 10 * penalty.median) << m.name;
      }
    }
  }
}

// A 10 kg disc dropped vertically on a Kelvin–Voigt spring–damper, k = 1e4
// N/m, ζ = 0.2, no friction, under gravity: d'' = g − (k·d + c·d')/m while
// the force k·d + c·d' is positive, d(0) = 0, d'(0) = v (d the depth). With
// ω = √(k/m), ω_d = ω·√(1 − ζ²) and d0 = m·g/k,
//   d(t) = d0 + e^(−ζωt)·(−d0·cos ω_d·t + (v − ζω·d0)/ω_d·sin ω_d·t);
// the force first returns to zero at t_s (found here by stepping 1e-6 s and
// bisecting), and the disc then rises freely from depth d(t_s) at −d'(t_s):
// it leaves the ground at √(d'(t_s)² − 2g·d(t_s)). Without gravity the
// contact lasts τ(ζ)/ω = 0.084 s (benchmarks/impact.hpp), with it longer:
// over 0.08 s, the fixed window the replays once followed (they then
// returned the velocity in mid-contact, and the fit came back with ζ = 0.27
// and 0.29, k = 6e4 and 1.1e5 N/m on these impacts).
// `contact`: set to the contact's duration t_s.
double disc_rebound_speed(double k, double zeta, double m, double g, double v, double* contact) {
  const double w = std::sqrt(k / m), wd = w * std::sqrt(1.0 - zeta * zeta), d0 = m * g / k;
  const double b = (v - zeta * w * d0) / wd;
  auto depth = [&](double t) {
    return d0 + std::exp(-zeta * w * t) * (-d0 * std::cos(wd * t) + b * std::sin(wd * t));
  };
  auto rate = [&](double t) {
    const double e = std::exp(-zeta * w * t), c = std::cos(wd * t), s = std::sin(wd * t);
    return e * (-zeta * w * (-d0 * c + b * s) + wd * (d0 * s + b * c));
  };
  auto force = [&](double t) { return k * depth(t) + 2.0 * zeta * std::sqrt(k * m) * rate(t); };
  double lo = 1e-6, hi = lo;
  while (force(hi) > 0.0) {
    lo = hi;
    hi += 1e-6;
  }
  for (int i = 0; i < 60; ++i) ((force(0.5 * (lo + hi)) > 0.0) ? lo : hi) = 0.5 * (lo + hi);
  *contact = lo;
  const double up = -rate(lo), d = depth(lo);
  return std::sqrt(up * up - 2.0 * g * d);
}

TEST(ImpactFit, FollowsAContactLongerThanTheOldWindowToItsEnd) {
  const double k = 1e4, zeta = 0.2, m = 10.0, g = 9.81, radius = 0.05;
  Recording rec;
  rec.path = rec.csv = "synthetic";
  rec.kind = "impacts";
  rec.frame_rate = 250.0;
  rec.body = default_scene(Shape::Circle);
  rec.body.radius = radius;
  rec.body.mass = m;
  rec.body.sim.gravity = g;
  for (int i = 0; i < 12; ++i) {
    const double v = 1.0 + 0.2 * i;  // 1 to 3.2 m/s: gravity's share g/(ω·v) varies
    RecordedImpact impact;
    impact.id = i;
    impact.line = i + 2;
    impact.before.q = Vec3(0.0, radius, 0.0);
    impact.before.v = Vec3(0.0, -v, 0.0);
    impact.after.q = impact.before.q;
    double contact = 0.0;
    impact.after.v = Vec3(0.0, disc_rebound_speed(k, zeta, m, g, v, &contact), 0.0);
    EXPECT_GT(contact, 0.08) << "the contact must outlast the old window";
    rec.impacts.push_back(impact);
  }
  const analysis::ImpactFit fit = quick_fit(rec);
  for (const analysis::SplitFit& split : fit.splits) {
    SCOPED_TRACE(split.split);
    const analysis::ModelFit& penalty = split.models.front();
    ASSERT_EQ(penalty.name, "penalty");
    auto parameter = [&penalty](const std::string& name) { return parameter_of(penalty, name); };
    // Semi-implicit Euler at ω·Δt = 0.02 is off the restitution by at most
    // 0.16·ω·Δt = 0.3 % relative (tests/core/test_ellipse.cpp), and the
    // replay stops at the first step above the ground (g·Δt = 6e-5 m/s):
    // the true law replays these impacts to about 0.003. Measured: held-out
    // medians 0.0031 (seeded) and 0.0029 (chronological); ζ 0.2028 and
    // 0.2007, k 1.029e4 and 1.004e4 N/m. Bounds: a median of 0.01, ζ within
    // 5 %, k within 20 % (gravity's share of the rebound, 10–30 % here, is
    // what sets k).
    EXPECT_LT(penalty.median, 0.01);
    EXPECT_NEAR(parameter("zeta"), zeta, 0.05 * zeta);
    EXPECT_NEAR(parameter("k"), k, 0.2 * k);
    EXPECT_EQ(penalty.unseparated_replays, 0);
    EXPECT_EQ(penalty.failed_replays, 0);
  }
}

// A box has no rolling resistance: its replays never read μ_roll (the
// scene refuses one), so the "penalty" fit's μ_roll was wherever BOBYQA left
// a flat direction (its starts hold 0.003 and 0.01) and was reported as
// fitted. Now 0. The impacts: a 1 kg box (0.4 × 0.2 m) dropped flat, both
// bottom corners landing together, each a Kelvin–Voigt contact of k and
// c = 2ζ·√(k·m) as the fit writes them; together one oscillator of 2k and
// 2c, ζ_total = √2·ζ, whose rebound is disc_rebound_speed's (the same
// closed form: nothing turns). Bounds as in the disc's test above.
TEST(ImpactFit, ABoxHasNoRollingResistanceToFit) {
  const double k = 1e4, zeta = 0.2, m = 1.0, g = 9.81;
  Recording rec;
  rec.path = rec.csv = "synthetic";
  rec.kind = "impacts";
  rec.frame_rate = 250.0;
  rec.body = default_scene(Shape::Box);
  rec.body.mass = m;
  rec.body.sim.gravity = g;
  for (int i = 0; i < 12; ++i) {
    const double v = 1.0 + 0.2 * i;
    RecordedImpact impact;
    impact.id = i;
    impact.line = i + 2;
    impact.before.q = Vec3(0.0, 0.5 * rec.body.height, 0.0);
    impact.before.v = Vec3(0.0, -v, 0.0);
    impact.after.q = impact.before.q;
    double contact = 0.0;
    impact.after.v =
        Vec3(0.0, disc_rebound_speed(2.0 * k, std::sqrt(2.0) * zeta, m, g, v, &contact), 0.0);
    rec.impacts.push_back(impact);
  }
  const analysis::ImpactFit fit = quick_fit(rec);
  for (const analysis::SplitFit& split : fit.splits) {
    SCOPED_TRACE(split.split);
    const analysis::ModelFit& penalty = split.models.front();
    ASSERT_EQ(penalty.name, "penalty");
    auto parameter = [&penalty](const std::string& name) { return parameter_of(penalty, name); };
    EXPECT_EQ(parameter("mu_roll"), 0.0);
    EXPECT_LT(penalty.median, 0.01);
    EXPECT_NEAR(parameter("zeta"), zeta, 0.05 * zeta);
  }
}

// The fit is never worse, on its own objective (the training median), than
// a point it evaluated itself: its special case without rolling resistance
// (μ_roll = 0 is inside its box) and every point of k's profile. On these
// impacts (the real ellipse's body, k = 1e5 N/m, ζ = 0.3, μ = 0.05, μ_roll =
// 0.002) BOBYQA from the three fixed starts stopped in the plateau of high
// k: a training median of 0.0035 against 0.00027 at k's profile point 1e5
// N/m (seeded split); now 0.00014 on both splits.
TEST(ImpactFit, IsNoWorseThanItsSpecialCaseOrItsOwnProfileOfK) {
  ContactParams law;
  law.damping = DampingLaw::KelvinVoigt;
  law.k = 1e5;
  law.c = 2.0 * 0.3 * std::sqrt(law.k * 0.0364);
  law.mu = 0.05;
  law.mu_roll = 0.002;
  const Recording rec = synthetic(law, 24);
  analysis::ImpactFitOptions options;
  options.bootstrap = 0;
  options.threads = 1;
  const analysis::ImpactFit fit = analysis::fit_impacts(rec, options);
  for (const analysis::SplitFit& split : fit.splits) {
    SCOPED_TRACE(split.split);
    const analysis::ModelFit& penalty = split.models.at(0);
    const analysis::ModelFit& no_rolling = split.models.at(1);
    ASSERT_EQ(penalty.name, "penalty");
    ASSERT_EQ(no_rolling.name, "penalty_no_rolling");
    // The same objective at the same points: no tolerance.
    EXPECT_LE(penalty.train_median, no_rolling.train_median);
    ASSERT_FALSE(split.k_profile.empty());
    for (const auto& [k, median] : split.k_profile) {
      EXPECT_LE(penalty.train_median, median) << "k = " << k;
    }
  }
}

}  // namespace
}  // namespace contact2d
