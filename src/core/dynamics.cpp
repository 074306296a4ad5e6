#include "core/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "core/vector_math.hpp"

namespace contact2d {

namespace {

// Contacts per tanh batch: the force stage's scratch lives on the stack
// (allocation-free) and a model with more contacts touching at once takes
// more than one batch, summed in the same order.
constexpr size_t kBatch = 16;

// One contact under a cone law (core/contact.hpp); `fn` is the normal law's
// force. Under soft_cone the force acts halfway into the penetration, where
// MuJoCo puts every contact point (midway between the two surfaces), on
// the ground and on an obstacle alike: the body's point r moved back out
// along the normal by d/2, lever r + (d/2)·n, so that
// v_t = t·(v + ω × (r + (d/2)·n)) (v_n is the same as at the point, n × n
// being 0). viscous_cone keeps the contact's own point.
void add_cone(const Contact& c, const ContactParams& law, double fn, const Vec3& v, double omega,
              bool rolls, Vec2& force, double& torque) {
  const bool soft = law.friction == FrictionLaw::SoftCone;
  const Vec2 n = c.normal();
  const double shift = soft ? 0.5 * c.depth : 0.0;
  const double rx = c.rx + shift * n.x();
  const double ry = c.ry + shift * n.y();
  const Vec2 vc(v.x() - omega * ry, v.y() + omega * rx);  // v + ω × r
  const Vec2 t(n.y(), -n.x());
  const double spin = rolls ? v.z() : 0.0;
  const ConeForce f =
      soft ? soft_cone_force(law, normal_aim(law, c.depth, vc.dot(n)), vc.dot(t), spin)
           : viscous_cone_force(law, fn, vc.dot(t), spin);
  const Vec2 total = f.fn * n + f.ft * t;
  force += total;
  torque += rx * total.y() - ry * total.x() + f.roll;
}

// The derivatives of one tanh-law contact's (f_x, f_y, τ) with respect to
// (x, y, θ, vx, vy, ω), added to the rows of `jac` (add_contacts with a
// Jacobian). `f_n` is its normal force, `s` = tanh(α·v_t), `s_roll` the
// rolling tanh when `rolls`, (f_x, f_y) its force.
void add_contact_jacobian(const Contact& c, const ContactParams& law, bool on_ground,
                          const ShapeFeatures& features, const Vec3& v, double f_n, double s,
                          bool rolls, double s_roll, double radius, double f_x, double f_y,
                          double (*jac)[6]) {
  const double omega = features.turns ? v.z() : 0.0;
  // Derivatives in (x, y, θ, vx, vy, ω), written out entry by entry
  // (most are zero). The lever arm turns with θ when the points
  // rotate: ∂r/∂θ = (rtx, rty) = (−r_y, r_x); the contact point
  // c = p + r moves with ∂c/∂q = [I | ∂r/∂θ]; v_c = v + ω·(−r_y, r_x);
  // the depth along a fixed normal is d = −n·c + const.
  const double nx = c.nx, ny = c.ny, tx = ny, ty = -nx;
  const double rtx = !features.rolls ? -c.ry : 0.0;
  const double rty = !features.rolls ? c.rx : 0.0;
  const double wf = features.turns ? 1.0 : 0.0;
  const double dd_t = -(nx * rtx + ny * rty);
  const double dvn_t = omega * (ny * rtx - nx * rty);
  const double dvn_w = wf * (ny * c.rx - nx * c.ry);
  const double dvt_t = omega * (ty * rtx - tx * rty);
  const double dvt_w = wf * (ty * c.rx - tx * c.ry);
  // The branch of the normal law: Fn = k_b·d − c_b·v_n + const.
  const double v_n = (v.x() - omega * c.ry) * nx + (v.y() + omega * c.rx) * ny;
  double k_b = 0.0, c_b = 0.0;
  if (c.depth > 0.0) {
    if (law.damping == DampingLaw::Compression) {
      k_b = law.k;
      c_b = v_n < 0.0 ? law.c : 0.0;
    } else if (law.k * c.depth - law.c * v_n > 0.0) {
      k_b = law.k;
      c_b = law.c;
    }
  }
  const double dfn[6] = {-k_b * nx, -k_b * ny, k_b * dd_t - c_b * dvn_t,
                         -c_b * nx, -c_b * ny, -c_b * dvn_w};
  const double dvt[6] = {0.0, 0.0, dvt_t, tx, ty, dvt_w};
  // Ft = −μ·Fn·s, s = tanh(α·v_t), s′ = α·(1 − s²).
  const double slope = f_n * law.alpha * (1.0 - s * s);
  const double roll_fn = rolls ? law.mu_roll * s_roll : 0.0;
  if (on_ground) {
    // n = (0, 1), t = (1, 0): ∂f_x = ∂F_t, ∂f_y = ∂F_n, and x never
    // enters (column 0 only ever receives zeros). The general loop's
    // products with 0 and 1 left out: the same sums, bit for bit (a
    // ±0 term added to these +0-started sums leaves them unchanged).
    for (int j = 1; j < 6; ++j) {
      const double dft = -law.mu * (s * dfn[j] + slope * dvt[j]);
      jac[0][j] += dft;
      jac[1][j] += dfn[j];
      jac[2][j] += c.rx * dfn[j] - c.ry * dft - roll_fn * dfn[j];
    }
  } else {
    for (int j = 0; j < 6; ++j) {
      const double dft = -law.mu * (s * dfn[j] + slope * dvt[j]);
      const double dfx = nx * dfn[j] + tx * dft;
      const double dfy = ny * dfn[j] + ty * dft;
      jac[0][j] += dfx;
      jac[1][j] += dfy;
      jac[2][j] += c.rx * dfy - c.ry * dfx - roll_fn * dfn[j];
    }
  }
  jac[2][2] += rtx * f_y - rty * f_x;
  if (rolls) jac[2][5] -= law.mu_roll * f_n * law.alpha * radius * (1.0 - s_roll * s_roll);
}

// The contact forces and torques of contacts [first, last) of `contacts`
// added to `force` and `torque`, in the order of the list — the order and
// the arithmetic of every sum are those of the one-contact-at-a-time loop
// this replaced, so that on one tanh path the result is bit for bit the
// same. In two passes per batch: the normal forces and every tanh
// argument (friction α·v_t, rolling α·R·ω) first, then one tanh_batch,
// then the sums.
//
// With a Jacobian (Newton, core/integrators.cpp) it also adds the analytic
// derivatives of (F_x, F_y, τ) with respect to (q, v) = (x, y, θ, vx, vy, ω)
// to the rows of `jac` (3 × 6, row-major), for contacts
// whose normal does not turn with q (the ground); see acceleration_jacobian.
// A contact under a cone friction law is added by add_cone instead (its
// Jacobian is never asked for: acceleration_jacobian differences it).
template <bool kJacobian>
void add_contacts(const Model& model, const ContactSet& contacts, size_t first, size_t last,
                  const Vec3& v, Vec2& force, double& torque, double (*jac)[6]) {
  const ShapeFeatures features = shape_features(model.body.shape);
  const double omega = features.turns ? v.z() : 0.0;
  const double radius = model.body.roll_radius;
  const size_t ground = contacts.ground_count();
  const Contact* const list = contacts.begin();
  double fn[kBatch];
  double arg[2 * kBatch];  // friction arguments, then the rolling ones
  for (size_t from = first; from < last; from += kBatch) {
    const size_t to = std::min(last, from + kBatch);
    size_t n_args = 0;
    // Pass 1: normal forces and friction arguments.
    for (size_t i = from; i < to; ++i) {
      const Contact& c = list[i];
      const ContactParams& law = i < ground ? model.contact : model.law(c);
      double v_n, v_t;
      if (i < ground) {  // n = (0, 1), t = (1, 0): v_n = v_c,y, v_t = v_c,x
        v_t = v.x() - omega * c.ry;
        v_n = v.y() + omega * c.rx;
      } else {
        const Vec2 vc(v.x() - omega * c.ry, v.y() + omega * c.rx);  // v + ω × r
        v_n = vc.dot(c.normal());
        v_t = vc.dot(Vec2(c.ny, -c.nx));
      }
      fn[i - from] = normal_force(law, c.depth, v_n);
      arg[n_args++] = law.alpha * v_t;
    }
    // … and the rolling arguments (a rolling body with μ_roll > 0 only).
    const size_t n_friction = n_args;
    if (features.resists_rolling) {
      for (size_t i = from; i < to; ++i) {
        const ContactParams& law = i < ground ? model.contact : model.law(list[i]);
        if (law.mu_roll > 0.0) arg[n_args++] = law.alpha * radius * v.z();
      }
    }
    tanh_batch(arg, n_args);
    // Pass 2: the sums, contact by contact.
    size_t rolling = n_friction;
    for (size_t i = from; i < to; ++i) {
      const Contact& c = list[i];
      const ContactParams& law = i < ground ? model.contact : model.law(c);
      if (law.friction != FrictionLaw::Tanh) {
        const bool rolls = features.resists_rolling && law.mu_roll > 0.0;
        if (rolls) ++rolling;  // its tanh argument was computed and is not used
        add_cone(c, law, fn[i - from], v, omega, rolls, force, torque);
        continue;
      }
      const double f_n = fn[i - from];
      const double s = arg[i - from];
      const double ft = -law.mu * f_n * s;
      double roll = 0.0, s_roll = 0.0;
      const bool rolls = features.resists_rolling && law.mu_roll > 0.0;
      if (rolls) {
        s_roll = arg[rolling++];
        roll = -law.mu_roll * f_n * s_roll;
      }
      double f_x, f_y;
      if (i < ground) {
        f_x = ft;
        f_y = f_n;
        force += Vec2(ft, f_n);
        torque += c.rx * f_n - c.ry * ft + roll;
      } else {
        const Vec2 n = c.normal();
        const Vec2 t(n.y(), -n.x());
        const Vec2 f = f_n * n + ft * t;
        f_x = f.x();
        f_y = f.y();
        force += f;
        torque += c.rx * f.y() - c.ry * f.x() + roll;
      }
      if constexpr (kJacobian) {
        add_contact_jacobian(c, law, i < ground, features, v, f_n, s, rolls, s_roll, radius, f_x,
                             f_y, jac);
      }
    }
  }
}

Vec3 to_acceleration(const RigidBody& body, const Vec2& force, double torque) {
  const bool turns = shape_features(body.shape).turns;
  const double alpha = (turns && body.inertia > 0.0) ? torque / body.inertia : 0.0;
  return {force.x() / body.mass, force.y() / body.mass, alpha};
}

// ∂a/∂q and ∂a/∂v under a cone law by forward differences of the whole
// force stage (the laws' branches, stick, slide and off, meet with
// continuous forces but not derivatives; its use is comparison, where the
// Newton solve needs a consistent Jacobian, not a cheap one). Steps
// h = 1e-7·max(1, |x|): about √ε of the state, the usual forward-difference
// balance of truncation against rounding.
Vec3 cone_jacobian(const Model& model, const ContactSet& contacts, const Vec3& q, const Vec3& v,
                   AccelerationJacobian& jacobian, ContactSet& probe) {
  Vec3 a = acceleration(model, contacts, v);
  for (int j = 0; j < 3; ++j) {
    const double h = 1e-7 * std::max(1.0, std::abs(q[j]));
    Vec3 qp = q;
    qp[j] += h;
    find_contacts(model, qp, probe);
    jacobian.dq.col(j) = (acceleration(model, probe, v) - a) / h;
  }
  for (int j = 0; j < 3; ++j) {
    const double h = 1e-7 * std::max(1.0, std::abs(v[j]));
    Vec3 vp = v;
    vp[j] += h;
    jacobian.dv.col(j) = (acceleration(model, contacts, vp) - a) / h;
  }
  return a;
}

}  // namespace

Vec3 acceleration(const Model& model, const ContactSet& contacts, const Vec3& v) {
  const RigidBody& body = model.body;
  Vec2 force(model.applied.x(), model.applied.y() - body.mass * model.gravity);
  double torque = model.applied.z();
  add_contacts<false>(model, contacts, 0, contacts.size(), v, force, torque, nullptr);
  return to_acceleration(body, force, torque);
}

Vec3 acceleration_jacobian(const Model& model, const ContactSet& contacts, const Vec3& q,
                           const Vec3& v, AccelerationJacobian& jacobian, ContactSet& probe) {
  const RigidBody& body = model.body;
  // A cone law, or a smooth outline whose contact point moves over the rim
  // with θ (its lever arm's derivative is not that of a body point):
  // forward differences.
  if (model.uses_cone_law() || shape_features(body.shape).smooth)
    return cone_jacobian(model, contacts, q, v, jacobian, probe);
  Vec2 force(model.applied.x(), model.applied.y() - body.mass * model.gravity);
  double torque = model.applied.z();
  double d[3][6] = {};
  add_contacts<true>(model, contacts, 0, contacts.size(), v, force, torque, d);
  Vec3 a = to_acceleration(body, force, torque);
  // (F, τ) → a = (F/m, τ/I): the same scaling of the derivatives.
  const bool turns = shape_features(body.shape).turns;
  const double inv_i = (turns && body.inertia > 0.0) ? 1.0 / body.inertia : 0.0;
  const double scale[3] = {1.0 / body.mass, 1.0 / body.mass, inv_i};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      jacobian.dq(i, j) = d[i][j] * scale[i];
      jacobian.dv(i, j) = d[i][j + 3] * scale[i];
    }
  }
  if (contacts.size() > contacts.ground_count()) {
    // Obstacle contacts: their normal and depth depend on q in ways the
    // contact stage decides (a face, a capsule's round end, an obstacle
    // vertex against a body edge), so ∂a/∂q of their part is taken by
    // forward differences of that part alone (their ∂a/∂v above is exact).
    auto obstacle_part = [&](const ContactSet& set) {
      Vec2 f = Vec2::Zero();
      double tau = 0.0;
      add_contacts<false>(model, set, set.ground_count(), set.size(), v, f, tau, nullptr);
      return Vec3(f.x() / body.mass, f.y() / body.mass, tau * inv_i);
    };
    double dobs[3][6] = {};
    {
      Vec2 f = Vec2::Zero();
      double tau = 0.0;
      add_contacts<true>(model, contacts, contacts.ground_count(), contacts.size(), v, f, tau,
                         dobs);
    }
    const Vec3 base = obstacle_part(contacts);
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-7 * std::max(1.0, std::abs(q[j]));
      Vec3 qp = q;
      qp[j] += h;
      find_contacts(model, qp, probe);
      const Vec3 fd = (obstacle_part(probe) - base) / h;
      for (int i = 0; i < 3; ++i) jacobian.dq(i, j) += fd[i] - dobs[i][j] * scale[i];
    }
  }
  return a;
}

double energy(const Model& model, const ContactSet& contacts, const State& s) {
  const RigidBody& body = model.body;
  double e = 0.5 * body.mass * (s.v.x() * s.v.x() + s.v.y() * s.v.y()) +
             0.5 * body.inertia * s.v.z() * s.v.z() + body.mass * model.gravity * s.q.y();
  for (const Contact& c : contacts) e += 0.5 * model.law(c).k * c.depth * c.depth;
  return e;
}

Vec3 acceleration(const Model& model, const Vec3& q, const Vec3& v) {
  ContactSet contacts(model);
  find_contacts(model, q, contacts);
  return acceleration(model, contacts, v);
}

double energy(const Model& model, const State& s) {
  ContactSet contacts(model);
  find_contacts(model, s.q, contacts);
  return energy(model, contacts, s);
}

double max_penetration(const Model& model, const Vec3& q) {
  ContactSet contacts(model);
  find_contacts(model, q, contacts);
  return max_penetration(contacts);
}

}  // namespace contact2d
