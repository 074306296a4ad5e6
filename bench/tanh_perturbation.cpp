// contact2d_tanh_perturbation: how far the built-in trajectories move when
// every tanh of the force stage (friction, rolling) is one ulp larger or
// smaller (std::nextafter on glibc's value, wherever |x| < 22), and how far
// the vector path (SLEEF, ≤ 1 ULP) moves them, both against the scalar
// glibc run; every step's state compared, for each integrator.
//
//   build/bench/contact2d_tanh_perturbation    (docs/speed.md quotes it)
#include <cstdio>
#include <string>

#include "io/scene_file.hpp"
#include "tanh_study.hpp"

int main() {
  using namespace contact2d;
  if (!vector_tanh_available()) std::printf("vector path not available: it equals scalar below\n");
  std::printf("%-11s %-20s %12s %12s %12s %12s %7s\n", "scene", "integrator", "1ulp pos m",
              "1ulp ang rad", "vector pos", "vector ang", "ratio");
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    for (Integrator integrator :
         {Integrator::SemiImplicitEuler, Integrator::RK4, Integrator::ImplicitEuler}) {
      Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + name + ".toml");
      scene.sim.integrator = integrator;
      const study::Perturbation p = study::perturbation(scene);
      const double ratio = p.ulp.position > 0.0 ? p.vector.position / p.ulp.position : 0.0;
      std::printf("%-11s %-20s %12.3e %12.3e %12.3e %12.3e %7.3f%s\n", name,
                  std::string(integrator_name(integrator)).c_str(), p.ulp.position, p.ulp.angle,
                  p.vector.position, p.vector.angle, ratio,
                  p.ulp.same_length && p.vector.same_length ? "" : "  (a run stopped early)");
    }
  }
  return 0;
}
