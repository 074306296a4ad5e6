#include "core/dynamics.hpp"

#include <algorithm>

namespace contact2d {

Vec3 acceleration(const Model& model, const ContactSet& contacts, const Vec3& v) {
  const RigidBody& body = model.body;
  const ContactParams& law = model.contact;
  const double omega = body.rotates ? v.z() : 0.0;
  Vec2 force(model.applied.x(), model.applied.y() - body.mass * model.gravity);
  double torque = model.applied.z();

  // Ground: n = (0, 1), t = (1, 0), so v_n = v_c,y, v_t = v_c,x, f = (Ft, Fn).
  const Contact* ground_end = contacts.begin() + contacts.ground_count();
  for (const Contact* it = contacts.begin(); it != ground_end; ++it) {
    const double rx = it->rx, ry = it->ry;
    const double vc_x = v.x() - omega * ry;
    const double vc_y = v.y() + omega * rx;
    const double fn = normal_force(law, it->depth, vc_y);
    const double ft = friction_force(law, fn, vc_x);
    force += Vec2(ft, fn);
    torque += rx * fn - ry * ft + rolling_torque(law, fn, body.roll_radius, v.z());
  }
  // Obstacles: the same law along their normal n and tangent t = (n_y, −n_x).
  for (const Contact* it = ground_end; it != contacts.end(); ++it) {
    const Contact& contact = *it;
    const Vec2 n = contact.normal();
    const Vec2 r = contact.r();
    const Vec2 t(n.y(), -n.x());
    const Vec2 vc(v.x() - omega * r.y(), v.y() + omega * r.x());  // v + ω × r
    const ContactParams& own = model.law(contact);
    const double fn = normal_force(own, contact.depth, vc.dot(n));
    const double ft = friction_force(own, fn, vc.dot(t));
    const Vec2 f = fn * n + ft * t;
    force += f;
    torque += r.x() * f.y() - r.y() * f.x() + rolling_torque(own, fn, body.roll_radius, v.z());
  }

  const double alpha = (body.rotates && body.inertia > 0.0) ? torque / body.inertia : 0.0;
  return {force.x() / body.mass, force.y() / body.mass, alpha};
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
