// Drops a point mass onto the ground through the installed public header and
// checks it comes to rest at the static penetration m·g/k, then steps it by
// hand as the header's example does (exit 0) — proof that headers, library
// and CMake package work together outside the tree.
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
  if (!(std::abs(depth - expected) < 1e-9)) return 3;

  // The header's "step it yourself", as written there: 1000 RK4 steps of the
  // same scene end where simulate's RK4 run of 0.1 s does.
  scene.sim.integrator = contact2d::Integrator::RK4;
  scene.sim.dt = 1e-4;
  scene.sim.duration = 0.1;
  const contact2d::Model model = contact2d::make_model(scene);
  contact2d::State s = contact2d::initial_state(scene);
  contact2d::StepWorkspace ws(model);  // the step's scratch, made once
  for (int i = 0; i < 1000; ++i)
    if (contact2d::step(model, contact2d::Integrator::RK4, 1e-4, s, ws) !=
        contact2d::StepStatus::Ok)
      break;
  const contact2d::Trajectory run = contact2d::simulate(scene);
  if (run.samples.empty() || run.samples.back().state.q != s.q) return 4;
  std::printf("1000 steps by hand = simulate's last sample: y = %.9g m\n", s.q.y());
  return 0;
}
