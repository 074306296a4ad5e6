#include "core/divergence.hpp"

#include "core/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace contact2d {

ContactStiffness contact_stiffness(const Model& model) {
  ContactStiffness cs;
  cs.m_eff = min_effective_mass(model.body);
  if (model.contact.k > 0.0) {
    // The stiffest law (an obstacle's may be stiffer than the ground's).
    cs.omega = std::sqrt(model.max_k() / cs.m_eff);
    cs.zeta = model.contact.c / (2.0 * std::sqrt(model.contact.k * cs.m_eff));
  }
  return cs;
}

DivergenceMonitor::DivergenceMonitor(const Model& model, const State& initial,
                                     const ContactSet& contacts)
    : model_(&model) {
  const RigidBody& body = model.body;
  const double mg = body.mass * model.gravity;
  // Height of the lowest contact point above the ground.
  double lowest = std::numeric_limits<double>::infinity();
  const double ct = body.points_rotate ? std::cos(initial.q.z()) : 1.0;
  const double st = body.points_rotate ? std::sin(initial.q.z()) : 0.0;
  for (const Vec2& r : body.points)
    lowest = std::min(lowest, initial.q.y() + st * r.x() + ct * r.y());
  const double h0 = std::isfinite(lowest) ? std::max(0.0, lowest) : 0.0;
  const double kinetic = 0.5 * body.mass * initial.v.head<2>().squaredNorm() +
                         0.5 * body.inertia * initial.v.z() * initial.v.z();
  initial_energy_ = energy(model, contacts, initial);
  const double spring = initial_energy_ - kinetic - mg * initial.q.y();
  available_ = kinetic + mg * (h0 + body_extent(body)) + spring;
  // A body with no weight and no motion still gets a tiny positive scale.
  available_ = std::max(available_, 1e-12 * std::max(1.0, body.mass));
  max_depth_ = depth_limit(available_);
}

double DivergenceMonitor::depth_limit(double energy) const {
  const double mg = model_->body.mass * model_->gravity;
  // The softest law lets a spring hold the energy deepest.
  const double k = model_->min_k();
  return k > 0.0 ? 2.0 * (mg + std::sqrt(mg * mg + 2.0 * k * energy)) / k
                 : std::numeric_limits<double>::infinity();
}

std::optional<Divergence> DivergenceMonitor::check(const State& s, const ContactSet& contacts,
                                                   double t, double applied_work,
                                                   double* energy_out) const {
  if (!s.q.allFinite() || !s.v.allFinite()) {
    return Divergence{DivergenceKind::NonFinite, t, std::numeric_limits<double>::quiet_NaN(), 0.0};
  }
  const double e = energy(*model_, contacts, s);
  if (energy_out) *energy_out = e;
  const double gain = e - initial_energy_;
  const double allowed = available_ + std::abs(applied_work);
  if (gain > allowed) return Divergence{DivergenceKind::EnergyGain, t, gain, allowed};
  const double depth = max_penetration(contacts);
  // Work put in by applied forces can end up in one spring too.
  const double depth_allowed = applied_work == 0.0 ? max_depth_ : depth_limit(allowed);
  if (depth > depth_allowed)
    return Divergence{DivergenceKind::Penetration, t, depth, depth_allowed};
  return std::nullopt;
}

namespace {

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  return format_text(fmt, a, b, c);
}

}  // namespace

StepStability reference_stability(const Model& model, Integrator integrator, double dt) {
  const ContactStiffness cs = contact_stiffness(model);
  StepStability s;
  s.scheme = integrator;
  s.omega_dt = cs.omega * dt;
  s.limit = stability_limit(integrator, cs.zeta);
  if (model.contact.damping == DampingLaw::Compression && integrator != Integrator::ExplicitEuler)
    s.limit = std::min(s.limit, stability_limit(integrator, 0.0));
  return s;
}

namespace {

// The friction's rate (1/s) of one load `fn` at lever `lever` (the terms of
// friction_step's λ; the lever counts only for a body that turns).
double friction_rate(const Model& model, double fn, double lever) {
  const ContactParams& law = model.contact;
  const RigidBody& body = model.body;
  const ShapeFeatures features = shape_features(body.shape);
  const bool turns = features.turns && body.inertia > 0.0;
  double rate =
      law.mu * fn * law.alpha * (1.0 / body.mass + (turns ? lever * lever / body.inertia : 0.0));
  if (turns && features.resists_rolling && law.mu_roll > 0.0)
    rate += law.mu_roll * fn * law.alpha * body.roll_radius / body.inertia;
  return rate;
}

FrictionStep friction_limit(Integrator integrator, double rate_dt) {
  FrictionStep f;
  f.rate_dt = rate_dt;
  switch (integrator) {
    case Integrator::ExplicitEuler:
    case Integrator::SemiImplicitEuler: f.limit = 2.0; break;
    case Integrator::RK4: f.limit = 2.785293563405282; break;  // z³ − 4z² + 12z − 24 = 0
    case Integrator::ImplicitEuler: break;                     // none
  }
  return f;
}

bool tanh_with_gravity(const Model& model) {
  return model.contact.friction == FrictionLaw::Tanh && model.gravity > 0.0;
}

}  // namespace

