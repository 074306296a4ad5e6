// Energy behaviour with c = 0 and μ = 0 over 1e5 steps.
//
// A point mass (m = 1, k = 1e3, ω = 31.6 rad/s) oscillating about its rest
// height with amplitude 2 mm stays in contact (mg/k = 9.8 mm), so the motion
// is a linear oscillator and energy() − energy(rest) = ½m·v² + ½k·(y − y_eq)²
// is its oscillation energy E_osc. With Δt = 1e-4, ω·Δt = 3.16e-3, n = 1e5:
//   semi-implicit Euler conserves H̃ = ½v² + ½ω²x² − ½·Δt·ω²·x·v exactly
//     (per unit mass). |½Δt·ω²·x·v| ≤ (ω·Δt/2)·E_osc, and H̃ = E_osc(0) for a
//     start at rest (v = 0), so |E_osc/E_osc(0) − 1| ≤ (ω·Δt/2)/(1 − ω·Δt/2)
//     = 1.58e-3 at all times, and the last tenth of the run strays no further
//     than the first (no drift);
//   explicit Euler multiplies E_osc by exactly (1 + ω²Δt²) every step:
//     E_osc(n)/E_osc(0) = (1 + 1e-5)^(1e5) = 2.71827; rounding over 1e5 steps
//     is ~1e-11 relative, tolerance 1e-6.
#include <gtest/gtest.h>

#include <algorithm>

#include "support/support.hpp"

namespace contact2d {
namespace {

struct Oscillator {
  Model model;
  State start;
  State rest;
};

Oscillator conservative_oscillator() {
  Scene scene = default_scene(Shape::PointMass);
  scene.contact.k = 1e3;
  scene.contact.c = 0.0;
  scene.contact.mu = 0.0;
  Oscillator o{make_model(scene), {}, {}};
  const double y_eq = scene.half_height - scene.mass * scene.sim.gravity / scene.contact.k;
  o.rest.q = Vec3(0.0, y_eq, 0.0);
  o.start.q = Vec3(0.0, y_eq + 2e-3, 0.0);
  return o;
}

constexpr double kDt = 1e-4;
constexpr long long kSteps = 100000;

TEST(Energy, SemiImplicitEulerErrorStaysBounded) {
  const Oscillator o = conservative_oscillator();
  const double e_rest = energy(o.model, o.rest);
  const double e0 = energy(o.model, o.start) - e_rest;
  const double omega_dt = std::sqrt(o.model.contact.k / o.model.body.mass) * kDt;
  double first_tenth = 0.0, last_tenth = 0.0;
  State s = o.start;
  StepWorkspace ws(o.model);
  find_contacts(o.model, s.q, ws.contacts);
  for (long long i = 1; i <= kSteps; ++i) {
    step(o.model, Integrator::SemiImplicitEuler, kDt, s, ws);
    const double rel = std::abs((energy(o.model, s) - e_rest) / e0 - 1.0);
    (i <= kSteps / 10 ? first_tenth : last_tenth) =
        std::max(i <= kSteps / 10 ? first_tenth : last_tenth, rel);
  }
  std::printf("semi-implicit Euler: max |dE/E| first tenth %.3g, last tenth %.3g, bound %.3g\n",
              first_tenth, last_tenth, (omega_dt / 2.0) / (1.0 - omega_dt / 2.0) + 1e-12);
  EXPECT_LE(std::max(first_tenth, last_tenth), (omega_dt / 2.0) / (1.0 - omega_dt / 2.0) + 1e-12);
  // No drift: the band of the last tenth is the band of the first (within
  // 1 %, the sampling of the oscillation's extremes).
  EXPECT_LE(last_tenth, 1.01 * first_tenth);
}

TEST(Energy, ExplicitEulerGrowsByOnePlusOmegaDtSquaredPerStep) {
  const Oscillator o = conservative_oscillator();
  const double e_rest = energy(o.model, o.rest);
  const double e0 = energy(o.model, o.start) - e_rest;
  const double omega_dt = std::sqrt(o.model.contact.k / o.model.body.mass) * kDt;
  const State s = test::advance(o.model, Integrator::ExplicitEuler, kDt, o.start, kSteps);
  const double growth = (energy(o.model, s) - e_rest) / e0;
  const double expected = std::pow(1.0 + omega_dt * omega_dt, static_cast<double>(kSteps));
  std::printf("explicit Euler: energy x%.6f after 1e5 steps, expected x%.6f\n", growth, expected);
  EXPECT_NEAR(growth, expected, 1e-6 * expected);
}

}  // namespace
}  // namespace contact2d
