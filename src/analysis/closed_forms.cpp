// Both engines and the converged solution against closed forms
// (analysis/closed_forms.hpp; derivations in docs/closed-forms.md). Every
// closed form is computed by src/benchmarks/; this file builds the scenes,
// states the tolerances and reads the runs.
#include "analysis/closed_forms.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "analysis/engine.hpp"
#include "analysis/reference.hpp"
#include "benchmarks/impact.hpp"
#include "benchmarks/rest.hpp"
#include "benchmarks/rolling.hpp"
#include "benchmarks/sliding.hpp"
#include "benchmarks/slope.hpp"
#include "core/format.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {
namespace {

namespace bm = benchmarks;

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ------------------------------------------------------------ extractors

// The sample nearest to time t.
const State& at(const Trajectory& tr, double t) {
  const auto it = std::lower_bound(tr.samples.begin(), tr.samples.end(), t,
                                   [](const Sample& s, double value) { return s.t < value; });
  if (it == tr.samples.end()) return tr.samples.back().state;
  if (it != tr.samples.begin() && std::abs(std::prev(it)->t - t) < std::abs(it->t - t))
    return std::prev(it)->state;
  return it->state;
}
const State& last(const Trajectory& tr) { return tr.samples.back().state; }

// Acceleration along d from a least-squares parabola through the positions
// sampled in [t0, t1]: exact for a uniformly accelerated body, and it
// averages out the rattle of a body that hops (MuJoCo on the slope), which a
// difference of two sampled velocities would not.
double fitted_acceleration(const Trajectory& tr, const Vec2& d, double t0, double t1) {
  const double tm = 0.5 * (t0 + t1);
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const Sample& s : tr.samples) {
    if (s.t < t0 - 1e-12 || s.t > t1 + 1e-12) continue;
    const double t = s.t - tm;
    const Eigen::Vector3d row(1.0, t, t * t);
    normal += row * row.transpose();
    rhs += row * (s.state.q.x() * d.x() + s.state.q.y() * d.y());
  }
  return 2.0 * normal.ldlt().solve(rhs)(2);
}

// The first time (linear interpolation between samples) at which the slip
// of the disc's contact point, u = v_x + ω·R, falls to `u_th`; NaN if never.
double slip_time(const Scene& scene, const Trajectory& tr, double u_th) {
  const double R = scene.radius;
  for (size_t i = 1; i < tr.samples.size(); ++i) {
    const Sample& a = tr.samples[i - 1];
    const Sample& b = tr.samples[i];
    const double ua = a.state.v.x() + a.state.v.z() * R;
    const double ub = b.state.v.x() + b.state.v.z() * R;
    if (ua > u_th && ub <= u_th) return a.t + (b.t - a.t) * (ua - u_th) / (ua - ub);
  }
  return kNaN;
}

// ------------------------------------------------------------ scenes

Scene base(Shape shape, double k, double c, double duration) {
  Scene s = default_scene(shape);
  s.mass = 1.0;
  s.contact.k = k;
  s.contact.c = c;
  s.contact.mu = 0.0;
  s.contact.mu_roll = 0.0;
  s.contact.alpha = 100.0;
  s.contact.damping = DampingLaw::KelvinVoigt;
  s.sim.dt = 1e-4;
  s.sim.integrator = Integrator::SemiImplicitEuler;
  s.sim.duration = duration;
  s.sim.output_dt = 1e-3;
  s.initial = State{};
  return s;
}

// MuJoCo's contact constants of a scene under the default mapping, read
// from the compiled model: stiffness s = −solref[0] (direct form), flat
// impedance d = solimp[0], Â = body_invweight0 (translational), contacts
// per 2D point.
struct MujocoConstants {
  double stiffness = kNaN, impedance = kNaN, inv_weight = kNaN, impratio = kNaN;
  int split = 1;
  bool direct_flat = false;
};
MujocoConstants mujoco_constants(const Scene& scene) {
  const mujoco::GeneratedModel g = mujoco::generate_mjcf(scene, mujoco::MjcfOptions{});
  const mujoco::ModelPtr m = mujoco::load_model(g.xml, "closed-form static scene");
  MujocoConstants out;
  out.split = g.settings.split;
  out.direct_flat = g.settings.solref[0] < 0.0 && g.settings.solimp[0] == g.settings.solimp[1];
  out.stiffness = -g.settings.solref[0];
  out.impedance = g.settings.solimp[0];
  out.impratio = g.settings.impratio;
  out.inv_weight = m->body_invweight0[2];  // body 1 (the scene's body), its translational entry
  return out;
}

// ------------------------------------------------------------ cases

// How many contact points a body resting flat stands on (whether they are
// corners, MuJoCo's corner spheres, is shape_features'). Only the point
// mass and the flat box have this case; a new shape decides here whether
// it has one.
int resting_contacts(Shape shape) {
  switch (shape) {
    case Shape::PointMass: return 1;
    case Shape::Box: return 2;
    case Shape::TShape:
    case Shape::Circle:
    case Shape::Ellipse:
      break;  // not cases of the table (the ellipse's: tests/core/test_ellipse.cpp)
  }
  throw std::logic_error("static_case: no resting closed form for " +
                         std::string(shape_name(shape)));
}

