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
//
// Two more friction laws take MuJoCo's elliptic friction cone apart
// (docs/physics.md, "The cone laws"). They are not models of physical
// friction: they exist so that a comparison can tell how much of a
// difference is the friction law's shape, how much the cone's push, and how
// much the rest. With ρ the cone ratio (MuJoCo's impratio), b = ρ·c and
// s = √((μ·v_t)² + (μ_roll·ω)²) (μ_roll·ω only for a rolling contact):
//
//   viscous_cone (friction_law = "viscous_cone"): the normal law as given
//   (Fn from above), friction viscous inside the cone and on its boundary
//   while sliding, sliding and rolling under one budget:
//     b·s ≤ μ²·Fn:  Ft = −b·v_t,         τ = −b·(μ_roll/μ)²·ω
//     else          Ft = −μ²·Fn·v_t/s,   τ = −μ_roll²·Fn·ω/s
//
//   soft_cone (friction_law = "soft_cone"): what MuJoCo 2.2's soft cone does
//   when every row of a contact shares the damper c. With F* the normal
//   law's unclamped aim (k·d − c·v_n, or k·d + c·max(0, −v_n) under
//   compression):
//     b·s ≤ μ²·F*:   Fn = F*,  Ft = −b·v_t,  τ = −b·(μ_roll/μ)²·ω
//     F* + c·s > 0:  Fn = (F* + c·s)/(1 + μ²/ρ),
//                    Ft = −μ²·Fn·v_t/s,  τ = −μ_roll²·Fn·ω/s
//     else           no force.
//   The term c·s is the push: the friction rows' damper projected onto the
//   cone lifts a sliding body; 1 + μ²/ρ is the projection's divisor. On the
//   ground the law acts where MuJoCo puts the contact, halfway into the
//   penetration (the lever r + (0, d/2)).
//
// Both are continuous across stick ↔ slide and where Fn reaches 0 (their
// derivatives are not).
#pragma once

#include <cmath>
#include <optional>
#include <string_view>

#include "core/body.hpp"
#include "core/vector_math.hpp"

namespace contact2d {

enum class DampingLaw { Compression, KelvinVoigt };
enum class FrictionLaw { Tanh, ViscousCone, SoftCone };

// "compression", "kelvin_voigt" (the scene files' damping): the one name
// table of the damping law; damping_law_title is its name in prose.
inline std::string_view damping_law_name(DampingLaw law) {
  switch (law) {
    case DampingLaw::Compression: return "compression";
    case DampingLaw::KelvinVoigt: return "kelvin_voigt";
  }
  return "compression";
}
inline std::string_view damping_law_title(DampingLaw law) {
  return law == DampingLaw::Compression ? "compression" : "Kelvin-Voigt";
}
inline std::optional<DampingLaw> parse_damping_law(std::string_view name) {
  for (DampingLaw law : {DampingLaw::Compression, DampingLaw::KelvinVoigt})
    if (damping_law_name(law) == name) return law;
  return std::nullopt;
}

// "tanh", "viscous_cone", "soft_cone" (the scene files' friction_law).
inline std::string_view friction_law_name(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::Tanh: return "tanh";
    case FrictionLaw::ViscousCone: return "viscous_cone";
    case FrictionLaw::SoftCone: return "soft_cone";
  }
  return "tanh";
}
inline std::optional<FrictionLaw> parse_friction_law(std::string_view name) {
  for (FrictionLaw law : {FrictionLaw::Tanh, FrictionLaw::ViscousCone, FrictionLaw::SoftCone})
    if (friction_law_name(law) == name) return law;
  return std::nullopt;
}

struct ContactParams {
  double k = 1e4;           // stiffness, N/m
  double c = 200.0;         // damping, N·s/m
  double mu = 0.0;          // sliding friction coefficient
  double alpha = 100.0;     // tanh regularisation of friction, s/m
  double mu_roll = 0.0;     // rolling resistance, m (circle only)
  double mu_torsion = 0.0;  // torsional friction (3D only; passed to MuJoCo)
  DampingLaw damping = DampingLaw::Compression;
  FrictionLaw friction = FrictionLaw::Tanh;
  double cone_ratio = 1.0;  // ρ of the cone laws (MuJoCo's impratio); unused by tanh
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

// The normal law's aim before the clamp at zero: k·d − c·v_n (Kelvin–Voigt)
// or k·d + c·max(0, −v_n) (compression), for d > 0.
inline double normal_aim(const ContactParams& p, double depth, double v_n) {
  if (p.damping == DampingLaw::Compression) return p.k * depth + p.c * (v_n < 0.0 ? -v_n : 0.0);
  return p.k * depth - p.c * v_n;
}

// The force of one contact under a cone law (see the top of this file).
struct ConeForce {
  double fn = 0.0;    // normal force
  double ft = 0.0;    // tangential force along t
  double roll = 0.0;  // rolling torque
};

// viscous_cone: `fn` the normal law's force (≥ 0), v_t the slip, `spin` the
// rolling rate ω (0 for a contact that does not roll).
inline ConeForce viscous_cone_force(const ContactParams& p, double fn, double v_t, double spin) {
  ConeForce f;
  f.fn = fn;
  if (p.mu <= 0.0 || fn <= 0.0) return f;  // no friction rows, or no load
  const double mu2 = p.mu * p.mu;
  const double roll2 = p.mu_roll * p.mu_roll;
  const double slip = std::sqrt(mu2 * v_t * v_t + roll2 * spin * spin);  // s
  const double b = p.cone_ratio * p.c;                                   // ρ·c
  if (b * slip <= mu2 * fn) {                                            // inside the cone
    f.ft = -b * v_t;
    f.roll = -b * (roll2 / mu2) * spin;
  } else {
    f.ft = -mu2 * fn * v_t / slip;
    f.roll = -roll2 * fn * spin / slip;
  }
  return f;
}

// soft_cone: `aim` = normal_aim(...) (F*), v_t the slip at MuJoCo's contact
// point, `spin` the rolling rate ω (0 for a contact that does not roll).
inline ConeForce soft_cone_force(const ContactParams& p, double aim, double v_t, double spin) {
  ConeForce f;
  if (p.mu <= 0.0) {  // no friction rows: the normal law alone
    f.fn = aim > 0.0 ? aim : 0.0;
    return f;
  }
  const double mu2 = p.mu * p.mu;
  const double roll2 = p.mu_roll * p.mu_roll;
  const double slip = std::sqrt(mu2 * v_t * v_t + roll2 * spin * spin);  // s
  const double b = p.cone_ratio * p.c;                                   // ρ·c
  if (aim > 0.0 && b * slip <= mu2 * aim) {                              // inside the cone
    f.fn = aim;
    f.ft = -b * v_t;
    f.roll = -b * (roll2 / mu2) * spin;
    return f;
  }
  const double pushed = aim + p.c * slip;
  if (pushed <= 0.0 || slip <= 0.0) return f;  // the polar cone: no force
  f.fn = pushed / (1.0 + mu2 / p.cone_ratio);
  f.ft = -mu2 * f.fn * v_t / slip;
  f.roll = -roll2 * f.fn * spin / slip;
  return f;
}

// tanh(x), the regularised sign used by both friction laws (the tanh law
// and rolling resistance): contact2d's own bounded_tanh (core/vector_math.hpp,
// ≤ 1.27 ULP, exactly ±1 from |x| = 22 on), the function the force stage's
// default path evaluates too, so the converged solution
// (reference/dense_reference.cpp) and the steppers share one law.
inline double smooth_sign(double x) { return bounded_tanh(x); }

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
