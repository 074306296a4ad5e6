// Closed forms of one impact on a linear spring–damper (docs/closed-forms.md,
// section 2).
//
// A body of mass m meets a contact of stiffness k (N/m) and damping c
// (N·s/m) at speed v0, without gravity or friction. With ω = √(k/m) (rad/s)
// and the damping ratio ζ = c/(2√(k·m)), time measured in units of 1/ω and
// the penetration x in units of v0/ω, every law below is the oscillator
//   x'' = −F(x, x'),   x(0) = 0, x'(0) = 1,
// while the force F is positive; the body leaves when F returns to zero,
// with the speed e (the restitution v_out/v0, independent of v0 and ω) at
// the time τ (ω·t_c, the contact time in units of 1/ω). The two laws:
//   compression-only damper   F = x + 2ζ·max(0, x')   (damped going in only)
//   Kelvin–Voigt, clamped     F = max(0, x + 2ζ·x')   (leaves when
//                                                      x + 2ζ·x' = 0, x > 0)
// and, for comparison, the unclamped dashpot F = x + 2ζ·x', which pulls
// the body back at the end and separates at x = 0.
#pragma once

namespace contact2d::benchmarks {

// Compression-only damper, 0 ≤ ζ < 1. Going in, x = e^(−ζt)·sin(ω_d·t)/ω_d
// (ω_d = √(1 − ζ²)) until x' = 0 at ω_d·t* = φ = atan(√(1 − ζ²)/ζ), depth
// x* = e^(−ζφ/ω_d) (sin φ = ω_d); the undamped spring then returns ½·x*²:
//   e = exp(−ζ·φ/√(1 − ζ²)).
// NaN outside [0, 1).
double compression_restitution(double zeta);
// Its contact time: the damped way in, φ/ω_d, then a quarter period of the
// undamped spring back from x*:
//   τ = φ/√(1 − ζ²) + π/2.
double compression_contact_time(double zeta);

// Kelvin–Voigt with the force clamped at zero, ζ ≥ 0. For ζ < 1,
// x = e^(−ζt)·sin(ω_d·t)/ω_d and the force x + 2ζ·x' first returns to zero
// at tan(ω_d·τ) = −2ζω_d/(1 − 2ζ²), i.e.
//   ω_d·τ = π − atan2(2ζ·ω_d, 1 − 2ζ²),
//   e = e^(−ζτ)·(ζ/ω_d·sin(ω_d·τ) − cos(ω_d·τ)).
// For ζ > 1, x = (e^(λ₁t) − e^(λ₂t))/(λ₁ − λ₂), λ = −ζ ± √(ζ² − 1), and the
// force 0 = (1 + 2ζλ₁)·e^(λ₁τ) − (1 + 2ζλ₂)·e^(λ₂τ) at
//   τ = ln((1 + 2ζλ₂)/(1 + 2ζλ₁))/(λ₁ − λ₂),
//   e = −(λ₁·e^(λ₁τ) − λ₂·e^(λ₂τ))/(λ₁ − λ₂).
// At ζ = 1 (critical), x = t·e^(−t): the force (2 − t)·e^(−t) returns to
// zero at τ = 2, and e = e^(−2) = 0.1353353 (x' = (1 − t)·e^(−t)). Near it
// both forms above tend to it, as e(1 + ε) = e^(−2)·(1 − 4ε/3) + O(ε²) and
// τ(1 + ε) = 2 − 2ε/3 + O(ε²) (first order in ε: ∂x/∂ζ solves
// y'' + 2y' + y = −2x', y = (t³/3 − t²)·e^(−t); tests/benchmarks checks it).
// The clamped law rebounds more than the dashpot: 0.744 against 0.729 at
// ζ = 0.1. NaN for ζ < 0 or NaN.
double kelvin_voigt_restitution(double zeta);
double kelvin_voigt_contact_time(double zeta);

// The unclamped dashpot, 0 ≤ ζ < 1 (the textbook coefficient): x = 0 again
// after half a damped period, ω_d·τ = π, so
//   e = exp(−ζπ/√(1 − ζ²)).
double dashpot_restitution(double zeta);

// The normal impulse of one impact, N·s: the body of mass m (kg) arrives
// at v_in (m/s) and leaves at e·v_in, so
//   P = m·(1 + e)·v_in.
double impact_normal_impulse(double mass, double restitution, double v_in);

}  // namespace contact2d::benchmarks