ClosedFormCase static_case(Shape shape) {
  const int n = resting_contacts(shape);
  const bool box = shape_features(shape).corners;
  ClosedFormCase cs;
  cs.id = box ? "static.box" : "static.point_mass";
  cs.name = box ? "static penetration, flat box (2 corners)" : "static penetration, point mass";
  // ζ = 1 of the vertical mode: c = 2√(k·m)/N with N bottom contacts.
  const double k = 1e4;
  Scene& s = cs.scene = base(shape, k, 2.0 * std::sqrt(k * 1.0) / n, 0.3);
  const double surface = box ? 0.5 * s.height : s.half_height;  // COM above the contact points
  s.initial.q = Vec3(0.0, surface, 0.0);
  const double m = s.mass, g = s.sim.gravity;
  const double depth = bm::rest_depth(m, g, k, n);
  const Extractor extract = [surface](const Scene&, const Trajectory& tr) {
    return surface - last(tr).q.y();
  };

  ClosedFormQuantity q;
  q.name = "depth at rest (m)";
  q.formula = box ? "m·g/(2k)" : "m·g/k";
  q.closed_form = depth;
  q.extract = extract;
  // At rest a = 0 is a fixed point of the integrator; what is left is the
  // critically damped transient (1 + ωT)·e^(−ωT) ≤ 3e-12 at ωT = 30, and
  // rounding: 1e-9 relative.
  q.tolerance = 1e-9 * depth;
  q.why = "transient (1+ωT)e^(−ωT) < 3e-12 + rounding: 1e-9·depth";
  // The dense solution at tol 1e-10: a few times atol in y.
  q.converged_tolerance = 10.0 * kConvergedTol;
  const MujocoConstants mj = mujoco_constants(s);
  // MuJoCo under the mapping: its own answer, (1 − d)·m·g/k under
  // calibrated: off by d·depth, plus, for corner spheres, the sphere radius
  // ε = 1e-9 m by which MuJoCo's contact sits below the 2D point.
  const double eps = box ? mujoco::kCornerRadius : 0.0;
  q.mujoco_bound = mj.impedance * depth + eps + 1e-9 * depth;
  q.mujoco_bound_derived = true;
  q.mujoco_why = "d·depth (impedance d = " + format_number(mj.impedance, 3) + ")" +
                 (box ? " + ε = 1e-9 m (corner sphere)" : "") + " + 1e-9·depth";
  cs.quantities.push_back(q);

  // MuJoCo's own direct-form answer (its RestPenetration test: g(1 − d)/s
  // for a free body, Â = 1/m): p = f·Â·(1 − d)/s per contact, f = m·g/(N·n).
  ClosedFormQuantity own;
  own.name = "MuJoCo's own rest depth (m)";
  own.formula = "m·g·Â·(1−d)/(N·n·s)";
  own.closed_form = bm::soft_constraint_rest_depth(m, g, mj.inv_weight, mj.impedance, n * mj.split,
                                                   mj.stiffness) -
                    eps;
  own.extract = extract;
  own.reference_applies = false;
  own.mujoco_bound = 1e-9 * depth;
  own.mujoco_bound_derived = true;
  own.mujoco_why = "its own law at rest: transient + rounding, 1e-9·depth";
  if (!mj.direct_flat) own.mujoco_why += " (not direct form with flat solimp: formula approximate)";
  own.why = "MuJoCo only";
  cs.quantities.push_back(own);
  return cs;
}

// Semi-implicit Euler's error on the restitution e(ζ) of one impact, to
// first order in ωΔt (docs/closed-forms.md): (1) the damper's force c·v0
// switches on at touchdown and the first step applies it for a whole Δt
// where the velocity it acts on lags by Δt/2: an early impulse that lowers e
// by about ζ·ωΔt·e; (2) the damper evaluated at the lagging velocity acts
// like a mass m·(1 − ζωΔt), raising ζ to ζ/√(1 − ζωΔt). Tolerance: twice
// their sum (they are estimates to first order) plus (ωΔt)² for the next
// order and the exit inside a step.
struct RestitutionTolerance {
  double early = 0.0, shift = 0.0, total = 0.0;
};
RestitutionTolerance sie_restitution_tolerance(double (*e_of)(double), double zeta, double w_dt) {
  RestitutionTolerance t;
  const double e = e_of(zeta);
  const double zeta_eff = zeta / std::sqrt(1.0 - zeta * w_dt);
  t.shift = std::abs(e_of(zeta_eff) - e);
  t.early = zeta * w_dt * e;
  t.total = 2.0 * (t.early + t.shift) + w_dt * w_dt;
  return t;
}

