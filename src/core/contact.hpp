// Penalty contact law for one point against the ground y = 0 (docs/physics.md).
//
//   d  = max(0, −c_y)                                   penetration
//   Fn = k·d + c·max(0, −v_y)                           compression (the scene files' default)
//   Fn = max(0, k·d − c·v_y)                            Kelvin–Voigt (never pulls)
//   Ft = −μ·Fn·tanh(α·v_x)                              regularised Coulomb friction
//   τ_roll = −μ_roll·Fn·sgn_ε(ω),  sgn_ε(ω) = tanh(α·R·ω) rolling resistance
//
// Rolling resistance near rest: sign(ω) is replaced by tanh(α·R·ω), the same
// regularisation as sliding friction applied to the rim speed R·ω. Below a rim
// speed of about 1/α the torque behaves like a viscous damper, so ω decays
// smoothly to zero instead of flipping sign every step (no chatter), and with
// no driving torque nothing makes it creep. The price is an exponential tail
// with time constant ≈ 1.5·R/(μ_roll·g·α) for a disc, which shifts the stop
// distance by O(1/α²) relative to the Coulomb (sign) law.
#pragma once

#include <cmath>

#include "core/body.hpp"

namespace contact2d {

enum class DampingLaw { Compression, KelvinVoigt };

struct ContactParams {
  double k = 1e4;           // stiffness, N/m
  double c = 200.0;         // damping, N·s/m
  double mu = 0.0;          // sliding friction coefficient
  double alpha = 100.0;     // tanh regularisation of friction, s/m
  double mu_roll = 0.0;     // rolling resistance, m (circle only)
  double mu_torsion = 0.0;  // torsional friction (3D only; passed to MuJoCo)
  DampingLaw damping = DampingLaw::Compression;
};

// Normal force for penetration depth d ≥ 0 and normal velocity v_n of the point.
inline double normal_force(const ContactParams& p, double depth, double v_n) {
  if (depth <= 0.0) return 0.0;
  if (p.damping == DampingLaw::Compression) {
    return p.k * depth + p.c * (v_n < 0.0 ? -v_n : 0.0);
  }
  const double fn = p.k * depth - p.c * v_n;
  return fn > 0.0 ? fn : 0.0;
}

// tanh(x), the regularised sign used by both friction laws. For |x| ≥ 22,
// 1 − tanh|x| < 2·e⁻⁴⁴ ≈ 1.6e-19, far below half an ulp of 1 (1.1e-16), so
// the correctly rounded result is exactly ±1 — glibc returns the same from
// the same threshold. Returning it here skips a ~20 ns libm call for every
// point that slides or spins faster than 22/α; results are bit-identical.
inline double smooth_sign(double x) {
  if (x >= 22.0) return 1.0;
  if (x <= -22.0) return -1.0;
  return std::tanh(x);
}

// Tangential force −μ·Fn·tanh(α·v_t) for normal force Fn and slip speed v_t.
inline double friction_force(const ContactParams& p, double fn, double v_t) {
  return -p.mu * fn * smooth_sign(p.alpha * v_t);
}

// Rolling-resistance torque −μ_roll·Fn·tanh(α·R·ω) of a rolling contact of
// radius R (0 for a point that does not roll: no torque).
inline double rolling_torque(const ContactParams& p, double fn, double radius, double omega) {
  if (radius <= 0.0 || p.mu_roll <= 0.0) return 0.0;
  return -p.mu_roll * fn * smooth_sign(p.alpha * radius * omega);
}

}  // namespace contact2d
