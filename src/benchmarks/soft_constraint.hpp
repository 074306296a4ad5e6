// Closed forms of the soft-constraint (impedance) contact law, the law of a
// solver that regularises each contact row (MuJoCo's; docs/mujoco.md derives
// it). The functions take the solver's constants as numbers and know
// nothing of the solver; benchmarks/rest.hpp and benchmarks/slope.hpp hold
// the law's answers at rest and in creep.
//
// One row with the true inverse mass A (1/kg), the approximate one Â, the
// impedance d and the reference acceleration aref (m/s²) has the
// regulariser R = (1 − d)/d·Â; the solver's force f (N) on a row that stays
// active satisfies f = (aref − a)/R, where a = a0 + A·f is the row's
// acceleration with the force and a0 the one without it.
#pragma once

namespace contact2d::benchmarks {

// Solving f·R = aref − a0 − A·f for f and multiplying by d/d:
//   f = d·(aref − a0)/(d·A + (1 − d)·Â)   (N).
double soft_constraint_force(double inv_mass, double inv_weight, double impedance, double aref,
                             double a0);

// A frictional contact under an elliptic cone |f_t| ≤ μ·f_n, its normal row
// carrying the spring–damper k·p − c·v_n and its tangential row a damper
// with R_t = R/impratio, so unconstrained f_t⁰ = −impratio·c·v_t. Inside
// the cone (|f_t⁰| ≤ μ·f_n⁰) the rows act alone:
//   f_n = k·p − c·v_n,   f_t = −impratio·c·v_t;
// on it, the projection in the metric of R (weights 1 and 1/impratio)
// minimises (f_n − f_n⁰)² + (μ·f_n − |f_t⁰|)²/impratio over f_n:
//   f_n = (k·p − c·v_n + μ·c·|v_t|)/(1 + μ²/impratio),
//   f_t = −μ·f_n·sgn v_t.
// k in N/m, p the depth (m), c in N·s/m, speeds in m/s.
struct ConeForce {
  double normal = 0.0;      // f_n (N)
  double tangential = 0.0;  // f_t (N)
};
ConeForce elliptic_cone_force(double stiffness, double depth, double damping, double vn, double vt,
                              double mu, double impratio);

}  // namespace contact2d::benchmarks