ClosedFormCase rebound_case(DampingLaw law, double zeta) {
  const bool kv = law == DampingLaw::KelvinVoigt;
  ClosedFormCase cs;
  cs.id = "rebound." +
          std::string(damping_law_name(kv ? DampingLaw::KelvinVoigt : DampingLaw::Compression)) +
          ".zeta" + format_number(zeta, 2);
  cs.name = std::string("rebound, ") + (kv ? "Kelvin–Voigt" : "compression-only damper") +
            ", ζ = " + format_number(zeta, 2);
  const double k = 1e4, m = 1.0;
  Scene& s = cs.scene = base(Shape::PointMass, k, zeta * 2.0 * std::sqrt(k * m), 0.05);
  s.contact.damping = law;
  s.sim.gravity = 0.0;
  s.initial.q = Vec3(0.0, s.half_height - 1e-12, 0.0);
  s.initial.v = Vec3(0.0, -1.0, 0.0);
  const double w_dt = std::sqrt(k / m) * s.sim.dt;  // ω·Δt = 0.01

  ClosedFormQuantity q;
  q.name = "restitution v_out/v_in";
  q.formula =
      kv ? "e^(−ζωt_e)·|cos φ − ζ sin φ/√(1−ζ²)|, φ = ω_d t_e" : "exp(−ζ·atan(√(1−ζ²)/ζ)/√(1−ζ²))";
  double (*const e_of)(double) = kv ? bm::kelvin_voigt_restitution : bm::compression_restitution;
  q.closed_form = e_of(zeta);
  q.extract = [](const Scene& sc, const Trajectory& tr) {
    return last(tr).v.y() / -sc.initial.v.y();
  };
  // Semi-implicit Euler, to first order in ωΔt: sie_restitution_tolerance.
  const double e = q.closed_form;
  const RestitutionTolerance tol = sie_restitution_tolerance(e_of, zeta, w_dt);
  q.tolerance = tol.total;
  q.why = "SIE, first order: early damper impulse ζωΔt·e = " + format_number(tol.early, 2) +
          " + ζ → ζ/√(1−ζωΔt): " + format_number(tol.shift, 2) + "; 2× their sum + (ωΔt)²";
  q.converged_tolerance = 1e-8;
  if (kv) {
    // MuJoCo's Euler is semi-implicit too (same shift); its force is the
    // Kelvin–Voigt force to a relative d·(A/Â − 1) = 5e-5, which moves e
    // by less than that.
    q.mujoco_bound = q.tolerance + 5e-5;
    q.mujoco_bound_derived = true;
    q.mujoco_why = "as the reference + d·(A/Â − 1) = 5e-5";
  } else {
    // MuJoCo's damper acts both ways: it can only do Kelvin–Voigt, so it
    // misses by |e_KV − e_compression| (a finding, not a tolerance).
    q.mujoco_bound = std::abs(bm::kelvin_voigt_restitution(zeta) - e) + q.tolerance + 5e-5;
    q.mujoco_why = "MISS: MuJoCo has no compression-only damper, it gives e_KV = " +
                   format_number(bm::kelvin_voigt_restitution(zeta), 4);
  }
  cs.quantities.push_back(q);
  return cs;
}

ClosedFormCase slide_case() {
  ClosedFormCase cs;
  cs.id = "slide.box";
  cs.name = "box sliding to rest (μ = 0.3, α = 10 s/m, v0 = 1.5 m/s)";
  const double k = 1e5, m = 1.0;
  Scene& s = cs.scene = base(Shape::Box, k, 2.0 * std::sqrt(k * m), 1.5);
  s.contact.mu = 0.3;
  s.contact.alpha = 10.0;
  const double g = s.sim.gravity, mu = s.contact.mu, alpha = s.contact.alpha;
  const double w = s.width, h = s.height, v0 = 1.5;
  s.initial.q = Vec3(0.0, 0.5 * h - bm::rest_depth(m, g, k, 2), 0.0);
  s.initial.v = Vec3(v0, 0.0, 0.0);
  const bm::BoxSlide slide = bm::box_sliding_distance(v0, mu, g, alpha, m, w, h, k);
  const double coulomb = slide.coulomb, tanh_term = slide.tanh, compliance = slide.pitch;

  ClosedFormQuantity q;
  q.name = "distance to rest (m)";
  q.formula = "v0²/(2μg) + π²/(12α²μg) + s_k";
  q.closed_form = slide.distance();
  q.extract = [](const Scene& sc, const Trajectory& tr) {
    return last(tr).q.x() - sc.initial.q.x();
  };
  // Semi-implicit Euler, to first order in Δt: (1) it moves by Δt·v_{n+1},
  // short of the trapezoid rule by Δt·v0/2 over the slide (exact for a
  // constant deceleration); (2) its velocity update is explicit in the tanh
  // tail, whose rate μgα sets a relative error μgα·Δt on the tail term
  // (doubled: an estimate); (3) the compliance term's lag, (c/k)·μgα·|s_k|
  // (tests/core/test_friction.cpp), which the converged solution has too.
  const double lag = s.contact.c / k * mu * g * alpha * std::abs(compliance);
  const double sie = s.sim.dt * v0 / 2.0 + 2.0 * s.sim.dt * mu * g * alpha * tanh_term;
  q.tolerance = sie + lag + 1e-9;
  q.why = "SIE: Δt·v0/2 + 2·μgαΔt·(tanh term) = " + format_number(sie, 2) +
          "; pitch lag (c/k)μgα|s_k| = " + format_number(lag, 2);
  q.converged_tolerance = lag + 1e-9;
  // MuJoCo has no tanh: against this closed form it misses by the tanh
  // term; the next row holds it to Coulomb's law.
  q.mujoco_bound = 1.1 * tanh_term + 2.0 * s.sim.dt * v0;
  q.mujoco_why = "MISS by the tanh term π²/(12α²μg) = " + format_number(tanh_term, 3) +
                 " m, which MuJoCo does not have: its friction is Coulomb's on the cone";
  cs.quantities.push_back(q);

  ClosedFormQuantity coulomb_q;
  coulomb_q.name = "distance to rest, Coulomb (m)";
  coulomb_q.formula = "v0²/(2μg)";
  coulomb_q.closed_form = coulomb;
  coulomb_q.extract = q.extract;
  coulomb_q.reference_applies = false;
  // MuJoCo's Euler moves by Δt·v_{n+1} too (Δt·v0/2 = 7.5e-5 m short);
  // inside the cone its friction is viscous (f_t = impratio·c·v_t per
  // contact), a tail far shorter than Δt·v0. Measured 8.6e-5 m short.
  coulomb_q.mujoco_bound = 2.0 * s.sim.dt * v0;
  coulomb_q.mujoco_why = "SIE's Δt·v0/2 = " + format_number(s.sim.dt * v0 / 2.0, 2) +
                         " m short, doubled; 8.6e-5 m short";
  coulomb_q.why = "MuJoCo only";
  cs.quantities.push_back(coulomb_q);
  return cs;
}