FrictionStep friction_step(const Model& model, Integrator integrator, double dt) {
  if (!tanh_with_gravity(model)) return {};
  const double weight = model.body.mass * model.gravity;
  return friction_limit(integrator, friction_rate(model, weight, body_extent(model.body)) * dt);
}

FrictionStep friction_step(const Model& model, Integrator integrator, double dt,
                           const ContactSet& contacts) {
  if (!tanh_with_gravity(model)) return {};
  double rate = 0.0;
  int loaded = 0;
  const Contact* const list = contacts.begin();
  for (size_t i = 0; i < contacts.ground_count(); ++i) {
    if (!(list[i].depth > 0.0)) continue;
    rate += friction_rate(model, model.contact.k * list[i].depth, list[i].ry);
    ++loaded;
  }
  if (!(rate > 0.0)) return friction_step(model, integrator, dt);
  FrictionStep f = friction_limit(integrator, rate * dt);
  if (loaded > 1) f.onset = 0.8;
  return f;
}

double energy_rise_tolerance(const StepStability& stability, double available_energy) {
  const double rounding = 1e-9 * available_energy;
  const double wdt = stability.omega_dt;
  // Explicit Euler's growth over one undamped contact: π/(ω·Δt) steps of 1 + (ω·Δt)².
  const double growth =
      stability.scheme == Integrator::ExplicitEuler
          ? std::expm1(std::log1p(wdt * wdt) * std::acos(-1.0) / std::max(wdt, 1e-300))
          : 0.0;
  if (stability.beyond()) return available_energy * std::min(1.0, growth) + rounding;
  const double oscillation = wdt < 1.0 ? 2.0 * (0.5 * wdt) / (1.0 - 0.5 * wdt) : 1.0;
  return available_energy * std::min(1.0, oscillation + growth) + rounding;
}

double free_flight_gain(const Model& model, Integrator integrator, double dt, long long steps) {
  if (integrator != Integrator::ExplicitEuler) return 0.0;
  const double g = model.gravity;
  return static_cast<double>(steps) * 0.5 * model.body.mass * g * g * dt * dt;
}

double body_size(const RigidBody& body) { return 2.0 * body_extent(body); }

std::string describe_energy_rise(const EnergyBalance& b, double available_energy,
                                 const Scene& scene) {
  const Model model = make_model(scene);
  const double wdt = contact_stiffness(model).omega * scene.sim.dt;
  const double g = model.gravity;
  const double flight_step = 0.5 * model.body.mass * g * g * scene.sim.dt * scene.sim.dt;
  std::string cause;
  if (scene.sim.integrator == Integrator::ExplicitEuler && !b.rise_in_contact) {
    cause = "explicit Euler gains ½·m·g²·Δt² = " + format("%.3g", flight_step) +
            " J on every step in free flight, and nothing touched during this rise; a smaller "
            "--dt shrinks it";
  } else if (scene.sim.integrator == Integrator::ExplicitEuler) {
    cause = "explicit Euler multiplies the energy by 1 + (ω·Δt)² = 1 + " +
            format("%.3g", wdt * wdt) +
            " on every step in contact (and gains ½·m·g²·Δt² = " + format("%.3g", flight_step) +
            " J on every step in free flight)";
  } else if (!b.rise_in_contact) {
    cause = std::string(integrator_title(scene.sim.integrator)) +
            " does not gain energy in free flight, and nothing touched during this rise";
  } else if (b.stability.beyond()) {
    const std::string scheme(integrator_title(b.stability.scheme));
    cause = "ω·Δt = " + format("%.3g", b.stability.omega_dt) + " on the contact is beyond the " +
            scheme + " limit " + format("%.3g", b.stability.limit) +
            (b.stability.scheme != scene.sim.integrator
                 ? " (the engine integrates the contact force with " + scheme + ")"
                 : std::string()) +
            ", where every step in contact adds energy (no oscillation bound holds, only "
            "rounding is allowed); try --dt " +
            format("%.2g", 0.5 * scene.sim.dt * b.stability.limit / b.stability.omega_dt);
  } else {
    cause = "the contact is resolved with ω·Δt = " + format("%.3g", wdt) +
            "; a smaller --dt shrinks the rise";
  }
  return "energy rose by " + format("%.3g", b.max_rise) + " J (" +
         format("%.3g", 100.0 * b.max_rise / available_energy) +
         " % of the energy available) at t = " + format("%.6g", b.time_of_max_rise) +
         " s, more than the " + format("%.3g", b.tolerance) +
         " J the integrator explains (a passive system only loses energy); likely cause: " + cause;
}

