#include "reference/dense_reference.hpp"

#include "core/ellipse.hpp"

#include "core/cancel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace contact2d {
namespace {

// Dormand–Prince 5(4) (Hairer, Nørsett & Wanner, Solving ODEs I, §II.5/II.6).
// The nodes c = (1/5, 3/10, 4/5, 8/9, 1, 1) are not needed: the right-hand
// side does not depend on t (applied forces are constant over a run).
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                 a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784,
                 a76 = 11.0 / 84;
// Error coefficients b − b̂.
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;
// Continuous extension (Hairer's CONTD5).
constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                 d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                 d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;

// Step-size control: standard safety factor and bounds on the change ratio.
constexpr double kSafety = 0.9;
constexpr double kFacMin = 0.2;
constexpr double kFacMax = 10.0;
// Consecutive zero-length mode flips at one instant before the flipping stops
// and the function is resolved instead (see find_event and resolve_chatter).
constexpr int kMaxZeroLengthFlips = 8;
constexpr double kEps = std::numeric_limits<double>::epsilon();

Vec6 interpolate(const Vec6 (&r)[5], double s) {
  const double s1 = 1.0 - s;
  return r[0] + s * (r[1] + s1 * (r[2] + s * (r[3] + s1 * r[4])));
}

// d/dt of the continuous extension (h = step length).
Vec6 interpolate_rate(const Vec6 (&r)[5], double s, double h) {
  const double s1 = 1.0 - s;
  const Vec6 c = r[3] + s1 * r[4];
  const Vec6 b = r[2] + s * c;
  const Vec6 a = r[1] + s1 * b;
  const Vec6 db = c - s * r[4];
  const Vec6 da = -b + s1 * db;
  return (a + s * da) / h;
}

// The body, its contact law and the mode bits of its contact points.
class System {
 public:
  explicit System(const Model& model)
      : model_(model), n_(model.body.points.size()), contact_(n_, 0), active_(n_, 0) {}

  size_t points() const { return n_; }
  size_t functions() const { return 2 * n_; }
  bool contact(size_t i) const { return contact_[i] != 0; }
  bool active(size_t i) const { return active_[i] != 0; }
  void set_contact(size_t i, bool on) { contact_[i] = on ? 1 : 0; }
  void set_active(size_t i, bool on) { active_[i] = on ? 1 : 0; }
  // Function j < n: contact of point j; j ≥ n: damper/force of point j − n,
  // watched only while that point is in contact.
  bool monitored(size_t j) const { return j < n_ || contact_[j - n_] != 0; }
  bool bit(size_t j) const { return j < n_ ? contact_[j] != 0 : active_[j - n_] != 0; }

  // Right-hand side on the smooth branch of the current mode.
  void rhs(const Vec6& y, Vec6& dy) const {
    const RigidBody& body = model_.body;
    const ContactParams& law = model_.contact;
    const ShapeFeatures features = shape_features(body.shape);
    // A disc's point stays below the centre, an ellipse's is its lowest
    // point (core/ellipse.hpp); a rolling law adds resistance.
    const bool rolls = features.resists_rolling && law.mu_roll > 0.0;
    double cos_t = 1.0, sin_t = 0.0;
    if (!features.rolls && !features.smooth) {
      cos_t = std::cos(y[2]);
      sin_t = std::sin(y[2]);
    }
    double fx = model_.applied.x();
    double fy = model_.applied.y() - body.mass * model_.gravity;
    double torque = model_.applied.z();
    for (size_t i = 0; i < n_; ++i) {
      if (!contact_[i]) continue;
      const Vec2 r = lever(i, y, cos_t, sin_t);
      const double rx = r.x();
      const double ry = r.y();
      const double depth = -(y[1] + ry);
      if (law.friction == FrictionLaw::SoftCone) {
        // The core's soft-cone law (core/contact.hpp) at MuJoCo's contact
        // point, halfway into the penetration; no mode: the law clamps
        // itself, continuously (its kinks are not located, see
        // point_functions).
        const double ry_mid = ry + 0.5 * depth;
        const ConeForce f = soft_cone_force(law, normal_aim(law, depth, y[4] + y[5] * rx),
                                            y[3] - y[5] * ry_mid, rolls ? y[5] : 0.0);
        fx += f.ft;
        fy += f.fn;
        torque += rx * f.fn - ry_mid * f.ft + f.roll;
        continue;
      }
      const double vcx = y[3] - y[5] * ry;
      const double vcy = y[4] + y[5] * rx;
      double fn = law.k * depth;
      if (law.damping == DampingLaw::Compression) {
        if (active_[i]) fn -= law.c * vcy;
      } else {
        fn = active_[i] ? fn - law.c * vcy : 0.0;
      }
      if (law.friction == FrictionLaw::ViscousCone) {
        const ConeForce f = viscous_cone_force(law, fn, vcx, rolls ? y[5] : 0.0);
        fx += f.ft;
        fy += fn;
        torque += rx * fn - ry * f.ft + f.roll;
        continue;
      }
      const double ft = friction_force(law, fn, vcx);
      fx += ft;
      fy += fn;
      torque += rx * fn - ry * ft +
                (features.resists_rolling ? rolling_torque(law, fn, body.roll_radius, y[5]) : 0.0);
    }
    dy.head<3>() = y.tail<3>();
    dy[3] = fx / body.mass;
    dy[4] = fy / body.mass;
    dy[5] = (features.turns && body.inertia > 0.0) ? torque / body.inertia : 0.0;
  }

