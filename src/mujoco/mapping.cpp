#include "mujoco/mapping.hpp"

#include "core/format.hpp"

#include <algorithm>
#include <cmath>

#include "core/input_error.hpp"

namespace contact2d::mujoco {
namespace {

// impratio is kept inside a range where MuJoCo's R_t = R/impratio stays a
// normal floating-point number (R ≈ Â/d ≈ 1e4·Â).
constexpr double kMinImpratio = 1e-15;
constexpr double kMaxImpratio = 1e10;
constexpr double kMinMu = 1e-5;  // MuJoCo's mjMINMU

std::string number(double v) { return format_number("%g", v); }

void require_spring_and_damper(const ContactParams& contact, Mapping mapping) {
  const std::string why =
      std::string(" for --mapping ") + std::string(mapping_name(mapping)) +
      " (its timeconst and dampratio need k > 0 and c > 0; use --mapping calibrated)";
  if (!(contact.k > 0.0))
    throw InputError("contact.k = " + number(contact.k) + " must be > 0 N/m" + why);
  if (!(contact.c > 0.0))
    throw InputError("contact.c = " + number(contact.c) + " must be > 0 N·s/m" + why);
}

// Largest inverse mass a contact point can present along the ground
// (tangentially): 1/m + r²/I with r the farthest contact point from the COM
// (for the circle the point below the centre, r = R). 1/m without rotation.
double max_tangential_inverse_mass(const RigidBody& body) {
  if (!shape_features(body.shape).turns || body.inertia <= 0.0) return 1.0 / body.mass;
  const double r = body_extent(body);
  return 1.0 / body.mass + r * r / body.inertia;
}

// impratio (see mapping.hpp): the largest value for which MuJoCo's explicit
// viscous friction, slope impratio·c per contact, does not reverse a slip
// within one step at any contact: Δt·A_t·impratio·c ≤ 1 (sliding) and, for a
// rolling contact, Δt·(1/I)·impratio·c·(μ_roll/μ)² ≤ 1 (the rolling rows'
// regulariser is R_t·μ²/μ_roll²). μ is clamped at MuJoCo's mjMINMU = 1e-5.
// Without sliding or rolling friction, the smallest impratio switches off
// what remains of MuJoCo's friction (coefficients are clamped at 1e-5) in a
// contact of condim > 1. The generated model has condim 1 then (mjcf.hpp),
// with no friction rows at all, and does not write impratio.
double calibrated_impratio(const ContactParams& p, const RigidBody& body, double dt,
                           double largest_c) {
  // A scene under a cone law is MuJoCo's own friction: its ratio is the
  // impratio (core/contact.hpp), so that a diagnosis's fix, pasted, runs
  // both engines as the diagnosis did.
  if (p.friction != FrictionLaw::Tanh) return std::clamp(p.cone_ratio, kMinImpratio, kMaxImpratio);
  const bool rolls = shape_features(body.shape).resists_rolling && p.mu_roll > 0.0;
  if (!(p.c > 0.0)) return 1.0;  // no damper: MuJoCo's friction has no velocity term at all
  if (p.mu <= 0.0 && !rolls) return kMinImpratio;
  // impratio is one value for every contact: the bound of the stiffest damper.
  const double step = largest_c * dt;
  double ratio = 1.0 / (step * max_tangential_inverse_mass(body));
  if (rolls) {
    const double mu = std::max(p.mu, kMinMu);
    ratio = std::min(ratio, body.inertia * (mu / p.mu_roll) * (mu / p.mu_roll) / step);
  }
  return std::clamp(ratio, kMinImpratio, kMaxImpratio);
}

}  // namespace

double largest_damping(const Scene& scene) {
  double c = scene.contact.c;
  for (const Obstacle& o : scene.obstacles) c = std::max(c, o.contact.apply(scene.contact).c);
  return c;
}

std::string_view mapping_name(Mapping mapping) {
  switch (mapping) {
    case Mapping::Seed: return "seed";
    case Mapping::Exact: return "exact";
    case Mapping::Calibrated: return "calibrated";
    case Mapping::Compensated: return "compensated";
  }
  return "?";
}

std::optional<Mapping> parse_mapping(std::string_view name) {
  for (Mapping mapping : kAllMappings) {
    if (mapping_name(mapping) == name) return mapping;
  }
  return std::nullopt;
}

std::string_view geometry_name(Geometry geometry) {
  return geometry == Geometry::CornerSpheres ? "corners" : "boxes";
}

std::optional<Geometry> parse_geometry(std::string_view name) {
  for (Geometry g : {Geometry::CornerSpheres, Geometry::BoxGeoms}) {
    if (geometry_name(g) == name) return g;
  }
  return std::nullopt;
}

int contacts_per_point(Shape shape, Geometry geometry) {
  const bool boxes = shape_features(shape).corners;
  return boxes && geometry == Geometry::BoxGeoms ? 2 : 1;
}

int resting_points(const RigidBody& body) {
  if (!shape_features(body.shape).corners || body.points.empty()) return 1;
  double lowest = body.points.front().y();
  for (const Vec2& p : body.points) lowest = std::min(lowest, p.y());
  const double size = body_extent(body);
  int n = 0;
  for (const Vec2& p : body.points) n += p.y() <= lowest + 1e-12 * size ? 1 : 0;
  return n;
}

void set_friction_damper(SolverSettings& s, const ContactParams& contact, const RigidBody& body,
                         double dt, double gravity) {
  if (s.mapping != Mapping::Compensated)
    throw InputError("friction damper: only over --mapping compensated (under " +
                     std::string(mapping_name(s.mapping)) +
                     " the friction rows' regulariser leaves no room for a small damper)");
  if (!(contact.mu > 0.0) || !(contact.c > 0.0)) return;  // no friction rows to damp, or no damper
  const double pi = 3.14159265358979323846;
  const double a_t = max_tangential_inverse_mass(body);
  const double weight = body.mass * gravity / resting_points(body);
  // α = 0 is Coulomb's step: the cap is the slope. Without a resting load
  // (gravity 0) the matched slope is 0, a damper with no friction at all:
  // there every load is an impact's, and the cap, which follows Coulomb
  // under load closest (docs/mujoco3.md), is the slope.
  const double tanh_matched = std::sqrt(6.0) / pi * contact.mu * contact.alpha * weight;
  const double cap = 1.0 / (dt * a_t);
  s.stick_slope = contact.alpha > 0.0 && weight > 0.0 ? std::min(tanh_matched, cap) : cap;
  const double d = s.solimp[0];
  const double regulariser = (1.0 - d) / d * s.inv_mass;
  s.friction_ratio = 1e3 * a_t * s.stick_slope / (regulariser * contact.c);
  s.impratio =
      std::clamp(s.stick_slope / (s.friction_ratio * contact.c), kMinImpratio, kMaxImpratio);
}

SolverSettings solver_settings(const Scene& scene, Mapping mapping, double inv_mass, int split) {
  return solver_settings(scene.contact, make_body(scene), scene.sim.dt, mapping, inv_mass, split,
                         largest_damping(scene));
}

SolverSettings solver_settings(const ContactParams& contact, const RigidBody& body, double dt,
                               Mapping mapping, double inv_mass, int split, double largest_c) {
  SolverSettings s;
  s.mapping = mapping;
  const double m = body.mass;
  const double k = contact.k;
  const double c = contact.c;
  if (mapping == Mapping::Compensated) {
    // mapping.hpp: MuJoCo divides the direct solref by D = d·A + (1 − d)·Â;
    // multiplying by D with A = 1/m undoes that exactly where A = 1/m and to
    // d·(A − 1/m)/Â ≤ d/kCompensatingGain elsewhere.
    s.inv_mass = inv_mass;
    s.split = split;
    s.assumed_inv_mass = 1.0 / m;
    const double scale = solref_scale(s);
    s.solref = {-k * scale / split, -c * scale / split};
    s.solimp = kMinimalSolimp;
    s.elliptic = true;
    s.impratio = calibrated_impratio(contact, body, dt, largest_c > 0.0 ? largest_c : contact.c);
    return s;
  }
  if (mapping == Mapping::Calibrated) {
    s.inv_mass = inv_mass;
    s.split = split;
    s.solref = {-k * inv_mass / split, -c * inv_mass / split};
    s.solimp = kMinimalSolimp;
    s.elliptic = true;
    s.impratio = calibrated_impratio(contact, body, dt, largest_c > 0.0 ? largest_c : contact.c);
    return s;
  }
  require_spring_and_damper(contact, mapping);
  const double dampratio = c / (2.0 * std::sqrt(m * k));
  const double timeconst = mapping == Mapping::Seed ? std::sqrt(m / k) : 2.0 * m / c;
  // Extreme k, c or m overflow or underflow them (√(m/k) or 2m/c = inf,
  // dampratio = 0, subnormal or inf): MuJoCo would read "inf" and lose the
  // spring, read a timeconst of 0 as the direct form, or mix a subnormal
  // dampratio with the ground's (0.5·ζ + 0.5·ζ) to 0 and warn "mixed solref
  // format".
  auto usable = [](double v) { return v > 0.0 && std::isnormal(v); };
  if (!usable(timeconst) || !usable(dampratio)) {
    throw InputError(
        "contact.k = " + number(k) + ", contact.c = " + number(c) + " with mass " + number(m) +
        " kg give timeconst " + number(timeconst) + " s, dampratio " + number(dampratio) +
        " for --mapping " + std::string(mapping_name(mapping)) +
        ": MuJoCo's solref needs both > 0, finite and not subnormal; use --mapping calibrated");
  }
  s.solref = {timeconst, dampratio};
  s.refsafe_clamped = timeconst < 2.0 * dt;
  return s;
}

double solref_scale(const SolverSettings& s) {
  const double d = kMinimalSolimp[0];
  switch (s.mapping) {
    case Mapping::Calibrated: return s.inv_mass;
    case Mapping::Compensated: return d * s.assumed_inv_mass + (1.0 - d) * s.inv_mass;
    case Mapping::Seed:
    case Mapping::Exact: break;
  }
  return 0.0;
}

double compensating_lever(double mass, double hinge_inertia, double max_inverse_mass) {
  // (2/m + L²/I)/3 = G·A_max  ⇔  L² = I·(3·G·A_max − 2/m)
  return std::sqrt(hinge_inertia * (3.0 * kCompensatingGain * max_inverse_mass - 2.0 / mass));
}

AccelerationGains acceleration_gains(const std::array<double, 2>& solref) {
  if (solref[0] <= 0.0 && solref[1] <= 0.0) return {-solref[0], -solref[1]};
  const double tc = solref[0];
  const double zeta = solref[1];
  return {1.0 / (tc * tc * zeta * zeta), 2.0 / tc};
}

std::string mujoco_integrator(Integrator integrator) {
  switch (integrator) {
    case Integrator::SemiImplicitEuler: return "Euler";
    case Integrator::RK4: return "RK4";
    case Integrator::ImplicitEuler: return "implicit";
    case Integrator::ExplicitEuler: break;
  }
  throw InputError(
      "sim.integrator = explicit_euler has no MuJoCo 2.2 counterpart: use semi_implicit_euler "
      "(MuJoCo Euler), "
      "rk4 (MuJoCo RK4) or implicit_euler (MuJoCo implicit)");
}

}  // namespace contact2d::mujoco
