// Rebound of a point mass without gravity (g = 0, so the only force is the
// contact's and the exit velocity stays constant after separation).
// The mass starts touching at t = 0, moving down at v0, with d0 = 1e-12 m so
// that the first force evaluation already sees the contact: both laws jump
// from 0 to c·v0 at touchdown, and a step that straddled the jump would add
// an O((c/m)·Δt) error (measured: 3e-5·(ζ/0.1) when started at d0 = 0).
// d0 changes e by about ω·d0/v0 = 1e-10. ω = √(k/m), ζ = c/(2√(mk)),
// ω_d = ω·√(1−ζ²).
//
// Compression-only damping: damped oscillation until the deepest point
// (v = 0, reached at ω_d·t* = φ = atan(√(1−ζ²)/ζ), depth (v0/ω)·e^(−ζφ/√(1−ζ²))),
// then an undamped spring returns the stored energy:
//   e = v_out/v0 = exp(−ζ·φ/√(1−ζ²)).
// Kelvin–Voigt: x = (v0/ω_d)·e^(−ζωt)·sin(ω_d t) until the force k·x + c·x'
// reaches zero, at tan(ω_d·t_e) = −2ζ√(1−ζ²)/(1−2ζ²), i.e.
//   ω_d·t_e = π − atan2(2ζ√(1−ζ²), 1−2ζ²),
// where the point leaves the spring with
//   e = e^(−ζω·t_e)·|cos(ω_d t_e) − ζ/√(1−ζ²)·sin(ω_d t_e)|.
//
// Tolerance: RK4 at ω·Δt = 1e-3. Smooth parts err by O((ω·Δt)⁴) ≈ 1e-12; the
// damper's kink (at v = 0, or at Fn = 0 for Kelvin–Voigt) puts a jump of c/m
// in ∂a/∂v inside one step, an error of about (c/m)·|a|·Δt² in velocity, i.e.
// 2ζ·(ω·Δt)² = 2e-6·ζ relative to v0, which is the tolerance (measured:
// at most 3e-8 relative over the ζ below).
#include <gtest/gtest.h>

#include <cmath>

#include "benchmarks/impact.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

constexpr double kKinkError = 2e-6;  // 2·(ω·Δt)², per unit ζ

double simulated_restitution(DampingLaw law, double zeta) {
  Scene scene = test::impact_scene(Shape::PointMass, law, zeta);  // ω·Δt = 1e-3
  const double v0 = 1.0;
  scene.initial.q = Vec3(0.0, scene.half_height - 1e-12, 0.0);
  scene.initial.v = Vec3(0.0, -v0, 0.0);
  const Trajectory trajectory = simulate(scene);
  EXPECT_FALSE(trajectory.divergence);
  const State& end = trajectory.samples.back().state;
  EXPECT_GT(end.q.y(), scene.half_height) << "still in contact at the end";
  return end.v.y() / v0;
}

class Rebound : public ::testing::TestWithParam<double> {};

TEST_P(Rebound, CompressionLawMatchesClosedForm) {
  const double zeta = GetParam();
  const double expected = benchmarks::compression_restitution(zeta);
  const double e = simulated_restitution(DampingLaw::Compression, zeta);
  std::printf("compression  zeta=%.2f  e_sim=%.8f  e_closed=%.8f\n", zeta, e, expected);
  EXPECT_NEAR(e, expected, kKinkError * zeta * expected);
}

TEST_P(Rebound, KelvinVoigtLawMatchesClosedForm) {
  const double zeta = GetParam();
  const double expected = benchmarks::kelvin_voigt_restitution(zeta);
  const double e = simulated_restitution(DampingLaw::KelvinVoigt, zeta);
  std::printf("kelvin_voigt zeta=%.2f  e_sim=%.8f  e_closed=%.8f\n", zeta, e, expected);
  EXPECT_NEAR(e, expected, kKinkError * zeta * expected);
}

// ζ < 1/√2 keeps 1 − 2ζ² > 0 (the Kelvin–Voigt formula's branch) — the
// compression law has no such limit but is tested at the same ζ.
INSTANTIATE_TEST_SUITE_P(DampingRatios, Rebound, ::testing::Values(0.05, 0.1, 0.3, 0.6));

}  // namespace
}  // namespace contact2d