  // Switching functions of point i (positive = on) and their time rates
  // along a path with state y and rate ydot:
  //   contact  g = −c_y                       ġ = −ċ_y
  //   damper   g = −v_c,y (compression)       ġ = −v̇_c,y
  //            g = k·d − c·v_c,y (Kelvin–Voigt)
  void point_functions(size_t i, const Vec6& y, const Vec6* ydot, double& g_contact,
                       double& g_active, double& rate_contact, double& rate_active) const {
    const RigidBody& body = model_.body;
    const ContactParams& law = model_.contact;
    const ShapeFeatures features = shape_features(body.shape);
    // A disc's point stays below the centre; an ellipse's is its lowest
    // point; every other body's turns with θ.
    const bool points_turn = !features.rolls;
    double cos_t = 1.0, sin_t = 0.0;
    if (points_turn && !features.smooth) {
      cos_t = std::cos(y[2]);
      sin_t = std::sin(y[2]);
    }
    const Vec2 r = lever(i, y, cos_t, sin_t);
    const double rx = r.x(), ry = r.y();
    const double cy = y[1] + ry;
    const double vcy = y[4] + y[5] * rx;
    g_contact = -cy;
    g_active = law.damping == DampingLaw::Compression ? -vcy : -law.k * cy - law.c * vcy;
    rate_contact = rate_active = 0.0;
    // The soft cone has no damper mode: its force is continuous where the
    // damper, the push or stick ↔ slide switch (a kink, not a jump), so only
    // entry and exit are events; the step control takes the kinks.
    if (law.friction == FrictionLaw::SoftCone) g_active = 1.0;
    if (!ydot) return;
    const Vec6& yd = *ydot;
    const double spin = points_turn ? yd[2] : 0.0;  // dθ/dt moving the point
    const double cy_rate = yd[1] + spin * rx;
    // The lever arm's own rate: −ω·r_y for a body point, the lowest
    // point's dr_x/dθ·θ̇ for an ellipse (core/ellipse.hpp).
    const double vcy_rate =
        features.smooth
            ? yd[4] + yd[5] * rx +
                  y[5] * spin *
                      ellipse_lowest_point_turn_rate(body.semi_axes.x(), body.semi_axes.y(), y[2])
            : yd[4] + yd[5] * rx - y[5] * spin * ry;
    rate_contact = -cy_rate;
    rate_active = law.friction == FrictionLaw::SoftCone    ? 0.0
                  : law.damping == DampingLaw::Compression ? -vcy_rate
                                                           : -law.k * cy_rate - law.c * vcy_rate;
  }

