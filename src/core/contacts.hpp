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
//               (d = distance to the nearest face, or into a capsule),
//             then every obstacle vertex v (a box's corners, a segment's
//             round ends of radius ρ) against every part outline of the body
//               (u = R(θ)ᵀ·(v − p) − c_j in the part's frame; d = ρ + the
//               distance to the nearest edge inside, ρ − the distance to the
//               edge above or beside it outside; n = −R(θ)·m, m the edge's
//               outward normal; r = v + ρ·n − p; core/obstacles.hpp derives
//               it and says why no pair of features counts twice)
//
// Each contact carries depth d > 0, the unit normal n out of the surface the
// body touches (for an obstacle vertex: out of the vertex, into the body's
// edge) and the lever arm r from the COM to the contact point. The tangent is
// t = (n_y, −n_x), which is +x on the ground. The force stage applies the
// same law to every contact whatever made it.
//
// A ContactSet's capacity is fixed when it is made for a model (points ×
// (1 + obstacles), plus one per obstacle for a disc, plus four obstacle
// vertices × parts per obstacle), so finding contacts in a step never
// allocates.
#pragma once

#include <vector>

#include "core/model.hpp"

namespace contact2d {

class ContactSet {
 public:
  ContactSet() = default;
  // Room for every contact the model can have at once.
  explicit ContactSet(const Model& model);

  void clear() { size_ = ground_ = 0; }

  // Every contact, ground first.
  const Contact* begin() const { return storage_.data(); }
  const Contact* end() const { return storage_.data() + size_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  size_t capacity() const { return storage_.size(); }
  // The ground contacts (normal +y) are [begin, begin + ground_count); the
  // force stage takes them on a path with n = (0, 1) written in.
  size_t ground_count() const { return ground_; }

 private:
  // Writes through a local pointer and counts, so that the compiler need not
  // assume its stores change the model it reads.
  friend void find_contacts(const Model& model, const Vec3& q, ContactSet& out);
  std::vector<Contact> storage_;  // sized once; [0, size_) in use
  size_t size_ = 0;
  size_t ground_ = 0;
};

// The position stage: every active contact of the body at configuration q.
void find_contacts(const Model& model, const Vec3& q, ContactSet& out);

// Penetration of the deepest contact (0 when none touches).
double max_penetration(const ContactSet& contacts);

}  // namespace contact2d