ClosedFormCase roll_case() {
  ClosedFormCase cs;
  cs.id = "roll.disc";
  cs.name = "disc rolling with rolling resistance (μ_roll = 0.01 m, v0 = 1 m/s)";
  const double k = 1e5, m = 1.0;
  Scene& s = cs.scene = base(Shape::Circle, k, 2.0 * std::sqrt(k * m), 2.0);
  s.contact.mu = 0.5;
  s.contact.mu_roll = 0.01;
  s.contact.alpha = 100.0;
  const double g = s.sim.gravity, R = s.radius, alpha = s.contact.alpha, v0 = 1.0;
  s.initial.q = Vec3(0.0, R - bm::rest_depth(m, g, k, 1), 0.0);
  s.initial.v = Vec3(v0, 0.0, -v0 / R);
  const double kappa = bm::kDiscInertiaRatio;  // I = m·R²/2
  const double a = bm::rolling_resistance_deceleration(s.contact.mu_roll, g, R, kappa);

  ClosedFormQuantity dec;
  dec.name = "deceleration over [0.2, 1] s (m/s²)";
  dec.formula = "μ_roll·g/(R·(1 + I/(mR²)))";
  dec.closed_form = a;
  dec.extract = [](const Scene&, const Trajectory& tr) {
    return (at(tr, 0.2).v.x() - at(tr, 1.0).v.x()) / 0.8;
  };
  dec.tolerance = 1e-6 * a;
  dec.why = "constant torque, tanh(αRω) = 1: exact but transient";
  dec.converged_tolerance = 1e-6 * a;
  // MuJoCo's contact point sits p/2 inside the disc (p = m·g/k): lever arm
  // R − p/2, a relative change of p/(2R) = 4.9e-4 in the deceleration's
  // factors; measured 1.3e-4 relative. Bound: 5e-4 relative.
  dec.mujoco_bound = 5e-4 * a;
  dec.mujoco_why =
      "1.3e-4 relative high; lever arm R − p/2 of its contact point: ≲ p/(2R) = 4.9e-4";
  cs.quantities.push_back(dec);

  ClosedFormQuantity dist;
  dist.name = "distance to rest (m)";
  dist.formula = "v0²/(2a) + v_s·v0/(3a) + π²/(12α²a)";
  dist.closed_form = bm::rolling_distance(v0, a, s.contact.mu, g, alpha, kappa);
  dist.extract = [](const Scene& sc, const Trajectory& tr) {
    return last(tr).q.x() - sc.initial.q.x();
  };
  dist.tolerance = 1e-4 + s.sim.dt * v0;
  dist.why = "1e-4 m (tests/core/test_friction.cpp) + SIE Δt·v0";
  dist.converged_tolerance = 1e-4;
  // Measured 1.26e-2 m long (1.6 %). The deceleration agrees to 1.3e-4
  // from 0.2 s on; the difference is made in the first ~60 ms, where
  // MuJoCo's disc hops (the cone's slip term μ·c·|v_t| in the normal force,
  // with the slip of 1.3e-2 to 2.5e-2 m/s its viscous friction needs): off
  // the ground for 12 ms (up to 0.23 mm), then shorter hops. In flight no
  // rolling resistance acts: 7.8e-3 m/s faster at 0.05 s, × the 1.5 s to
  // rest ≈ 12 mm. Bound: 2e-2 m.
  dist.mujoco_bound = 2e-2;
  dist.mujoco_why =
      "MISS, 1.26e-2 m long: the disc hops in the first ~60 ms (12 ms off the "
      "ground at first, the cone's slip term), no rolling resistance in flight: "
      "7.8e-3 m/s faster at 0.05 s; the deceleration then agrees to 1.3e-4";
  cs.quantities.push_back(dist);
  return cs;
}