  // Signed switching function of j: ≥ 0 while consistent with its mode bit.
  double signed_value(size_t j, const Vec6& y, const Vec6* ydot, double* rate) const {
    double gc, ga, rc, ra;
    const size_t i = j < n_ ? j : j - n_;
    point_functions(i, y, ydot, gc, ga, rc, ra);
    const double g = j < n_ ? gc : ga;
    const double sign = bit(j) ? 1.0 : -1.0;
    if (rate) *rate = sign * (j < n_ ? rc : ra);
    return sign * g;
  }

  // Mode read from the state itself, as acceleration() decides it.
  void mode_from_state(const Vec6& y) {
    for (size_t i = 0; i < n_; ++i) {
      double gc, ga, rc, ra;
      point_functions(i, y, nullptr, gc, ga, rc, ra);
      contact_[i] = gc > 0.0 ? 1 : 0;
      active_[i] = (gc > 0.0 && ga > 0.0) ? 1 : 0;
    }
  }

 private:
  // Lever arm of contact point i at state y ((cos_t, sin_t) of θ, or of 0
  // for a disc and an ellipse, whose points do not turn with the body).
  Vec2 lever(size_t i, const Vec6& y, double cos_t, double sin_t) const {
    const RigidBody& body = model_.body;
    if (shape_features(body.shape).smooth)
      return ellipse_lowest_point(body.semi_axes.x(), body.semi_axes.y(), y[2]);
    const Vec2& local = body.points[i];
    return {cos_t * local.x() - sin_t * local.y(), sin_t * local.x() + cos_t * local.y()};
  }

  const Model& model_;
  size_t n_;
  std::vector<unsigned char> contact_;
  std::vector<unsigned char> active_;
};

Vec6 pack(const State& s) {
  Vec6 y;
  y << s.q, s.v;
  return y;
}

State unpack(const Vec6& y) {
  State s;
  s.q = y.head<3>();
  s.v = y.tail<3>();
  return s;
}

// One Dormand–Prince step of length h from (y0, k1) with the mode frozen.
struct StepResult {
  Vec6 y1;
  Vec6 k[7];           // k[0] = f(y0), …, k[6] = f(y1)
  double error = 0.0;  // scaled RMS error estimate; ≤ 1 accepts
};

void dopri_step(const System& sys, const Vec6& y0, const Vec6& f0, double h, double rtol,
                double atol, StepResult& out) {
  Vec6* k = out.k;
  k[0] = f0;
  sys.rhs(y0 + h * (a21 * k[0]), k[1]);
  sys.rhs(y0 + h * (a31 * k[0] + a32 * k[1]), k[2]);
  sys.rhs(y0 + h * (a41 * k[0] + a42 * k[1] + a43 * k[2]), k[3]);
  sys.rhs(y0 + h * (a51 * k[0] + a52 * k[1] + a53 * k[2] + a54 * k[3]), k[4]);
  sys.rhs(y0 + h * (a61 * k[0] + a62 * k[1] + a63 * k[2] + a64 * k[3] + a65 * k[4]), k[5]);
  out.y1 = y0 + h * (a71 * k[0] + a73 * k[2] + a74 * k[3] + a75 * k[4] + a76 * k[5]);
  sys.rhs(out.y1, k[6]);
  const Vec6 err = h * (e1 * k[0] + e3 * k[2] + e4 * k[3] + e5 * k[4] + e6 * k[5] + e7 * k[6]);
  double sum = 0.0;
  for (int i = 0; i < 6; ++i) {
    const double scale = atol + rtol * std::max(std::abs(y0[i]), std::abs(out.y1[i]));
    const double e = err[i] / scale;
    sum += e * e;
  }
  out.error = std::sqrt(sum / 6.0);
}

void dense_coefficients(const Vec6& y0, const StepResult& s, double h, Vec6 (&r)[5]) {
  const Vec6 ydiff = s.y1 - y0;
  const Vec6 bspl = h * s.k[0] - ydiff;
  r[0] = y0;
  r[1] = ydiff;
  r[2] = bspl;
  r[3] = ydiff - h * s.k[6] - bspl;
  r[4] = h * (d1 * s.k[0] + d3 * s.k[2] + d4 * s.k[3] + d5 * s.k[4] + d6 * s.k[5] + d7 * s.k[6]);
}

// Root of φ on [a, b] with φ(a) > 0 ≥ φ(b) (Illinois variant of regula falsi,
// ending in bisection when it stalls). Returns b of the final bracket: the
// first point known to be past the crossing.
template <typename F>
double bracket_root(F phi, double a, double fa, double b, double fb) {
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    if (b - a <= 4.0 * kEps * std::max(1.0, std::abs(b))) break;
    double m = (fa * b - fb * a) / (fa - fb);
    if (!(m > a && m < b) || it % 8 == 7) m = 0.5 * (a + b);
    const double fm = phi(m);
    if (fm > 0.0) {
      a = m;
      fa = fm;
      if (side == 1) fb *= 0.5;
      side = 1;
    } else {
      b = m;
      fb = fm;
      if (side == -1) fa *= 0.5;
      side = -1;
    }
  }
  return b;
}

