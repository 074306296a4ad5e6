// The contact stage: which points of the body touch something, how deep,
// along which normal and at which lever arm — found once per configuration q
// and read by everything that needs contacts.
//
// A simulation step reads like a table of contents (MuJoCo's mj_step →
// mj_fwdPosition → mj_fwdVelocity … is the model):
//
//   find_contacts(model, q, contacts)          position stage: geometry only
//   acceleration(model, contacts, q, v)        force stage: contact law, M⁻¹·F
//   energy(model, contacts, s)                 divergence monitor
//   max_penetration(contacts)                  divergence monitor, summaries
//
// The stage rotates the body's points once: with R(θ) = [cos θ −sin θ;
// sin θ cos θ] (identity for a circle, whose point stays below its centre),
// every body-fixed point r_b has world lever arm r = R(θ)·r_b and world
// position c = p + r. Then, in this order (the order the forces are summed in):
//
//   ground    for every point with c_y < 0:  d = −c_y,  n = (0, 1)
//   obstacles a circle: its true disc against every obstacle
//               (core/obstacles.hpp: d = R − |p − closest point|);
//             any other body: every point against every obstacle
//               (d = distance to the nearest face, or into a capsule)
//
// Each contact carries depth d > 0, the unit normal n out of the surface the
// body touches and the lever arm r from the COM to the contact point. The
// tangent is t = (n_y, −n_x), which is +x on the ground.
//
// A ContactSet's capacity is fixed when it is made for a model (points ×
// (1 + obstacles), plus one per obstacle for a disc), so finding contacts in
// a step never allocates.
#pragma once

#include <vector>

#include "core/body.hpp"
#include "core/obstacles.hpp"

namespace contact2d {

struct Model;

struct Contact {
  double depth = 0.0;            // penetration d > 0, m
  Vec2 normal = Vec2(0.0, 1.0);  // unit normal out of the touched surface
  Vec2 r = Vec2::Zero();         // lever arm: contact point − COM, world frame
};

class ContactSet {
 public:
  ContactSet() = default;
  // Room for every contact the model can have at once.
  explicit ContactSet(const Model& model);

  void clear() { contacts_.clear(); }
  // Within the capacity reserved by the constructor: never allocates.
  void add(const Contact& contact) { contacts_.push_back(contact); }

  auto begin() const { return contacts_.begin(); }
  auto end() const { return contacts_.end(); }
  size_t size() const { return contacts_.size(); }
  bool empty() const { return contacts_.empty(); }
  size_t capacity() const { return contacts_.capacity(); }

 private:
  std::vector<Contact> contacts_;
};

// The position stage: every active contact of the body at configuration q.
void find_contacts(const Model& model, const Vec3& q, ContactSet& out);

// Penetration of the deepest contact (0 when none touches).
double max_penetration(const ContactSet& contacts);

}  // namespace contact2d