ClosedFormCase bowling_case() {
  ClosedFormCase cs;
  cs.id = "bowling.disc";
  cs.name = "disc sliding into rolling (μ = 0.3, v0 = 1 m/s, no spin)";
  const double k = 1e5, m = 1.0;
  Scene& s = cs.scene = base(Shape::Circle, k, 2.0 * std::sqrt(k * m), 0.3);
  s.contact.mu = 0.3;
  s.contact.alpha = 100.0;
  s.sim.output_dt = 1e-4;
  const double g = s.sim.gravity, R = s.radius, mu = s.contact.mu, alpha = s.contact.alpha;
  const double v0 = 1.0;
  s.initial.q = Vec3(0.0, R - bm::rest_depth(m, g, k, 1), 0.0);
  s.initial.v = Vec3(v0, 0.0, 0.0);
  const double inertia = 0.5 * m * R * R;
  const double kappa = inertia / (m * R * R);  // I/(m·R²) = ½ for the disc
  const double ratio = m * R * R / inertia;    // 2 for the disc

  ClosedFormQuantity v;
  v.name = "final speed (m/s)";
  v.formula = "v0/(1 + I/(mR²)) = 2v0/3";
  v.closed_form = bm::slide_to_roll_final_speed(v0, 0.0, kappa);
  v.extract = [](const Scene&, const Trajectory& tr) { return last(tr).v.x(); };
  v.tolerance = 1e-11;
  v.why = "I·ω − m·R·v conserved by the step: rounding";
  v.converged_tolerance = 10.0 * kConvergedTol;
  v.mujoco_bound = 3e-4;
  v.mujoco_why =
      "1.3e-4 m/s slow: contact point p/2 inside the disc, lever arm R − p/2 "
      "(first-order estimate 2.2e-4 m/s)";
  cs.quantities.push_back(v);

  ClosedFormQuantity t;
  const double u_th = 0.01;
  t.name = "time until the slip is 0.01 m/s (s)";
  t.formula = "ln(sinh(αv0)/sinh(αu))/((1 + mR²/I)μgα)";
  t.closed_form =
      bm::tanh_sliding_time(v0, u_th, bm::slide_to_roll_slip_deceleration(mu, g, kappa), alpha);
  t.extract = [u_th](const Scene& sc, const Trajectory& tr) { return slip_time(sc, tr, u_th); };
  // Read by linear interpolation between samples Δs = output_dt apart:
  // error ≤ (Δs²/8)·|ü/u̇| ≤ (Δs²/8)·(1 + mR²/I)·μgα. The reference's slip
  // is forward Euler in the tanh zone, whose rate (1 + mR²/I)·μgα·Δt = 0.09
  // is small: its time error is a fraction of a step; tolerance Δt.
  const double interpolation =
      s.sim.output_dt * s.sim.output_dt / 8.0 * (1.0 + ratio) * mu * g * alpha;
  t.tolerance = s.sim.dt + interpolation;
  t.why = "forward-Euler slip in the tanh zone: Δt; interpolation " +
          format_number(interpolation, 2) + " s";
  t.converged_tolerance = interpolation;
  t.mujoco_bound = 1e-3;
  t.mujoco_why = "6.1e-4 s late: no tanh, viscous friction inside the cone";
  cs.quantities.push_back(t);
  return cs;
}