struct Event {
  double s = 0.0;  // position in the step, [0, 1]; 0 = at its start
  size_t function = 0;
  // The function is on its wrong side at both ends of the step after the
  // zero-length flips ran out, and the step shows no point where the current
  // mode is consistent: the step must not be accepted (see resolve_chatter).
  bool unresolved = false;
};

// After kMaxZeroLengthFlips zero-length flips of function j at the step's
// start, with φ(0) ≤ 0 and φ(1) < 0 (φ = signed value under the current
// mode on the continuous extension). The flips chatter because at the start
// φ is zero to rounding, so both modes see themselves "already past" it. The
// rate φ̇(0) is that of the true solution there (every switching function's
// time derivative is the same in both modes on its surface, header), so it
// decides which side the solution actually leaves to:
//   φ̇(0) > 0: into the current mode's side. φ(0) ≤ 0 is rounding at the
//     surface (e.g. the step redone up to an exit stops one ulp short of
//     it); the mode is right, and φ(1) < 0 means the function comes back
//     within the step: a genuine crossing after an interior maximum. Locate
//     the maximum (root of φ̇ on the continuous extension) and the crossing
//     after it, exactly like the grazing test does for a minimum.
//   otherwise, or no interior point with φ > 0: this step offers no stretch
//     where the current mode is consistent. Returned as unresolved: the step
//     is rejected and halved, so the search repeats on ever shorter steps
//     (a shorter step separates a crossing from the start or exposes the
//     maximum that a long one hides). If the step underflows first the
//     integration fails, naming time, point and function.
template <typename Phi, typename Rate>
Event resolve_chatter(size_t j, Phi phi, Rate rate, double rate0, double rate1, double s1) {
  const Event unresolved{0.0, j, true};
  if (!(rate0 > 0.0) || !(rate1 < 0.0)) return unresolved;
  const double m = bracket_root(rate, 0.0, rate0, 1.0, rate1);
  const double fm = phi(m);
  if (!(fm > 0.0)) return unresolved;
  return Event{bracket_root(phi, m, fm, 1.0, s1), j, false};
}

// Earliest switching-function crossing inside the step [t, t + h], on the
// continuous extension r. s_start/s_end and the rates are evaluated from the
// exact end states (y0, f0) and (y1, f1).
std::optional<Event> find_event(const System& sys, const Vec6& y0, const Vec6& f0, const Vec6& y1,
                                const Vec6& f1, const Vec6 (&r)[5], double h,
                                bool allow_start_events) {
  std::optional<Event> best;
  for (size_t j = 0; j < sys.functions(); ++j) {
    if (!sys.monitored(j)) continue;
    double rate0 = 0.0, rate1 = 0.0;
    const double s0 = sys.signed_value(j, y0, &f0, &rate0);
    const double s1 = sys.signed_value(j, y1, &f1, &rate1);
    auto phi = [&](double s) {
      const Vec6 y = interpolate(r, s);
      return sys.signed_value(j, y, nullptr, nullptr);
    };
    auto rate = [&](double s) {
      const Vec6 y = interpolate(r, s);
      const Vec6 yd = interpolate_rate(r, s, h);
      double v = 0.0;
      sys.signed_value(j, y, &yd, &v);
      return v;
    };
    double a = 0.0, fa = s0;
    double b = 1.0, fb = s1;
    if (s1 < 0.0) {
      if (s0 <= 0.0) {
        // Already on the far side at the start: a tangency the last flip got
        // the wrong way round, or rounding right at the surface.
        if (allow_start_events) return Event{0.0, j};
        // The flips chatter: never accept the step as it is.
        const Event e = resolve_chatter(j, phi, rate, rate0, rate1, s1);
        if (e.unresolved) return e;
        if (!best || e.s < best->s) best = e;
        continue;
      }
    } else if (s0 > 0.0 && rate0 < 0.0 && rate1 > 0.0) {
      // Consistent at both ends but dipping in between: find the interior
      // minimum (root of the rate on the continuous extension).
      // bracket_root wants φ(a) > 0: use −rate.
      const double m = bracket_root([&](double s) { return -rate(s); }, 0.0, -rate0, 1.0, -rate1);
      const double fm = phi(m);
      if (!(fm < 0.0)) continue;
      b = m;
      fb = fm;
    } else {
      continue;
    }
    const double root = bracket_root(phi, a, fa, b, fb);
    if (!best || root < best->s) best = Event{root, j};
  }
  return best;
}

