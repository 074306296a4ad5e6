// Forces and accelerations of one planar body on the ground (SPEC §2–3).
//
// With q = (x, y, θ) and v = (vx, vy, ω), one evaluation does:
//   F = (0, −m·g) + F_applied,  τ = τ_applied
//   for every contact point r (body frame, rotated by θ unless the point keeps
//   its world offset): c = p + r; if c_y < 0, v_c = v + ω·(−r_y, r_x),
//   (Ft, Fn) from the contact law, F += (Ft, Fn), τ += r × (Ft, Fn),
//   and for a rolling contact τ += −μ_roll·Fn·tanh(α·R·ω)
//   then the same law against every static obstacle (core/obstacles.hpp)
//   a = (F/m, τ/I)
#pragma once

#include "core/body.hpp"
#include "core/contact.hpp"
#include "core/obstacles.hpp"

namespace contact2d {

struct State {
  Vec3 q = Vec3::Zero();  // x, y, θ
  Vec3 v = Vec3::Zero();  // vx, vy, ω
};

struct Model {
  RigidBody body;
  ContactParams contact;
  double gravity = 9.81;
  Vec3 applied = Vec3::Zero();      // external (Fx, Fy, τ), e.g. from a player
  std::vector<Obstacle> obstacles;  // static geometry with the ground's contact law
};

// a = M⁻¹·F(q, v). Allocation-free.
Vec3 acceleration(const Model& model, const Vec3& q, const Vec3& v);

// Penetration of the deepest contact point, ground or obstacle (0 when none touches).
double max_penetration(const Model& model, const Vec3& q);

// Mechanical energy: ½m|v|² + ½Iω² + m·g·y + Σ ½·k·d² over the contacts
// with the ground and the obstacles.
double energy(const Model& model, const State& s);

}  // namespace contact2d