// A disc thrown at the ground without gravity, at v_in = 1 m/s down, with
// v_x = 1 m/s and backspin ω > 0 (slip u = v_x + ω·R at the contact point),
// Kelvin–Voigt at ζ = 0.3: one impact, normal impulse P = m·(1 + e)·v_in
// with the rebound case's e (the normal force acts through the centre, so
// friction does not change it), and Coulomb friction's impulse balance on
// the slip (benchmarks::spin_impact):
//   sliding through  (u > 3·μ·P/m):  v_x′ = v_x − μ·P/m,  R·ω′ = R·ω − 2·μ·P/m
//   rolling out      (u ≤ 3·μ·P/m):  v_x′ = v_x − u/3,    R·ω′ = R·ω − 2·u/3 (u′ = 0)
// `rolls`: ω = 5 rad/s (u = 1.5 m/s, stops slipping during the impact);
// otherwise ω = 30 rad/s (u = 4 m/s, still 1.8 m/s after it).
ClosedFormCase backspin_case(bool rolls) {
  ClosedFormCase cs;
  cs.id = rolls ? "backspin.rolls_out" : "backspin.slides";
  cs.name = std::string("disc bouncing with backspin, Coulomb impulse (μ = 0.5, ζ = 0.3, ") +
            (rolls ? "ω = 5 rad/s: rolls out)" : "ω = 30 rad/s: slides through)");
  const double k = 1e4, m = 1.0, zeta = 0.3;
  Scene& s = cs.scene = base(Shape::Circle, k, zeta * 2.0 * std::sqrt(k * m), 0.05);
  s.contact.mu = 0.5;
  s.contact.alpha = 100.0;
  s.sim.gravity = 0.0;
  const double R = s.radius, mu = s.contact.mu, v_in = 1.0, vx = 1.0;
  const double omega = rolls ? 5.0 : 30.0;
  s.initial.q = Vec3(0.0, R - 1e-12, 0.0);
  s.initial.v = Vec3(vx, -v_in, omega);
  const double e = bm::kelvin_voigt_restitution(zeta);
  const double impulse = bm::impact_normal_impulse(m, e, v_in);  // P
  const bm::SpinImpact after =
      bm::spin_impact(vx, omega * R, impulse, m, mu, bm::kDiscInertiaRatio);
  if (rolls != after.rolls)
    throw std::logic_error(cs.id + ": the case does not do what its name says");
  // The rebound case's tolerance on e (semi-implicit Euler at ωΔt = 0.01),
  // carried through P: δv_x = μ·v_in·δe, δ(Rω) = 2μ·v_in·δe while sliding.
  // Rolling out does not depend on P at all (once stuck, the friction
  // impulse is the slip's momentum m·u/3); the tanh law leaves a slip
  // remainder ~(1/α)·exp(−3μα·P_rest/m), P_rest = 0.45 N·s after sticking:
  // e^(−67), nothing. The step itself: friction is explicit in the slip
  // (forward Euler, rate 3μα·Fn/m ≤ 1.5/Δt at the peak force), exact in the
  // impulse sum but not in where the slip stops: bounded by Δt·(its rate
  // μ·Fn_peak·3/m)·(1/α) ≈ 1.5e-2 m/s … measured and stated below.
  const double w_dt = std::sqrt(k / m) * s.sim.dt;
  const double tol_e = sie_restitution_tolerance(bm::kelvin_voigt_restitution, zeta, w_dt).total;
  for (int which = 0; which < 2; ++which) {
    ClosedFormQuantity q;
    q.name = which == 0 ? "v_x after the bounce (m/s)" : "R·ω after the bounce (m/s)";
    q.formula = rolls ? (which == 0 ? "v_x − u/3" : "R·ω − 2u/3")
                      : (which == 0 ? "v_x − μ(1+e)v_in" : "R·ω − 2μ(1+e)v_in");
    q.closed_form = which == 0 ? after.vx : after.rim;
    if (which == 0)
      q.extract = [](const Scene&, const Trajectory& tr) { return last(tr).v.x(); };
    else
      q.extract = [](const Scene& sc, const Trajectory& tr) { return last(tr).v.z() * sc.radius; };
    const double factor = which == 0 ? mu * v_in : 2.0 * mu * v_in;
    if (rolls) {
      // Measured: the reference 1.1e-16 / 1.7e-16 m/s off, the converged
      // solution 2.2e-16 / 3.3e-16 (stuck: the slip decays to rounding
      // before the force ends); bound 1e-6 m/s, a stated margin over that.
      q.tolerance = 1e-6;
      q.why = "stuck: the impulse is m·u/3 whatever P; tanh's remainder e^(−67)";
      q.converged_tolerance = 1e-6;
    } else {
      q.tolerance = factor * tol_e;
      q.why = "the rebound's SIE tolerance on e × " + std::string(which == 0 ? "μ" : "2μ") +
              "·v_in = " + format_number(q.tolerance, 2);
      q.converged_tolerance = factor * 1e-8;
    }
    cs.quantities.push_back(q);
  }
  // MuJoCo, measured (the MISS bounds about 1.5 × that):
  //   slides     v_x′ 0.047 m/s and R·ω′ 0.077 m/s low: the push μ·c·|u| of
  //              its cone (docs/mujoco.md) raises the normal impulse — it
  //              leaves at v_y′ = 0.545 m/s instead of e·v_in = 0.449 — and
  //              the friction impulse with it; the reference under
  //              friction_law = "soft_cone" reproduces MuJoCo's v_x′ to 2e-5.
  //   rolls out  v_x′ 7.6e-3 m/s low, R·ω′ 2.1e-3 m/s high: not the push (once
  //              stuck the impulse is m·u/3 whatever the normal impulse) but
  //              MuJoCo's contact point, halfway into the penetration: the
  //              friction acts at R − p/2 (p up to v_in/ω_n = 1 cm), so the
  //              slip it stops is that of a point p/2 inside the rim.
  const double bounds[2][2] = {{0.07, 0.12}, {1.2e-2, 4e-3}};
  for (int which = 0; which < 2; ++which) {
    ClosedFormQuantity& q = cs.quantities[static_cast<size_t>(which)];
    q.mujoco_bound = bounds[rolls ? 1 : 0][which];
    q.mujoco_why = rolls ? "MISS: its contact point sits p/2 inside the rim (lever R − p/2 while "
                           "it sticks)"
                         : "MISS: the cone's push μ·c·|u| raises the normal impulse, and the "
                           "friction impulse with it";
  }
  return cs;
}