double initial_step(const System& sys, const Vec6& y0, const Vec6& f0, double rtol, double atol,
                    double h_max, long long& evaluations) {
  auto norm = [&](const Vec6& v) {
    double sum = 0.0;
    for (int i = 0; i < 6; ++i) {
      const double e = v[i] / (atol + rtol * std::abs(y0[i]));
      sum += e * e;
    }
    return std::sqrt(sum / 6.0);
  };
  const double dn0 = norm(y0), dn1 = norm(f0);
  double h0 = (dn0 < 1e-5 || dn1 < 1e-5) ? 1e-6 : 0.01 * dn0 / dn1;
  h0 = std::min(h0, h_max);
  Vec6 f1;
  sys.rhs(y0 + h0 * f0, f1);
  ++evaluations;
  const double dn2 = norm(f1 - f0) / h0;
  const double dmax = std::max(dn1, dn2);
  const double h1 = dmax <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dmax, 0.2);
  return std::min({100.0 * h0, h1, h_max});
}

// Under the soft cone a sliding point's normal force at zero depth is the
// push alone, c·s/(1 + μ²/impratio) with s = √((μ·v_t)² + (μ_roll·ω)²)
// (core/contact.hpp): the force jumps from 0 to it as the point touches.
// When it lifts the point faster than the point falls without it, the
// contact has no consistent mode at the surface: in contact the point is
// pushed out, out of contact it falls back, at every step however short
// (fixed steps hop there, lower and more often the shorter the step: the
// hops' limit holds the point on the surface, a motion this integrator has
// no mode for). Says so, with the slip and the push at state y; empty when
// the law is not the soft cone or nothing pushes.
std::string soft_cone_chatter(const Model& model, size_t i, const Vec6& y) {
  const ContactParams& law = model.contact;
  if (law.friction != FrictionLaw::SoftCone || law.mu <= 0.0) return "";
  const RigidBody& body = model.body;
  const ShapeFeatures features = shape_features(body.shape);
  const Vec2& local = body.points[i];
  const double cos_t = features.rolls ? 1.0 : std::cos(y[2]);
  const double sin_t = features.rolls ? 0.0 : std::sin(y[2]);
  const double ry = features.smooth
                        ? ellipse_lowest_point(body.semi_axes.x(), body.semi_axes.y(), y[2]).y()
                        : sin_t * local.x() + cos_t * local.y();
  const double v_t = y[3] - y[5] * ry;
  const double spin = features.resists_rolling && law.mu_roll > 0.0 ? y[5] : 0.0;
  const double slip = std::hypot(law.mu * v_t, law.mu_roll * spin);
  const double push = law.c * slip / (1.0 + law.mu * law.mu / law.cone_ratio);
  if (!(push > 0.0)) return "";
  char text[512];
  std::snprintf(text, sizeof text,
                ": under soft_cone the point slides at %.3g m/s on the surface, where the "
                "normal force at zero depth is the push c*sqrt((mu*v_t)^2 + (mu_roll*w)^2)/"
                "(1 + mu^2/impratio) = %.3g N; in contact it pushes the point out, out of "
                "contact the point falls back, so the contact opens and closes at every step "
                "however short (fixed steps hop there, lower and more often the shorter the step)",
                std::abs(v_t), push);
  return text;
}

