// Forces and accelerations of one planar body (docs/physics.md): the force stage,
// which reads the contacts found by the position stage (core/contacts.hpp).
//
// With q = (x, y, θ), v = (vx, vy, ω) and the contacts found at q:
//   F = (0, −m·g) + F_applied,  τ = τ_applied
//   for every contact (depth d, normal n, tangent t = (n_y, −n_x), lever arm r):
//     v_c = v + ω·(−r_y, r_x)                    velocity of the contact point
//     Fn  = normal law (d, v_c·n)                core/contact.hpp
//     Ft  = −μ·Fn·tanh(α·v_c·t)
//     f   = Fn·n + Ft·t,   F += f,   τ += r × f − μ_roll·Fn·tanh(α·R·ω)
//   a = (F/m, τ/I)
// The rolling term is there only for a rolling body (R > 0, μ_roll > 0).
#pragma once

#include <Eigen/Core>

#include "core/contacts.hpp"
#include "core/model.hpp"

namespace contact2d {

// a = M⁻¹·F(q, v) with `contacts` found at q (q enters only through them).
// Allocation-free.
Vec3 acceleration(const Model& model, const ContactSet& contacts, const Vec3& v);

// The same a together with its derivatives ∂a/∂q and ∂a/∂v, for implicit
// Euler's Newton solve (core/integrators.cpp). `contacts` are those found at
// q. Analytic for the ground contacts (d = −c_y with c = p + R(θ)·r_b, the
// lever arm's rotation, both damping laws, friction's tanh′ = 1 − tanh²,
// the rolling regularisation); for obstacle contacts ∂a/∂v is analytic and
// ∂a/∂q is taken by forward differences of their part (three contact
// stages into `probe`, sized for the model). At a kink of the law (d = 0,
// v_n = 0 under compression, k·d = c·v_n under Kelvin–Voigt) it is the
// derivative of the branch the state is on. Under a cone friction law
// (core/contact.hpp) the whole of it is taken by forward differences
// (three contact stages into `probe`). Allocation-free.
struct AccelerationJacobian {
  Eigen::Matrix3d dq;  // ∂a/∂q
  Eigen::Matrix3d dv;  // ∂a/∂v
};
Vec3 acceleration_jacobian(const Model& model, const ContactSet& contacts, const Vec3& q,
                           const Vec3& v, AccelerationJacobian& jacobian, ContactSet& probe);

// Mechanical energy: ½m|v|² + ½Iω² + m·g·y + Σ ½·k·d² over the contacts
// (each contact's own k).
double energy(const Model& model, const ContactSet& contacts, const State& s);

// Conveniences that run the contact stage themselves (they allocate a
// ContactSet: for summaries and tests, not for a step).
Vec3 acceleration(const Model& model, const Vec3& q, const Vec3& v);
double energy(const Model& model, const State& s);
double max_penetration(const Model& model, const Vec3& q);

}  // namespace contact2d
