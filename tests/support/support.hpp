// Shared fixtures of the test suites: scenes built in code, stepping without
// the run loop, and running the real program, in one header every suite
// includes. It holds no closed forms: each closed form a test compares
// against is a function of src/benchmarks/ (library contact2d_benchmarks).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "core/integrators.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"

namespace contact2d::test {

constexpr double kPi = 3.14159265358979323846;

// A critically damped Kelvin–Voigt contact (ζ = 1 for the body's mass),
// k = 1e4 N/m, Δt = 1e-4 s, 2 s: the body settles within a few 1/ω = 10 ms.
inline Scene resting_scene(Shape shape, Integrator integrator) {
  Scene scene = default_scene(shape);
  scene.contact.k = 1e4;
  scene.contact.c = 2.0 * std::sqrt(scene.contact.k * scene.mass);
  scene.contact.damping = DampingLaw::KelvinVoigt;
  scene.sim.integrator = integrator;
  scene.sim.duration = 2.0;
  scene.sim.dt = 1e-4;
  return scene;
}

// One impact on a linear spring–damper without gravity or friction:
// m = 1 kg, k = 1e4 N/m, c = ζ·2√(m·k), RK4 at Δt = 1e-5 s (ω·Δt = 1e-3),
// 0.05 s (the contact lasts < π/ω_d ≈ 0.04 s for ζ ≤ 0.7).
inline Scene impact_scene(Shape shape, DampingLaw law, double zeta) {
  Scene scene = default_scene(shape);
  scene.mass = 1.0;
  scene.contact.k = 1e4;
  scene.contact.c = zeta * 2.0 * std::sqrt(scene.mass * scene.contact.k);
  scene.contact.mu = 0.0;
  scene.contact.damping = law;
  scene.sim.gravity = 0.0;
  scene.sim.integrator = Integrator::RK4;
  scene.sim.dt = 1e-5;
  scene.sim.duration = 0.05;
  return scene;
}

// The last sample of the reference run (which must not diverge).
inline State final_state(const Scene& scene) {
  const Trajectory trajectory = simulate(scene);
  EXPECT_FALSE(trajectory.divergence);
  return trajectory.samples.back().state;
}

// Steps a model n times from s with the core's step() (no divergence rule,
// so a test can watch an unstable method grow).
inline State advance(const Model& model, Integrator integrator, double dt, State s, long long n) {
  StepWorkspace ws(model);
  find_contacts(model, s.q, ws.contacts);
  for (long long i = 0; i < n; ++i) step(model, integrator, dt, s, ws);
  return s;
}

}  // namespace contact2d::test