// Failure message for a chatter resolve_chatter could not resolve, at state y.
std::string chatter_message(const Model& model, double t, size_t j, const Vec6& y) {
  const size_t n = model.body.points.size();
  const size_t i = j < n ? j : j - n;
  const char* what = j < n ? "contact (c_y = 0)"
                     : model.contact.damping == DampingLaw::Compression
                         ? "compression damper (v_c,y = 0)"
                         : "Kelvin-Voigt force (k*d - c*v_c,y = 0)";
  char time[32];
  std::snprintf(time, sizeof time, "%.17g", t);
  return "inconsistent contact mode at t = " + std::string(time) + " s: contact point " +
         std::to_string(i) + ", switching function " + what +
         " is on the wrong side in both modes (chattering) and no shorter step resolves it" +
         (j < n ? soft_cone_chatter(model, i, y) : "");
}

// Flips the mode bits at an event located on function `located` at time t
// (state y); every flip is recorded as one event. `flips` is scratch of one
// entry per function.
void flip_modes(System& sys, size_t located, bool at_start, const Vec6& y, double t,
                std::vector<unsigned char>& flips, std::vector<double>& event_times,
                DenseStats& stats) {
  // Which functions flip, judged under the old mode: the located one, and
  // any other that is past its surface at the new state (simultaneous
  // crossings, e.g. a box landing flat on two corners).
  const size_t n = sys.points();
  for (size_t j = 0; j < sys.functions(); ++j) {
    flips[j] = sys.monitored(j) &&
               (j == located || (!at_start && sys.signed_value(j, y, nullptr, nullptr) < 0.0));
  }
  for (size_t i = 0; i < n; ++i) {
    if (flips[i]) {
      // Entering contact: the damper's side is read from the state (its
      // function is continuous through the entry); leaving: irrelevant.
      const bool on = !sys.contact(i);
      sys.set_contact(i, on);
      double gc, ga, rc, ra;
      sys.point_functions(i, y, nullptr, gc, ga, rc, ra);
      sys.set_active(i, on && ga > 0.0);
    } else if (flips[n + i]) {
      sys.set_active(i, !sys.active(i));
    } else {
      continue;
    }
    event_times.push_back(t);
    ++stats.events;
  }
}

}  // namespace

State DenseTrajectory::at(double t) const {
  if (segments_.empty()) return {};
  t = std::clamp(t, 0.0, t_end_);
  // Last segment starting at or before t.
  auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                             [](double value, const Segment& seg) { return value < seg.t0; });
  if (it != segments_.begin()) --it;
  const double s = it->h > 0.0 ? std::clamp((t - it->t0) / it->h, 0.0, 1.0) : 0.0;
  return unpack(interpolate(it->r, s));
}

