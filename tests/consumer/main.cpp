// Drops a point mass onto the ground through the installed public header and
// checks it comes to rest at the static penetration m·g/k (exit 0) — proof
// that headers, library and CMake package work together outside the tree.
#include <contact2d/contact2d.hpp>

#include <cmath>
#include <cstdio>

int main() {
  contact2d::Scene scene = contact2d::default_scene(contact2d::Shape::PointMass);
  scene.contact.c = 2.0 * std::sqrt(scene.contact.k * scene.mass);  // critical
  if (contact2d::validate(scene)) return 1;
  const contact2d::Trajectory t = contact2d::simulate(scene);
  if (t.divergence || t.samples.empty()) return 2;
  const double depth = scene.half_height - t.samples.back().state.q.y();
  const double expected = scene.mass * scene.sim.gravity / scene.contact.k;
  std::printf("rest depth %.9g m, m*g/k = %.9g m\n", depth, expected);
  return std::abs(depth - expected) < 1e-9 ? 0 : 3;
}
