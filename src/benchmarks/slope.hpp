// Closed forms of a block on a slope (docs/closed-forms.md, section 6).
//
// A block of mass m on a plane inclined at θ (rad), resting on N contact
// points that share its velocity, friction coefficient μ, gravity g (m/s²).
// Along the slope (s pointing down it, v = ds/dt) and across it:
//   m·dv/dt = m·g·sinθ − μ·Fn·law(v),   Fn = m·g·cosθ in all.
// Coulomb (law = sgn) slides when tanθ > μ and holds otherwise; the tanh
// law (law = tanh(α·v)) cannot hold: below tanθ = μ it creeps at a steady
// speed. A viscous law (each contact's tangential force b·v) creeps too.
#pragma once

namespace contact2d::benchmarks {

// The depth of each of the N points, springs of stiffness k (N/m) carrying
// the normal load m·g·cosθ:
//   N·k·d = m·g·cosθ.
double slope_rest_depth(double mass, double gravity, double theta, double stiffness, int contacts);

// Sliding (tanθ > μ, v > 0, Coulomb or tanh with α·v ≫ 1):
//   a = g·(sinθ − μ·cosθ)   (m/s²; θ = 30°, μ = 0.3: 2.356 m/s²).
double slope_sliding_acceleration(double gravity, double theta, double mu);

// Creep under the tanh law (tanθ < μ): steady when μ·m·g·cosθ·tanh(α·v) =
// m·g·sinθ, so
//   v = atanh(tanθ/μ)/α   (m/s; Coulomb: 0),
// reached at the rate μ·g·α·cosθ·(1 − (tanθ/μ)²).
double tanh_creep_speed(double theta, double mu, double alpha);

// Creep of a soft-constraint solver's viscous friction (MuJoCo's inside its
// elliptic cone, docs/mujoco.md): each tangential row has no spring,
// aref_t = −B·v, and R_t = R/impratio with R = (1 − d)/d·Â and B = c·Â/(n·d)
// (c in N·s/m, n rows per point). At steady creep J·qacc = 0, so each row
// carries f = aref_t/R_t = impratio·c·v/(n·(1 − d)), and N points balance the
// weight along the slope:
//   v = (1 − d)·m·g·sinθ/(N·impratio·c)   (m/s).
double soft_constraint_creep_speed(double mass, double gravity, double theta, int contacts,
                                   double impratio, double damping, double impedance);

}  // namespace contact2d::benchmarks
