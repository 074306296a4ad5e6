// What the fits against real data share (analysis/real_impacts.hpp,
// analysis/real_trajectories.hpp): the penalty law they fit, the recorded
// body's height above the ground, and the seeded split. The minimiser is
// analysis/minimise.hpp.
#pragma once

#include <cstdint>
#include <string>
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

// One 50/50 split of n recorded items (impacts, trajectories): the first
// n/2 of its order are fitted, the others held out (in index order).
struct Halves {
  std::string split;  // "seeded" or "chronological"
  std::vector<size_t> train, test;
};

// The two splits of the items 0 … n−1, n = chronological.size(): "seeded",
// the items shuffled with `seed` (Fisher–Yates on core/rng.hpp's
// next_uniform), and "chronological", the items in the order given (the
// order they were recorded in, as far as the recording tells).
std::vector<Halves> fit_splits(std::uint64_t seed, const std::vector<size_t>& chronological);

}  // namespace contact2d::analysis
