// Why a MuJoCo run diverged, in MuJoCo's terms.
//
// The reference's diagnosis (core/divergence.hpp) speaks of its own
// integrators and of implicit Euler's Newton iteration; none of that applies
// to MuJoCo, which solves the contact as a soft constraint and integrates
// the resulting force explicitly in all three of its 2.2 integrators
// (`implicit` treats joint damping and actuators implicitly, not contacts).
// The linear regime of one contact in MuJoCo 2.2 (engine_core_constraint.c):
// with impedance d (solimp, flat at d_max here), the model's solref gains
//   K·d_max², B·d_max      (mapping.hpp, acceleration_gains)
// and A the contact's true inverse mass, Â MuJoCo's estimate
// (body_invweight0), the force is f = d·(−B·v − K·d·p)/(d·A + (1 − d)·Â), so
// the contact point accelerates as a damped oscillator with
//   ω² = A·d²K/(d·A + (1 − d)·Â),   2ζω = A·d·B/(d·A + (1 − d)·Â).
// MuJoCo's Euler is semi-implicit (velocity first), so its limit on ω·Δt is
// the semi-implicit Euler limit at that ζ; its implicit integrator has the
// same limit for contacts; its RK4 has RK4's (core/integrators.hpp,
// stability_limit). Friction rows add a viscous slope impratio·B per unit
// tangential inverse mass A_t, explicit in v_t: Δt·A_t·impratio·B·d/(…) is
// the friction's ω·Δt (the calibrated mapping keeps it ≤ 1).
#pragma once

#include <string>

#include "core/divergence.hpp"
#include "mujoco/mapping.hpp"

namespace contact2d::mujoco {

// The contact's linear regime as MuJoCo integrates it.
struct MujocoContactRegime {
  double inv_mass = 0.0;    // A: the reference's largest contact inverse mass, 1/kg
  double inv_weight = 0.0;  // Â: body_invweight0, 1/kg
  double impedance = 0.0;   // d_max of solimp
  double omega = 0.0;       // rad/s
  double zeta = 0.0;
  double friction_rate =
      0.0;  // 1/s: impratio·(damping) on the tangential rows (0 without friction)
};
MujocoContactRegime mujoco_contact_regime(const Model& model, const SolverSettings& settings,
                                          double inv_weight);
MujocoContactRegime mujoco_contact_regime(const Scene& scene, const SolverSettings& settings,
                                          double inv_weight);

// The regime as the run loop's energy rule sees it (Stepper::stability()):
// ω·Δt of the oscillator above and the limit of the scheme MuJoCo integrates
// the contact force with — semi-implicit Euler for its Euler and implicit
// integrators, RK4 for its RK4 — at its ζ (MuJoCo's damping acts both ways).
StepStability mujoco_stability(const Model& model, Integrator integrator, double dt,
                               const SolverSettings& settings, double inv_weight);

// One paragraph: when and what (core divergence_event), MuJoCo's integrator
// and Δt, the model's solref/solimp/impratio, ω and ζ as MuJoCo sees them,
// ω·Δt against its integrator's limit, refsafe, and what to try — MuJoCo
// options only (its step, its RK4, another mapping), never the reference's.
std::string describe_mujoco_divergence(const Divergence& d, const Scene& scene,
                                       const SolverSettings& settings, double inv_weight);

}  // namespace contact2d::mujoco