// A box on a capsule inclined at `degrees`, COM placed at the equilibrium
// depth with its bottom face on the slope, launched at v0 down the slope.
ClosedFormCase slope_case(double degrees, double mu, double v0) {
  ClosedFormCase cs;
  const bool slides = std::tan(degrees * kPi / 180.0) > mu;
  cs.id = slides ? "slope.slides" : "slope.rests";
  cs.name = "box on a " + format_number(degrees, 3) + "° slope, μ = " + format_number(mu, 2) +
            (slides ? " (slides)" : " (holds)");
  const double k = 1e5, m = 1.0;
  Scene& s = cs.scene = base(Shape::Box, k, 2.0 * std::sqrt(k * m), slides ? 0.4 : 0.5);
  s.contact.mu = mu;
  s.contact.alpha = 100.0;
  const double th = degrees * kPi / 180.0, g = s.sim.gravity, r = 0.05;
  const Vec2 u(std::cos(th), std::sin(th)), n(-std::sin(th), std::cos(th));
  const Vec2 p0(0.0, 1.0);
  s.obstacles.push_back(make_segment_obstacle(p0 - u, p0 + u, r));
  const double depth = bm::slope_rest_depth(m, g, th, k, 2);
  const Vec2 c = p0 + 0.3 * u + (r + 0.5 * s.height - depth) * n;
  cs.slope_frame = SlopeFrame{th, p0 + r * n};
  s.initial.q = Vec3(c.x(), c.y(), th);
  s.initial.v = Vec3(-v0 * u.x(), -v0 * u.y(), 0.0);
  const Vec2 down = -u;

  ClosedFormQuantity q;
  if (slides) {
    q.name = "acceleration down the slope, fitted over [0.1, 0.4] s (m/s²)";
    q.formula = "g·(sinθ − μ·cosθ)";
    q.closed_form = bm::slope_sliding_acceleration(g, th, mu);
    q.extract = [down](const Scene&, const Trajectory& tr) {
      return fitted_acceleration(tr, down, 0.1, 0.4);
    };
    // tanh(αv) = 1 to 1e-43 at v ≥ 0.5 m/s; the load shift between the
    // corners that friction causes starts a pitch transient that decays at
    // ω ≥ 300 /s (ζ ≈ 1), e^(−30) by t = 0.1 s; semi-implicit Euler is exact
    // for a constant acceleration: rounding, 1e-9 relative.
    q.tolerance = 1e-9 * q.closed_form;
    q.why = "constant acceleration, tanh(αv) = 1, transient e^(−30): rounding";
    // Dormand–Prince at tol 1e-10 in the slope's frame: positions to ~1e-9 m,
    // a parabola fitted over 0.3 s moves by ~1e-9/0.3² m/s²; bound 1e-7.
    q.converged_tolerance = 1e-7;
    // Measured 5.6e-3 m/s² (0.24 %) slower: MuJoCo's box rattles on the
    // slope (it rises up to 0.7 mm off its rest depth and rocks at ±0.5
    // rad/s: the cone's slip term μ·c·|v_t| in the normal force, docs/
    // mujoco.md). Bound: about twice the measurement, 1.2e-2 m/s².
    q.mujoco_bound = 1.2e-2;
    q.mujoco_why =
        "MISS, 0.24 % slower: the box rattles and hops on the slope (the "
        "cone's slip term μ·c·|v_t| pushes it off)";
  } else {
    q.name = "creep speed down the slope over [0.3, 0.5] s (m/s)";
    q.formula = "atanh(tanθ/μ)/α (Coulomb: 0)";
    q.closed_form = bm::tanh_creep_speed(th, mu, s.contact.alpha);
    q.extract = [down](const Scene&, const Trajectory& tr) {
      const Vec3 a = at(tr, 0.3).q, b = at(tr, 0.5).q;
      return ((b.x() - a.x()) * down.x() + (b.y() - a.y()) * down.y()) / 0.2;
    };
    // Steady creep: μ·Fn·tanh(αv) summed over both corners (same v) is
    // μ·m·g·cosθ·tanh(αv) = m·g·sinθ exactly; the transient relaxes at
    // μgα·cosθ·(1 − (tanθ/μ)²) = 338 /s, gone (e^(−100)) by t = 0.3 s.
    // Rounding: 1e-9 relative.
    q.tolerance = 1e-9 * q.closed_form;
    q.why = "steady creep, transient e^(−100): rounding";
    // Dormand–Prince at tol 1e-10: positions to ~1e-9 m over 0.2 s; bound 1e-8 m/s.
    q.converged_tolerance = 1e-8;
    // MuJoCo's own law gives a creep of its own (next row); against this
    // one it misses by most of it.
    q.mujoco_bound = q.closed_form;
    q.mujoco_why = "MISS: MuJoCo creeps at its own viscous speed (next row), not the tanh law's";
    // MuJoCo's own creep: its tangential rows inside the elliptic cone are
    // viscous, and at steady creep (qacc = 0) each of the N·n contacts
    // carries impratio·c·v/(n·(1 − d)), whatever the true inverse mass
    // (benchmarks::soft_constraint_creep_speed derives it): v = (1 − d)·m·g·
    // sinθ/(N·impratio·c) exactly. Bound: rounding and the transient, which
    // relaxes at N·impratio·c/m = 5e3 /s.
    const MujocoConstants mj = mujoco_constants(s);
    const int contacts = 2;  // the bottom corners
    ClosedFormQuantity own;
    own.name = "MuJoCo's own creep speed (m/s)";
    own.formula = "(1−d)·m·g·sinθ/(N·impratio·c)";
    own.closed_form =
        bm::soft_constraint_creep_speed(m, g, th, contacts, mj.impratio, s.contact.c, mj.impedance);
    own.extract = q.extract;
    own.reference_applies = false;
    own.mujoco_bound = 1e-6 * own.closed_form;
    own.mujoco_bound_derived = true;
    own.mujoco_why = "steady creep, qacc = 0: rounding, 1e-6 relative (impratio = " +
                     format_number(mj.impratio, 4) + ")";
    own.why = "MuJoCo only";
    own.converged_tolerance = kNaN;
    cs.quantities.push_back(q);
    q = own;
  }
  cs.quantities.push_back(q);
  return cs;
}