DenseTrajectory integrate_dense(const Model& model, const State& initial, double duration,
                                const DenseOptions& options) {
  DenseTrajectory out;
  if (!model.obstacles.empty()) {
    // Obstacle contacts switch between faces and between point and disc
    // geometry; their switching functions are not modelled here, and a
    // reference that silently ignored them would be wrong, not converged.
    out.failure_ =
        "static obstacles are not supported by the converged reference (ground contact only)";
    return out;
  }
  System sys(model);
  const double rtol = options.rtol, atol = options.atol;
  const double h_max = options.h_max > 0.0 ? options.h_max : duration / 100.0;
  Vec6 y = pack(initial);
  sys.mode_from_state(y);
  Vec6 f;
  sys.rhs(y, f);
  DenseStats& stats = out.stats_;
  stats.evaluations = 1;
  out.segments_.reserve(4096);
  out.event_times_.reserve(256);

  double t = 0.0;
  double h = initial_step(sys, y, f, rtol, atol, h_max, stats.evaluations);
  bool rejected_last = false;
  int zero_length_flips = 0;
  // Function whose chatter the current step is being shortened to resolve.
  std::optional<size_t> unresolved;
  StepResult step;
  Vec6 r[5];
  std::vector<unsigned char> flips(sys.functions(), 0);
  auto fail = [&](std::string why) {
    out.failure_ = std::move(why);
    out.t_end_ = t;
    return out;
  };

  while (t < duration) {
    throw_if_cancelled();  // a Python Ctrl-C (core/cancel.hpp)
    if (stats.accepted + stats.rejected >= options.max_steps) {
      return fail("more than " + std::to_string(options.max_steps) + " steps");
    }
    const double remaining = duration - t;
    h = std::min(h, h_max);
    if (h >= remaining || remaining - h <= 1e-12 * remaining) h = remaining;
    if (h <= 8.0 * kEps * std::max(1.0, t)) {
      if (unresolved) return fail(chatter_message(model, t, *unresolved, y));
      return fail("step size underflow at t = " + std::to_string(t));
    }

    dopri_step(sys, y, f, h, rtol, atol, step);
    stats.evaluations += 6;
    if (!(step.error <= 1.0)) {  // also catches NaN
      ++stats.rejected;
      const double fac = std::isfinite(step.error)
                             ? std::max(kFacMin, kSafety * std::pow(step.error, -0.2))
                             : kFacMin;
      h *= fac;
      rejected_last = true;
      continue;
    }
    double fac = step.error > 0.0 ? kSafety * std::pow(step.error, -0.2) : kFacMax;
    fac = std::clamp(fac, kFacMin, rejected_last ? 1.0 : kFacMax);
    const double h_next = h * fac;
    rejected_last = false;

    dense_coefficients(y, step, h, r);
    const std::optional<Event> event =
        find_event(sys, y, f, step.y1, step.k[6], r, h, zero_length_flips < kMaxZeroLengthFlips);
    if (event && event->unresolved) {
      // Chattering function with no consistent stretch in this step: reject
      // it and try a shorter one (resolve_chatter).
      unresolved = event->function;
      ++stats.rejected;
      h *= 0.5;
      rejected_last = true;
      continue;
    }

    if (!event) {
      out.segments_.push_back({t, h, {r[0], r[1], r[2], r[3], r[4]}});
      ++stats.accepted;
      t = (h == remaining) ? duration : t + h;
      y = step.y1;
      f = step.k[6];
      h = h_next;
      zero_length_flips = 0;
      unresolved.reset();
      if (!y.allFinite()) return fail("non-finite state at t = " + std::to_string(t));
      continue;
    }

    // Flip the mode at the crossing: first redo the step exactly up to it.
    const double h_event = event->s * h;
    const bool at_start = t + h_event == t || event->s == 0.0;
    if (!at_start) {
      dopri_step(sys, y, f, h_event, rtol, atol, step);
      stats.evaluations += 6;
      dense_coefficients(y, step, h_event, r);
      out.segments_.push_back({t, h_event, {r[0], r[1], r[2], r[3], r[4]}});
      ++stats.accepted;
      t += h_event;
      y = step.y1;
      zero_length_flips = 0;
      unresolved.reset();
    } else {
      ++zero_length_flips;
    }
    flip_modes(sys, event->function, at_start, y, t, flips, out.event_times_, stats);
    sys.rhs(y, f);
    ++stats.evaluations;
    if (!at_start) h = h_next;
    if (!y.allFinite()) return fail("non-finite state at t = " + std::to_string(t));
  }
  out.t_end_ = duration;
  return out;
}

DenseTrajectory converged_reference(const Scene& scene, double tol) {
  const Model model = make_model(scene);
  State s0 = scene.initial;
  if (!shape_features(scene.shape).turns) {
    s0.q.z() = 0.0;
    s0.v.z() = 0.0;
  }
  DenseOptions options;
  options.rtol = options.atol = tol;
  return integrate_dense(model, s0, scene.sim.duration, options);
}

Vec3 dense_reference_acceleration(const Model& model, const Vec3& q, const Vec3& v) {
  System sys(model);
  Vec6 y;
  y << q, v;
  sys.mode_from_state(y);
  Vec6 dy;
  sys.rhs(y, dy);
  return dy.tail<3>();
}

}  // namespace contact2d