std::string describe_nonphysical(const EnergyBalance& balance, const DepthRecord& depth,
                                 double available_energy, const Scene& scene) {
  std::string text;
  const Model model = make_model(scene);
  const double k = model.min_k();
  const std::string static_depth =
      k > 0.0 ? format(" (its weight alone presses the softest contact m·g/k = %.3g m deep)",
                       model.body.mass * model.gravity / k)
              : std::string();
  if (depth.too_deep()) {
    text = format("the run ended (t = %.6g s) with a contact point %.3g m deep, deeper than ",
                  depth.time, depth.depth) +
           format("the body's own size %.3g m: the body is inside the surface, not on it",
                  depth.size) +
           static_depth;
  }
  if (depth.below_ground()) {
    text += (text.empty() ? "" : "; ") +
            format(
                "its centre of mass ended at y = %.3g m, more than the body's own size %.3g m "
                "below the ground",
                depth.y, depth.size);
  }
  if (balance.exceeded())
    text += (text.empty() ? "" : "; ") + describe_energy_rise(balance, available_energy, scene);
  return text;
}

std::string divergence_event(const Divergence& d) {
  switch (d.kind) {
    case DivergenceKind::NonFinite: return "the state became non-finite";
    case DivergenceKind::EnergyGain:
      return format("the energy rose by %.3g J, more than the %.3g J the system ever held", d.value,
                    d.limit);
    case DivergenceKind::Penetration:
      return format(
          "a contact point sank %.3g m into the ground, beyond the %.3g m any "
          "energy in the scene can explain",
          d.value, d.limit);
    case DivergenceKind::NewtonFailed:
      return "implicit Euler's Newton iteration did not converge even at dt/64";
  }
  return "";
}

std::string describe(const Divergence& d, const Scene& scene) {
  const Model model = make_model(scene);
  const ContactStiffness cs = contact_stiffness(model);
  const Integrator integrator = scene.sim.integrator;
  const double dt = scene.sim.dt;
  const std::string what = divergence_event(d);
  std::string message = "simulation diverged at t = " + format("%.6g", d.time) + " s in scene " +
                        std::string(shape_name(scene.shape)) + " (" +
                        std::string(integrator_name(integrator)) + ", dt = " + format("%g", dt) +
                        "): " + what + ". ";

  const double omega_dt = cs.omega * dt;
  const std::string method(integrator_title(integrator));
  // The compression law damps only while the point moves in: the rebound is
  // an undamped oscillator, so the binding limit is the smaller of ζ and 0.
  const double limit =
      scene.contact.damping == DampingLaw::Compression
          ? std::min(stability_limit(integrator, cs.zeta), stability_limit(integrator, 0.0))
          : stability_limit(integrator, cs.zeta);
  const std::string omega_text =
      format(" (ω = √(k/m_eff) = %.4g rad/s, ζ = %.3g)", cs.omega, cs.zeta);
  // Friction linearised at Fn ≈ m·g: a viscous rate μ·g·α (per unit mass).
  const double friction_rate_dt = scene.contact.mu * scene.sim.gravity * scene.contact.alpha * dt;
  const bool implicit = integrator == Integrator::ImplicitEuler;
  const std::string alternative = implicit ? "" : " or --integrator implicit_euler";
  if (implicit) {
    message += "Implicit Euler is stable on the linear contact at any step; at ω·Δt = " +
               format("%.3g", omega_dt) + omega_text +
               " the piecewise contact force defeats its Newton iteration. Try a smaller --dt.";
    if (scene.contact.friction == FrictionLaw::SoftCone)
      message +=
          " Under friction_law = \"soft_cone\" a smaller step may not help: its push c·μ·|v_t| "
          "keeps a sliding contact loaded up to the surface, so the force jumps there while the "
          "point separates and the implicit equation has no solution; run it with "
          "semi_implicit_euler, as MuJoCo does.";
  } else if (limit < 1e-3) {
    // Explicit Euler on an undamped rebound: no step is stable; each contact
    // step multiplies the energy by 1 + (ω·Δt)².
    const double safe_dt = 0.05 / cs.omega;
    message +=
        "Likely cause: " + method + " gains energy on every undamped rebound (the " +
        "compression law does not damp it): each contact step multiplies it by 1 + (ω·Δt)² = 1 + " +
        format("%.3g", omega_dt * omega_dt) + omega_text + ". Try --dt " + format("%.2g", safe_dt) +
        " or --integrator semi_implicit_euler.";
  } else if (omega_dt > limit) {
    const double safe_dt = 0.5 * limit / cs.omega;
    message += "Likely cause: ω·Δt = " + format("%.3g", omega_dt) + " exceeds the " + method +
               " limit " + format("%.3g", limit) + omega_text + ". Try --dt " +
               format("%.2g", safe_dt) + alternative + ".";
  } else if (friction_rate_dt > 1.0) {
    message += "Likely cause: stiff friction, μ·g·α·Δt = " + format("%.3g", friction_rate_dt) +
               " (explicit methods need it well below 2). Try a smaller --dt, a smaller "
               "contact.alpha" +
               alternative + ".";
  } else {
    message += "ω·Δt = " + format("%.3g", omega_dt) + " is within the " + method + " limit " +
               format("%.3g", limit) + omega_text +
               " for one contact; several contacts at once or a fast impact stiffen it. Try a "
               "smaller --dt" +
               alternative + ".";
  }
  return message;
}

}  // namespace contact2d