// The dense solution sampled at the scene's output times.
Trajectory sampled(const Scene& scene, const DenseTrajectory& dense) {
  Trajectory out;
  for (double t : output_times(scene.sim)) out.samples.push_back({t, dense.at(t)});
  return out;
}

// The converged solution of a slope case in its own frame (SlopeFrame),
// mapped back to the world frame.
Trajectory converged_on_slope(const Scene& scene, const SlopeFrame& f) {
  const Vec2 u(std::cos(f.theta), std::sin(f.theta)), n(-std::sin(f.theta), std::cos(f.theta));
  Scene flat = scene;
  flat.obstacles.clear();
  flat.sim.gravity = scene.sim.gravity * std::cos(f.theta);
  Model model = make_model(flat);
  model.applied = Vec3(-scene.mass * scene.sim.gravity * std::sin(f.theta), 0.0, 0.0);
  const Vec2 p = scene.initial.q.head<2>() - f.origin, v = scene.initial.v.head<2>();
  State initial;
  initial.q = Vec3(p.dot(u), p.dot(n), scene.initial.q.z() - f.theta);
  initial.v = Vec3(v.dot(u), v.dot(n), scene.initial.v.z());
  DenseOptions options;
  options.rtol = options.atol = kConvergedTol;
  const DenseTrajectory dense = integrate_dense(model, initial, scene.sim.duration, options);
  if (!dense.ok()) throw std::runtime_error("converged solution on the slope: " + dense.failure());
  Trajectory out;
  for (double t : output_times(scene.sim)) {
    const State s = dense.at(t);
    State w;
    w.q.head<2>() = f.origin + s.q.x() * u + s.q.y() * n;
    w.q.z() = s.q.z() + f.theta;
    w.v.head<2>() = s.v.x() * u + s.v.y() * n;
    w.v.z() = s.v.z();
    out.samples.push_back({t, w});
  }
  return out;
}

}  // namespace

std::vector<ClosedFormCase> closed_form_cases() {
  std::vector<ClosedFormCase> cases;
  cases.push_back(static_case(Shape::PointMass));
  cases.push_back(static_case(Shape::Box));
  for (DampingLaw law : {DampingLaw::KelvinVoigt, DampingLaw::Compression}) {
    for (double zeta : {0.1, 0.3}) cases.push_back(rebound_case(law, zeta));
  }
  cases.push_back(slide_case());
  cases.push_back(roll_case());
  cases.push_back(bowling_case());
  cases.push_back(backspin_case(false));
  cases.push_back(backspin_case(true));
  cases.push_back(slope_case(30.0, 0.3, 0.5));
  cases.push_back(slope_case(15.0, 0.5, 0.0));
  return cases;
}

ClosedFormTable closed_form_table(unsigned threads, const std::string& mujoco_engine) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ClosedFormCase> cases = closed_form_cases();
  struct Runs {
    EngineRun ref, mj;
    Trajectory converged;
    std::string note;
  };
  std::vector<Runs> runs(cases.size());
  // One task per (case, engine): 3·cases tasks, the MuJoCo ones the longest.
  parallel_for(3 * cases.size(), threads, [&](size_t i) {
    const ClosedFormCase& c = cases[i / 3];
    Runs& r = runs[i / 3];
    switch (i % 3) {
      case 0: r.mj = engines::run_engine(mujoco_engine, c.scene); break;
      case 1: r.ref = engines::run_engine("ref", c.scene); break;
      default:
        if (c.slope_frame) {
          r.converged = converged_on_slope(c.scene, *c.slope_frame);
          break;
        }
        if (!c.converged_available) {
          r.note = "no converged solution for this scene";
          break;
        }
        const DenseTrajectory dense = converged_reference(c.scene, kConvergedTol);
        if (!dense.ok())
          throw std::runtime_error(c.id + ": converged solution: " + dense.failure());
        r.converged = sampled(c.scene, dense);
    }
  });
  ClosedFormTable table;
  for (size_t i = 0; i < cases.size(); ++i) {
    const ClosedFormCase& c = cases[i];
    const Runs& r = runs[i];
    for (const EngineRun* run : {&r.ref, &r.mj}) {
      if (run->trajectory.divergence)
        throw std::runtime_error(c.id + ": " + run->engine +
                                 " diverged: " + run->divergence_message);
    }
    table.reference_engine = r.ref.description;
    table.mujoco_engine = r.mj.description;
    for (const ClosedFormQuantity& q : c.quantities) {
      ClosedFormRow row;
      row.case_id = c.id;
      row.case_name = c.name;
      row.quantity = q;
      if (q.reference_applies) row.reference = q.extract(c.scene, r.ref.trajectory);
      row.mujoco = q.extract(c.scene, r.mj.trajectory);
      if (c.converged_available && q.reference_applies)
        row.converged = q.extract(c.scene, r.converged);
      row.converged_note = r.note;
      table.rows.push_back(row);
    }
  }
  table.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return table;
}

}  // namespace contact2d::analysis
