// Convergence order on a smooth problem: a frictionless point mass held in
// contact by gravity (m = 1, k = 1e3, c = 0), displaced by A = 2 mm from its
// rest height y_eq = h − mg/k. The contact never opens (A < mg/k = 9.8 mm, and
// explicit Euler's growth (1+ω²Δt²)^(n/2) stays below 1.2 at these steps), so
// the motion is the linear oscillator
//   y(t) = y_eq + A·cos(ωt),  vy(t) = −A·ω·sin(ωt),  ω = √(k/m).
// The error is measured at t = 1 s in the phase-independent norm
//   e = √((y − y_exact)² + ((vy − vy_exact)/ω)²).
// For a method of order p, e(Δt) = C·Δt^p·(1 + δ). For explicit Euler δ is
// dominated by its amplitude growth exp(ω²·T·Δt/2) − 1, which bends the
// log–log line by about ω²·T·Δt/4 (0.25 at Δt = 1e-3, T = 1 s); the other
// methods have δ = O(ω·Δt). With Δt ≤ 1e-4 for the Euler methods (ω²·T·Δt/4
// ≤ 0.025) and ω·Δt ≤ 0.32 for RK4 the fitted slope departs from p by well
// under 0.1, which is the tolerance.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "analysis/sweep.hpp"
#include "benchmarks/oscillator.hpp"
#include "benchmarks/rest.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

double error_at_one_second(Integrator integrator, double dt) {
  Scene scene = default_scene(Shape::PointMass);
  scene.contact = ContactParams{};
  scene.contact.k = 1e3;
  scene.contact.c = 0.0;
  scene.contact.mu = 0.0;
  const Model model = make_model(scene);
  const double m = model.body.mass, k = model.contact.k, g = model.gravity;
  const double omega = std::sqrt(k / m);
  const double y_eq = scene.half_height - benchmarks::rest_depth(m, g, k, 1);
  const double amplitude = 2e-3;
  State s;
  s.q = Vec3(0.0, y_eq + amplitude, 0.0);
  const long long n = std::llround(1.0 / dt);
  s = test::advance(model, integrator, dt, s, n);
  const double t = dt * static_cast<double>(n);
  // The offset from y_eq, gravity taken up by the equilibrium.
  const benchmarks::OscillatorState exact =
      benchmarks::damped_oscillator(0.0, k / m, 0.0, amplitude, 0.0, t);
  const double dy = s.q.y() - (y_eq + exact.z);
  const double dv = s.v.y() - exact.w;
  return std::hypot(dy, dv / omega);
}

struct OrderCase {
  Integrator integrator;
  double order;
  std::vector<double> dts;
};

class ConvergenceOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(ConvergenceOrder, SlopeOfLogErrorMatchesNominalOrder) {
  const OrderCase& c = GetParam();
  std::vector<double> errors;
  for (double dt : c.dts) errors.push_back(error_at_one_second(c.integrator, dt));
  const double slope = analysis::log_log_slope(c.dts, errors);
  std::printf("observed order %s: %.4f\n", std::string(integrator_name(c.integrator)).c_str(),
              slope);
  EXPECT_NEAR(slope, c.order, 0.1) << integrator_name(c.integrator);
}

const std::vector<double> kEulerSteps = {1e-4, 5e-5, 2.5e-5, 1.25e-5};
INSTANTIATE_TEST_SUITE_P(
    Integrators, ConvergenceOrder,
    ::testing::Values(OrderCase{Integrator::ExplicitEuler, 1.0, kEulerSteps},
                      OrderCase{Integrator::SemiImplicitEuler, 1.0, kEulerSteps},
                      OrderCase{Integrator::ImplicitEuler, 1.0, kEulerSteps},
                      OrderCase{Integrator::RK4, 4.0, {1e-2, 5e-3, 2.5e-3, 1.25e-3}}),
    [](const auto& info) { return std::string(integrator_name(info.param.integrator)); });

}  // namespace
}  // namespace contact2d
