// Closed forms of a body sliding to rest on a flat floor (docs/closed-forms.md,
// section 3).
//
// A body launched along the floor at v0 (m/s) with friction coefficient μ
// under gravity g (m/s²), its weight carried by the floor (Fn = m·g on
// average). Coulomb's law and its tanh regularisation with slope α (s/m):
//   Coulomb   dv/dt = −μ·g·sgn(v)
//   tanh      dv/dt = −μ·g·tanh(α·v)
// The tanh law never stops: it slows exponentially at the rate μ·g·α once
// α·v ≪ 1, so its "time to rest" is the time to reach a small speed, and
// its distance to rest is finite.
//
// The same one-dimensional ODE, with another deceleration a in place of
// μ·g, governs the slip of a disc (benchmarks/rolling.hpp): the functions
// that only need the product take it as `deceleration` (m/s²).
#pragma once

namespace contact2d::benchmarks {

// Coulomb: uniform deceleration μ·g, so
//   s = v0²/(2μg) (m),   t = v0/(μg) (s).
// (v0 = 2 m/s, μ = 0.5, g = 9.81 m/s²: 0.4077 m in 0.4077 s.)
double coulomb_sliding_distance(double v0, double mu, double gravity);
double coulomb_sliding_time(double v0, double mu, double gravity);

// tanh: s = ∫₀^v0 v/(μg·tanh(αv)) dv = v0²/(2μg) + (π²/12 − ε)/(α²μg), with
// ε = α²·∫_v0^∞ 2v/(e^(2αv) − 1) dv < e^(−2αv0)·(2αv0 + 1) (3e-12 at
// α·v0 = 15). The excess over Coulomb's distance is
//   Δs = π²/(12α²μg)   (m)
// and the distance is Coulomb's plus Δs.
double tanh_sliding_distance_excess(double mu, double gravity, double alpha);
double tanh_sliding_distance(double v0, double mu, double gravity, double alpha);

// tanh, the speed: with a the deceleration (μ·g for a sliding body),
// d(sinh(αv))/dt = α·cosh(αv)·dv/dt = −a·α·sinh(αv), so
//   sinh(α·v(t)) = sinh(α·v0)·e^(−a·α·t),
// evaluated in logarithms (sinh(α·v0) overflows beyond α·v0 ≈ 710). v0 > 0.
double tanh_sliding_speed(double v0, double deceleration, double alpha, double t);
// The time at which the speed falls from v0 to v (0 < v < v0; α·v0 < 710):
//   t = ln(sinh(α·v0)/sinh(α·v))/(a·α)   (Coulomb: (v0 − v)/a).
double tanh_sliding_time(double v0, double v, double deceleration, double alpha);

// A flat box (width w, height h, m) sliding on its two bottom corners, each
// a spring of stiffness k (N/m), under the tanh law. Friction F = μ·m·g·tanh
// acts h/2 below the centre; the corners balance its torque by loading the
// front one and unloading the back one by ΔF = F·h/(2w), which pitches the
// box by θ = −β·tanh(α·v_c), β = μ·m·g·h/(k·w²) (quasi-static: the pitch
// mode is fast against the slide). In the tail, as tanh falls to 0, the box
// pitches back at ω = dθ/dt and the corners slip at v_c = v + ω·h/2: the
// extra friction shortens the slide by, to first order in β,
//   s_k = −(h·β/2)·∫₀^∞ u/(sinh u·cosh³u) du = −(h·β/2)·(π²/8 − ½)
//       = −m·μ·g·h²·(π²/8 − ½)/(2k·w²)   (m),
// independent of v0 and α (tests/core/test_friction.cpp derives it). The
// next term, the pitch's lag behind its quasi-static value, is of relative
// size ≲ (c/k)·μ·g·α.
double box_pitch_distance(double mass, double mu, double gravity, double width, double height,
                          double stiffness);

// The box's distance to rest, term by term: distance() = coulomb + tanh + pitch.
struct BoxSlide {
  double coulomb = 0.0;  // v0²/(2μg)
  double tanh = 0.0;     // π²/(12α²μg)
  double pitch = 0.0;    // s_k
  double distance() const { return coulomb + tanh + pitch; }
};
BoxSlide box_sliding_distance(double v0, double mu, double gravity, double alpha, double mass,
                              double width, double height, double stiffness);

}  // namespace contact2d::benchmarks
