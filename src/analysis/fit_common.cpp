#include "analysis/fit_common.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/rng.hpp"

namespace contact2d::analysis {

double ground_gap(const Model& model, const Vec3& q, ContactSet& contacts) {
  find_contacts(model, q, contacts);
  if (contacts.ground_count() > 0) {
    double deepest = 0.0;
    for (size_t i = 0; i < contacts.ground_count(); ++i)
      deepest = std::max(deepest, contacts.begin()[i].depth);
    return -deepest;
  }
  // Above the ground: lift the body's lowest point by probing how far down
  // it can go — for a smooth or a one-point body that is exact.
  Vec3 low = q;
  double lo = 0.0, hi = std::max(1.0, q.y() + 1.0);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, hi); ++i) {
    const double mid = 0.5 * (lo + hi);
    low.y() = q.y() - mid;
    find_contacts(model, low, contacts);
    (contacts.ground_count() > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

Scene penalty_scene(const Scene& body, const PenaltyParams& p, double m_eff, double omega_dt,
                    double duration) {
  Scene s = body;
  s.contact.k = std::pow(10.0, p.log_k);
  s.contact.c = 2.0 * p.zeta * std::sqrt(s.contact.k * body.mass);
  s.contact.mu = p.mu;
  // Rolling resistance is a circle's or an ellipse's (core/scene.hpp's
  // validate refuses it elsewhere): a box's fit has no such parameter.
  s.contact.mu_roll = shape_features(body.shape).resists_rolling ? p.mu_roll : 0.0;
  s.contact.damping = DampingLaw::KelvinVoigt;
  s.sim.integrator = Integrator::SemiImplicitEuler;
  s.sim.dt = omega_dt / std::sqrt(s.contact.k / m_eff);
  s.sim.duration = duration;
  s.sim.output_dt = s.sim.dt;
  s.obstacles.clear();
  return s;
}

std::vector<Halves> fit_splits(std::uint64_t seed, const std::vector<size_t>& chronological) {
  const size_t n = chronological.size();
  std::vector<size_t> shuffled(n);
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::uint64_t state = seed;
  for (size_t i = n > 0 ? n - 1 : 0; i > 0; --i)
    std::swap(shuffled[i],
              shuffled[static_cast<size_t>(next_uniform(state) * static_cast<double>(i + 1))]);
  std::vector<Halves> out = {{"seeded", {}, {}}, {"chronological", {}, {}}};
  for (Halves& h : out) {
    const std::vector<size_t>& all = h.split == "seeded" ? shuffled : chronological;
    const auto half = all.begin() + static_cast<std::ptrdiff_t>(n / 2);
    h.train.assign(all.begin(), half);
    h.test.assign(half, all.end());
    std::sort(h.test.begin(), h.test.end());
  }
  return out;
}

}  // namespace contact2d::analysis
