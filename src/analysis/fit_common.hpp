// What the fits against real data share (analysis/real_impacts.hpp,
// analysis/real_trajectories.hpp): the penalty law they fit, the recorded
// body's height above the ground, and the seeded split. The minimiser is
// analysis/minimise.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include "core/contacts.hpp"
#include "core/scene.hpp"

namespace contact2d::analysis {

// Height of the body's lowest point above the ground (negative: it
// penetrates, by the deepest contact's depth). Above the ground it is found
// by probing how far down the body can go (bisection to 1e-15 relative):
// exact for a smooth or a one-point body, and for a box's corners.
double ground_gap(const Model& model, const Vec3& q, ContactSet& contacts);

// The penalty law's parameters as a fit varies them.
struct PenaltyParams {
  double log_k = 5.0, zeta = 0.3, mu = 0.3, mu_roll = 0.0;
};

// The recorded body with the penalty law: Kelvin–Voigt normal force
// k·d − c·ḋ, k = 10^log_k, c = 2ζ·√(k·m), tanh friction μ, rolling
// resistance μ_roll; semi-implicit Euler at Δt = omega_dt / ω,
// ω = √(k/m_eff) (m_eff the body's smallest effective mass), for
// `duration` s, every step an output sample; no obstacles.
Scene penalty_scene(const Scene& body, const PenaltyParams& p, double m_eff, double omega_dt,
                    double duration);

// 0 … n−1 shuffled with `seed` (Fisher–Yates on core/rng.hpp's
// next_uniform): the seeded split's order, whose first half is fitted.
std::vector<size_t> seeded_order(size_t n, std::uint64_t seed);

}  // namespace contact2d::analysis
