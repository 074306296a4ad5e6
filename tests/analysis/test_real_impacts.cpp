// contact2d fit's parameter recovery: impacts made by the penalty law itself
// at known k, ζ, μ, μ_roll (a plain forward simulation here, from states
// just touching the ground) are fitted back by analysis::fit_impacts. The
// forward model is exact, so the held-out error at the generating
// parameters is 0 and the fit must find a point as good; ζ and μ_roll,
// which the real data determine to a few per cent, must come back close.
// Also: the metric and the quartiles on hand-made numbers.
#include <gtest/gtest.h>

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
  analysis::ImpactFitOptions options;
  options.bootstrap = 0;
  options.k_profile = false;
  options.threads = 1;
  const analysis::ImpactFit fit = analysis::fit_impacts(rec, options);
  ASSERT_EQ(fit.splits.size(), 2u);
  for (const analysis::SplitFit& split : fit.splits) {
    SCOPED_TRACE(split.split);
    const analysis::ModelFit& penalty = split.models.front();
    ASSERT_EQ(penalty.name, "penalty");
    auto parameter = [&penalty](const std::string& name) {
      for (const auto& [key, value] : penalty.parameters)
        if (key == name) return value;
      return std::nan("");
    };
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

}  // namespace
}  // namespace contact2d
