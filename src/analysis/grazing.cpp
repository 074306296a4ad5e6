#include "analysis/grazing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/contacts.hpp"

namespace contact2d::analysis {
namespace {

// The body's points in the world at configuration q: c = p + R(θ)·r_b, or
// p + r_b for a disc, whose point stays below its centre.
void world_points(const RigidBody& body, const Vec3& q, std::vector<Vec2>& out) {
  const double cos_t = body.points_rotate ? std::cos(q.z()) : 1.0;
  const double sin_t = body.points_rotate ? std::sin(q.z()) : 0.0;
  out.clear();
  for (const Vec2& r : body.points)
    out.emplace_back(q.x() + cos_t * r.x() - sin_t * r.y(), q.y() + sin_t * r.x() + cos_t * r.y());
}

// The largest distance between the same point of the body in two states.
double points_apart(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double apart = 0.0;
  for (size_t i = 0; i < a.size(); ++i) apart = std::max(apart, (a[i] - b[i]).norm());
  return apart;
}

// Samples of a and b at the same time, by index.
size_t common_samples(const Trajectory& a, const Trajectory& b) {
  const size_t n = std::min(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < n; ++i)
    if (std::abs(a.samples[i].t - b.samples[i].t) > 1e-12 * std::max(1.0, a.samples[i].t)) return i;
  return n;
}

// Contacts with each obstacle, and the deepest of them.
void per_obstacle(const ContactSet& set, std::vector<int>& count, std::vector<double>& deepest) {
  std::fill(count.begin(), count.end(), 0);
  std::fill(deepest.begin(), deepest.end(), 0.0);
  for (const Contact& c : set) {
    if (c.obstacle < 0) continue;
    const auto j = static_cast<size_t>(c.obstacle);
    ++count[j];
    deepest[j] = std::max(deepest[j], c.depth);
  }
}

}  // namespace

double departure_time(const Scene& scene, const Trajectory& a, const Trajectory& b,
                      double distance) {
  const Model model = make_model(scene);
  std::vector<Vec2> pa, pb;
  const size_t n = common_samples(a, b);
  for (size_t i = 0; i < n; ++i) {
    world_points(model.body, a.samples[i].state.q, pa);
    world_points(model.body, b.samples[i].state.q, pb);
    if (points_apart(pa, pb) > distance) return a.samples[i].t;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::optional<GrazingContact> grazing_contact(const Scene& scene, const Trajectory& a,
                                              const Trajectory& b, double distance) {
  const Model model = make_model(scene);
  const size_t obstacles = model.obstacles.size();
  ContactSet set_a(model), set_b(model);
  std::vector<int> count_a(obstacles), count_b(obstacles);
  std::vector<double> deep_a(obstacles), deep_b(obstacles);
  std::vector<Vec2> pa, pb;
  const size_t n = common_samples(a, b);
  for (size_t i = 0; i < n; ++i) {
    const Vec3& qa = a.samples[i].state.q;
    const Vec3& qb = b.samples[i].state.q;
    world_points(model.body, qa, pa);
    world_points(model.body, qb, pb);
    const double apart = points_apart(pa, pb);
    if (apart > distance) break;  // departed
    GrazingContact g;
    g.t = a.samples[i].t;
    g.apart = apart;
    for (size_t p = 0; p < pa.size(); ++p) {
      if ((pa[p].y() < 0.0) == (pb[p].y() < 0.0)) continue;
      g.where = "point " + std::to_string(p) + " on the ground";
      g.touches_a = pa[p].y() < 0.0;
      g.height_a = pa[p].y();
      g.height_b = pb[p].y();
      return g;
    }
    if (obstacles == 0) continue;
    find_contacts(model, qa, set_a);
    find_contacts(model, qb, set_b);
    per_obstacle(set_a, count_a, deep_a);
    per_obstacle(set_b, count_b, deep_b);
    for (size_t j = 0; j < obstacles; ++j) {
      if (count_a[j] == count_b[j]) continue;
      g.where = "obstacle " + std::to_string(j);
      g.touches_a = count_a[j] > count_b[j];
      constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
      g.height_a = g.touches_a ? -deep_a[j] : (count_a[j] > 0 ? -deep_a[j] : kNone);
      g.height_b = g.touches_a ? (count_b[j] > 0 ? -deep_b[j] : kNone) : -deep_b[j];
      return g;
    }
  }
  return std::nullopt;
}

}  // namespace contact2d::analysis
