// Free fall without contact: every integrator against y0 + vy0·t − g·t²/2.
//
// With constant acceleration the methods' errors are known exactly:
//   explicit Euler       y_n = y0 + vy0·t − g·Δt²·n(n−1)/2  → error +g·Δt·t/2
//   semi-implicit Euler  y_n = y0 + vy0·t − g·Δt²·n(n+1)/2  → error −g·Δt·t/2
//   implicit Euler       the same as semi-implicit for a constant force
//   RK4                  exact (a quadratic is integrated without error)
// Velocities are exact for all four. What remains is rounding: n = 1000 steps
// of values ≈ 100 m accumulate at most n·ulp(100) ≈ 1.4e-11 m, so 1e-10 m is
// the tolerance.
#include <gtest/gtest.h>

#include "benchmarks/oscillator.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

constexpr double kRounding = 1e-10;

class FreeFall : public ::testing::TestWithParam<Integrator> {};

TEST_P(FreeFall, MatchesTheIntegratorsKnownError) {
  const Integrator integrator = GetParam();
  Scene scene = default_scene(Shape::Box);
  scene.initial.q = Vec3(0.3, 100.0, 0.2);  // far above the ground: no contact in 1 s
  scene.initial.v = Vec3(1.5, 2.0, 0.7);
  const Model model = make_model(scene);
  const double g = model.gravity;
  const double dt = 1e-3;
  const long long n = 1000;
  const double t = dt * static_cast<double>(n);

  const State s = test::advance(model, integrator, dt, scene.initial, n);

  const benchmarks::OscillatorState exact =
      benchmarks::damped_oscillator(g, 0.0, 0.0, 100.0, 2.0, t);
  const double exact_y = exact.z;
  double expected_offset = 0.0;
  if (integrator == Integrator::ExplicitEuler) expected_offset = +0.5 * g * dt * t;
  if (integrator == Integrator::SemiImplicitEuler || integrator == Integrator::ImplicitEuler) {
    expected_offset = -0.5 * g * dt * t;
  }
  EXPECT_NEAR(s.q.y() - exact_y, expected_offset, kRounding);
  EXPECT_NEAR(s.v.y(), exact.w, kRounding);
  EXPECT_NEAR(s.q.x(), 0.3 + 1.5 * t, kRounding);
  EXPECT_NEAR(s.q.z(), 0.2 + 0.7 * t, kRounding);
  EXPECT_NEAR(s.v.z(), 0.7, kRounding);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, FreeFall, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(integrator_name(info.param)); });

}  // namespace
}  // namespace contact2d
