// Closed forms of a body on one linear spring–damper under gravity, and of
// its flight: the phases of a point mass bouncing on a penalty contact (the
// rebound of benchmarks/impact.hpp, docs/closed-forms.md section 2, is the
// same oscillator without gravity).
//
// The height z (m) of the contact point above the ground, w = dz/dt (m/s),
// gravity g (m/s²); in contact the spring k and the damper c act per unit
// mass (k/m in 1/s², c/m in 1/s):
//   flight   (k = 0, c = 0)   z'' = −g,
//   contact                   z'' = −g − k·z − c·z'.
// Flight: z = z0 + w0·s − g·s²/2, w = w0 − g·s after the time s.
// Contact, underdamped (c² < 4k): about the equilibrium z_eq = −g/k the
// offset u = z − z_eq obeys u'' + c·u' + k·u = 0. With β = c/2 and
// ω_d = √(k − β²), the solution with u(0) = u0, u'(0) = w0 is
//   u = e^(−βs)·(u0·cos(ω_d·s) + (w0 + β·u0)/ω_d·sin(ω_d·s)),
//   w = e^(−βs)·(w0·cos(ω_d·s) − (k·u0 + β·w0)/ω_d·sin(ω_d·s))
// (differentiate u: the cos terms give −β·u0 + w0 + β·u0 = w0, the sin
// terms −β·(w0 + β·u0)/ω_d − u0·ω_d = −(k·u0 + β·w0)/ω_d, as k = β² + ω_d²).
#pragma once

namespace contact2d::benchmarks {

struct OscillatorState {
  double z = 0.0;  // height (m)
  double w = 0.0;  // velocity (m/s)
};

// The state after the time s (s), from (z0, w0): flight when k = 0 and
// c = 0, the underdamped oscillator when c² < 4k, NaN otherwise.
OscillatorState damped_oscillator(double gravity, double stiffness, double damping, double z0,
                                  double w0, double s);

// Flight from the height z ≥ 0 at the velocity w down to z = 0: the
// positive root of z + w·s − g·s²/2 = 0,
//   s = (w + √(w² + 2g·z))/g   (s).
double fall_time(double gravity, double z, double w);

// The deepest point of a body of mass m (kg) dropped from rest at the height
// H (m) above an undamped spring of stiffness k (N/m): the energy
// ½·k·d² = m·g·(H + d) at the turning point gives
//   d = (m·g + √((m·g)² + 2k·m·g·H))/k   (m),
// an upper bound on the depth when a damper takes energy away.
double drop_depth(double mass, double gravity, double stiffness, double height);

// The height z (m) at the time t (s) of a point dropped from rest at the
// apex z0 > 0 onto an undamped spring (k per unit mass, 1/s²) under gravity,
// bouncing for ever: flight for t1 = √(2·z0/g) down to z = 0 at
// v1 = −g·t1; in contact, about z_eq = −g/k with ω = √k,
//   z − z_eq = A·cos ωτ + B·sin ωτ,  A = g/k,  B = v1/ω,
// = R·cos(ωτ − φ) with φ = atan2(B, A) ∈ (−π/2, 0): back at z = 0 when
// ωτ_c = 2π + 2φ, with −v1; then the rising flight z = −v1·s − g·s²/2.
// No energy is lost, so the motion repeats with the period 2·t1 + τ_c.
double bouncing_height(double gravity, double stiffness, double z0, double t);

}  // namespace contact2d::benchmarks
