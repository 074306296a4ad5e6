// MuJoCo's diagnosis of a divergence (mujoco/divergence.hpp).
#include "mujoco/divergence.hpp"

#include <algorithm>
#include <cmath>

#include "core/dynamics.hpp"
#include "core/format.hpp"
#include "core/integrators.hpp"

namespace contact2d::mujoco {
namespace {

// MuJoCo's integrators on a contact: Euler and implicit both update the
// velocity first with the explicit contact force (semi-implicit Euler);
// RK4 is RK4.
Integrator contact_scheme(Integrator integrator) {
  return integrator == Integrator::RK4 ? Integrator::RK4 : Integrator::SemiImplicitEuler;
}

}  // namespace

MujocoContactRegime mujoco_contact_regime(const Scene& scene, const SolverSettings& settings,
                                          double inv_weight) {
  return mujoco_contact_regime(make_model(scene), settings, inv_weight);
}

StepStability mujoco_stability(const Model& model, Integrator integrator, double dt,
                               const SolverSettings& settings, double inv_weight) {
  const MujocoContactRegime r = mujoco_contact_regime(model, settings, inv_weight);
  StepStability s;
  s.scheme = contact_scheme(integrator);
  s.omega_dt = r.omega * dt;
  s.limit = stability_limit(s.scheme, r.zeta);
  return s;
}

MujocoContactRegime mujoco_contact_regime(const Model& model, const SolverSettings& settings,
                                          double inv_weight) {
  MujocoContactRegime r;
  r.inv_mass = 1.0 / contact_stiffness(model).m_eff;
  r.inv_weight = inv_weight > 0.0 ? inv_weight : r.inv_mass;
  r.impedance = settings.solimp[1];
  const AccelerationGains gains = acceleration_gains(settings.solref);
  const double d = r.impedance;
  // f = d·(−B·v − K·d·p)/(d·A + (1 − d)·Â); gains = (K·d², B·d).
  const double denominator = d * r.inv_mass + (1.0 - d) * r.inv_weight;
  const double omega2 = r.inv_mass * gains.stiffness / denominator;
  r.omega = std::sqrt(std::max(0.0, omega2));
  r.zeta = r.omega > 0.0 ? r.inv_mass * gains.damping / denominator / (2.0 * r.omega) : 0.0;
  if (model.contact.mu > 0.0 || model.contact.mu_roll > 0.0) {
    // Tangential rows: R_t = R/impratio, no spring.
    const double tangential =
        d * r.inv_mass + (1.0 - d) * r.inv_weight / std::max(settings.impratio, 1e-300);
    r.friction_rate = r.inv_mass * gains.damping / tangential;
  }
  return r;
}

std::string describe_mujoco_divergence(const Divergence& d, const Scene& scene,
                                       const SolverSettings& settings, double inv_weight) {
  const Integrator integrator = scene.sim.integrator;
  const std::string mj_integrator = mujoco_integrator(integrator);
  const double dt = scene.sim.dt;
  std::string event = divergence_event(d);
  if (d.kind == DivergenceKind::NonFinite)
    event =
        "MuJoCo's state became non-finite (it counts a bad-number warning and resets "
        "its data; the run stops here instead)";
  std::string message = "MuJoCo diverged at t = " + format_text("%.6g", d.time) + " s in scene " +
                        std::string(shape_name(scene.shape)) + " (MuJoCo " + mj_integrator +
                        ", timestep = " + format_text("%g", dt) + ", " +
                        std::string(mapping_name(settings.mapping)) + " mapping): " + event + ". ";
  const MujocoContactRegime r = mujoco_contact_regime(scene, settings, inv_weight);
  message +=
      "Its contact: solref = (" + format_number(settings.solref[0], 3) + ", " +
      format_number(settings.solref[1], 3) + "), impedance d = " + format_number(r.impedance, 3) +
      ", impratio = " + format_number(settings.impratio, 3) +
      "; MuJoCo's soft constraint makes it an oscillator with ω = " + format_number(r.omega, 3) +
      " rad/s, ζ = " + format_number(r.zeta, 3) +
      " (contact inverse mass A = " + format_number(r.inv_mass, 3) +
      " 1/kg, body_invweight0 = " + format_number(r.inv_weight, 3) + " 1/kg). ";
  if (settings.refsafe_clamped)
    message +=
        "MuJoCo's refsafe raised the solref timeconst to 2·timestep, a softer contact "
        "than the scene asks for. ";
  const double omega_dt = r.omega * dt;
  const double limit = stability_limit(contact_scheme(integrator), r.zeta);
  const double rk4_limit = stability_limit(Integrator::RK4, r.zeta);
  const std::string scheme = integrator == Integrator::ImplicitEuler
                                 ? "MuJoCo's implicit integrator (contact forces are explicit "
                                   "in it, so it has Euler's limit)"
                                 : "MuJoCo's " + mj_integrator;
  const double friction_dt = r.friction_rate * dt;
  if (omega_dt > limit) {
    message += "Likely cause: ω·Δt = " + format_number(omega_dt, 3) + " exceeds the limit " +
               format_number(limit, 3) + " of " + scheme + ". Try --dt " +
               format_text("%.2g", 0.5 * limit / r.omega);
    if (integrator != Integrator::RK4 && omega_dt < rk4_limit)
      message += ", or --integrator rk4 (MuJoCo's RK4: limit " + format_number(rk4_limit, 3) + ")";
    message += ".";
  } else if (friction_dt > 1.0) {
    message += "Likely cause: the friction rows' viscous slope impratio·B gives Δt·rate = " +
               format_number(friction_dt, 3) +
               " > 1 (the slip reverses within one step). Try a smaller --dt.";
  } else {
    message += "ω·Δt = " + format_number(omega_dt, 3) + " is within the limit " +
               format_number(limit, 3) + " of " + scheme +
               " for one contact; several contacts at once or a fast impact stiffen it. Try a "
               "smaller --dt" +
               (integrator != Integrator::RK4 ? std::string(" or --integrator rk4") : "") + ".";
  }
  return message;
}

}  // namespace contact2d::mujoco
