// contact2d_tanh_perturbation: how far the built-in trajectories move when
// every tanh of the force stage (friction, rolling) is one ulp larger or
// smaller (std::nextafter on glibc's value, wherever |x| < 22), and how far
// the vector path (SLEEF, ≤ 1 ULP) and the bounded path (contact2d's own
// tanh, ≤ 1.27 ULP, the default) move them, all against the scalar glibc
// run; every step's state compared, for each integrator.
//
//   build/bench/contact2d_tanh_perturbation [SCENE.toml...]
//     (the four built-in scenes by default; docs/speed.md quotes both uses)
#include <cstdio>
#include <string>
#include <vector>

#include "io/scene_file.hpp"
#include "tanh_study.hpp"

int main(int argc, char** argv) {
  using namespace contact2d;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) paths.emplace_back(argv[i]);
  if (paths.empty()) {
    for (const char* name : {"point_mass", "box", "tshape", "circle"})
      paths.push_back(std::string(CONTACT2D_SCENES_DIR) + "/" + name + ".toml");
  }
  if (!vector_tanh_available()) std::printf("vector path not available: it equals scalar below\n");
  std::printf("%-11s %-20s %12s %12s %12s %12s %7s %12s %12s %7s\n", "scene", "integrator",
              "1ulp pos m", "1ulp ang rad", "vector pos", "vector ang", "ratio", "bounded pos",
              "bounded ang", "ratio");
  for (const std::string& path : paths) {
    const std::string name = path.substr(path.find_last_of('/') + 1, std::string::npos);
    for (Integrator integrator :
         {Integrator::SemiImplicitEuler, Integrator::RK4, Integrator::ImplicitEuler}) {
      Scene scene = load_scene(path);
      scene.sim.integrator = integrator;
      const study::Perturbation p = study::perturbation(scene);
      const double ratio = p.ulp.position > 0.0 ? p.vector.position / p.ulp.position : 0.0;
      const double bounded = p.ulp.position > 0.0 ? p.bounded.position / p.ulp.position : 0.0;
      std::printf("%-11s %-20s %12.3e %12.3e %12.3e %12.3e %7.3f %12.3e %12.3e %7.3f%s\n",
                  name.substr(0, name.size() - 5).c_str(),
                  std::string(integrator_name(integrator)).c_str(), p.ulp.position, p.ulp.angle,
                  p.vector.position, p.vector.angle, ratio, p.bounded.position, p.bounded.angle,
                  bounded,
                  p.ulp.same_length && p.vector.same_length && p.bounded.same_length
                      ? ""
                      : "  (a run stopped early)");
    }
  }
  return 0;
}
