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

// d(·)/d(x, y, θ, vx, vy, ω) of one scalar.
using Row = Eigen::Matrix<double, 1, 6>;

// The contact forces and torques of contacts [first, last) of `contacts`
// added to `force` and `torque`, in the order of the list — the order and
// the arithmetic of every sum are those of the one-contact-at-a-time loop
// this replaced, so that on the scalar tanh path the result is bit for bit
// the same. In two passes per batch: the normal forces and every tanh
// argument (friction α·v_t, rolling α·R·ω) first, then one tanh_batch,
// then the sums.
//
// With a Jacobian (Newton, core/integrators.cpp) it also adds the analytic
// derivatives of (F_x, F_y, τ) with respect to (q, v) to `d`, for contacts
// whose normal does not turn with q (the ground); see acceleration_jacobian.
template <bool kJacobian>
void add_contacts(const Model& model, const ContactSet& contacts, size_t first, size_t last,
                  const Vec3& v, Vec2& force, double& torque, Eigen::Matrix<double, 3, 6>* d) {
  const RigidBody& body = model.body;
  const bool rotates = body.rotates;
  const double omega = rotates ? v.z() : 0.0;
  const double radius = body.roll_radius;
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
    if (radius > 0.0) {
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
      const double f_n = fn[i - from];
      const double s = arg[i - from];
      const double ft = -law.mu * f_n * s;
      double roll = 0.0, s_roll = 0.0;
      const bool rolls = radius > 0.0 && law.mu_roll > 0.0;
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
        // Derivatives in (x, y, θ, vx, vy, ω). The lever arm turns with θ
        // when the points rotate: ∂r/∂θ = (−r_y, r_x); the contact point
        // c = p + r moves with ∂c/∂q = [I | ∂r/∂θ]; v_c = v + ω·(−r_y, r_x).
        const double nx = c.nx, ny = c.ny, tx = ny, ty = -nx;
        const double rtx = body.points_rotate ? -c.ry : 0.0;
        const double rty = body.points_rotate ? c.rx : 0.0;
        const double wf = rotates ? 1.0 : 0.0;
        Row dvcx, dvcy, dd;
        dvcx << 0.0, 0.0, -omega * rty, 1.0, 0.0, -c.ry * wf;
        dvcy << 0.0, 0.0, omega * rtx, 0.0, 1.0, c.rx * wf;
        // The depth along a fixed normal: d = −n·c + const.
        dd << -nx, -ny, -(nx * rtx + ny * rty), 0.0, 0.0, 0.0;
        const Row dvn = nx * dvcx + ny * dvcy;
        const Row dvt = tx * dvcx + ty * dvcy;
        const double v_n = (v.x() - omega * c.ry) * nx + (v.y() + omega * c.rx) * ny;
        Row dfn = Row::Zero();
        if (c.depth > 0.0) {
          if (law.damping == DampingLaw::Compression) {
            dfn = law.k * dd;
            if (v_n < 0.0) dfn -= law.c * dvn;
          } else if (law.k * c.depth - law.c * v_n > 0.0) {
            dfn = law.k * dd - law.c * dvn;
          }
        }
        const Row dft = -law.mu * (s * dfn + f_n * law.alpha * (1.0 - s * s) * dvt);
        const Row dfx = nx * dfn + tx * dft;
        const Row dfy = ny * dfn + ty * dft;
        Row dtau = c.rx * dfy - c.ry * dfx;
        dtau[2] += rtx * f_y - rty * f_x;
        if (rolls) {
          dtau -= law.mu_roll * s_roll * dfn;
          dtau[5] -= law.mu_roll * f_n * law.alpha * radius * (1.0 - s_roll * s_roll);
        }
        d->row(0) += dfx;
        d->row(1) += dfy;
        d->row(2) += dtau;
      }
    }
  }
}

Vec3 to_acceleration(const RigidBody& body, const Vec2& force, double torque) {
  const double alpha = (body.rotates && body.inertia > 0.0) ? torque / body.inertia : 0.0;
  return {force.x() / body.mass, force.y() / body.mass, alpha};
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
  Vec2 force(model.applied.x(), model.applied.y() - body.mass * model.gravity);
  double torque = model.applied.z();
  Eigen::Matrix<double, 3, 6> d = Eigen::Matrix<double, 3, 6>::Zero();
  add_contacts<true>(model, contacts, 0, contacts.size(), v, force, torque, &d);
  const Vec3 a = to_acceleration(body, force, torque);
  // (F, τ) → a = (F/m, τ/I): the same scaling of the derivatives.
  const double inv_i = (body.rotates && body.inertia > 0.0) ? 1.0 / body.inertia : 0.0;
  d.row(0) /= body.mass;
  d.row(1) /= body.mass;
  d.row(2) *= inv_i;
  jacobian.dq = d.leftCols<3>();
  jacobian.dv = d.rightCols<3>();
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
    Eigen::Matrix3d analytic = Eigen::Matrix3d::Zero();
    {
      Eigen::Matrix<double, 3, 6> dobs = Eigen::Matrix<double, 3, 6>::Zero();
      Vec2 f = Vec2::Zero();
      double tau = 0.0;
      add_contacts<true>(model, contacts, contacts.ground_count(), contacts.size(), v, f, tau,
                         &dobs);
      analytic.row(0) = dobs.row(0).leftCols<3>() / body.mass;
      analytic.row(1) = dobs.row(1).leftCols<3>() / body.mass;
      analytic.row(2) = dobs.row(2).leftCols<3>() * inv_i;
    }
    const Vec3 base = obstacle_part(contacts);
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-7 * std::max(1.0, std::abs(q[j]));
      Vec3 qp = q;
      qp[j] += h;
      find_contacts(model, qp, probe);
      jacobian.dq.col(j) += (obstacle_part(probe) - base) / h - analytic.col(j);
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

double Model::min_k() const {
  double k = contact.k;
  for (const ContactParams& p : obstacle_laws) k = std::min(k, p.k);
  return k;
}

double Model::max_k() const {
  double k = contact.k;
  for (const ContactParams& p : obstacle_laws) k = std::max(k, p.k);
  return k;
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
