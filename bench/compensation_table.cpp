// contact2d_compensation: the frictionless agreement table
// (body × ζ, calibrated and compensated) and the same on seeded random scenes.
//
//   build-dir/bench/contact2d_compensation [--random N] [--seed S] [--mappings a,b] [--keep-mu]
//
// Table 1, the drops of tests/mujoco/test_agreement.cpp (the same TOML as
// tests/mujoco/mj_test_util.hpp's drop_scene, μ = 0): each body (1 kg,
// k = 1e4 N/m, Kelvin–Voigt, Δt = 1e-4 s, semi-implicit Euler in both
// engines, 2 s, samples every 1 ms) at ζ = c/(2√(k·m)) ∈ {0.1, 0.3, 1, 5},
// max position difference (m) and max angle difference (rad) between the
// reference and MuJoCo under each mapping.
// Table 2, N random scenes of report/random_scenes.hpp drawn from seed S
// (default 7, not the report's 20260101) with μ = 0: the worst and the
// median over the scenes, and each scene's ζ and difference; --keep-mu
// keeps the drawn friction μ = U(0.1, 1) (then the push of docs/mujoco.md
// dominates both mappings).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "analysis/trajectory_error.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"
#include "report/random_scenes.hpp"

namespace {

using namespace contact2d;

Scene drop_scene(Shape shape, double c) {
  const std::string contact = "[contact]\nk = 1e4\nc = " + std::to_string(c) +
                              "\nmu = 0\nalpha = 100\ndamping = \"kelvin_voigt\"\n";
  const std::string sim =
      "[sim]\ndt = 1e-4\nduration = 2.0\nintegrator = \"semi_implicit_euler\"\n";
  std::string text;
  switch (shape) {
    case Shape::PointMass:
      text = "scene = \"point_mass\"\n[body]\nmass = 1.0\nhalf_height = 0.05\n" + contact +
             "[initial]\ny = 1.0\nvx = 0.5\n" + sim;
      break;
    case Shape::Box:
      text = "scene = \"box\"\n[body]\nmass = 1.0\nwidth = 0.4\nheight = 0.2\n" + contact +
             "[initial]\ny = 0.6\ntheta = 0.3\nvx = 0.5\nomega = 1.0\n" + sim;
      break;
    case Shape::TShape:
      text = "scene = \"tshape\"\n" + contact + "[initial]\ny = 0.8\ntheta = 0.2\nvx = 0.3\n" + sim;
      break;
    case Shape::Circle:
      text = "scene = \"circle\"\n[body]\nmass = 1.0\nradius = 0.1\n" + contact +
             "[initial]\ny = 0.5\nvx = 1.0\n" + sim;
      break;
    case Shape::Ellipse:
      text = "scene = \"ellipse\"\n[body]\nmass = 1.0\na = 0.2\nb = 0.1\n" + contact +
             "[initial]\ny = 0.6\ntheta = 0.3\nvx = 0.5\nomega = 1.0\n" + sim;
      break;
  }
  return parse_scene(text, "drop scene");
}

analysis::TrajectoryError compare(const Scene& scene, const Trajectory& reference,
                                  mujoco::Mapping mapping) {
  mujoco::MjcfOptions options;
  options.mapping = mapping;
  mujoco::MujocoStepper stepper(scene, options);
  return analysis::error_between(reference, simulate(stepper, scene.sim));
}

std::vector<mujoco::Mapping> parse_mappings(const std::string& list) {
  std::vector<mujoco::Mapping> out;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    const auto m = mujoco::parse_mapping(list.substr(start, end - start));
    if (!m) throw std::runtime_error("unknown mapping in " + list);
    out.push_back(*m);
    start = end + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int random = 32;
  unsigned long long seed = 7;
  std::string mapping_list = "calibrated,compensated";
  bool keep_mu = false;
  for (int i = 1; i < argc; ++i) {
    const bool value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--random") && value) random = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--seed") && value) seed = std::strtoull(argv[++i], nullptr, 10);
    if (!std::strcmp(argv[i], "--mappings") && value) mapping_list = argv[++i];
    if (!std::strcmp(argv[i], "--keep-mu")) keep_mu = true;
  }
  try {
    const std::vector<mujoco::Mapping> mappings = parse_mappings(mapping_list);
    std::printf(
        "Frictionless drops (k = 1e4 N/m, m = 1 kg, dt = 1e-4 s, 2 s): max position (m) / "
        "max angle (rad) difference, reference vs MuJoCo\n");
    std::printf("%-11s %-5s", "body", "zeta");
    for (mujoco::Mapping m : mappings)
      std::printf("  %-23s", std::string(mujoco::mapping_name(m)).c_str());
    std::printf("\n");
    for (Shape shape : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
      for (double zeta : {0.1, 0.3, 1.0, 5.0}) {
        const Scene scene = drop_scene(shape, 2 * zeta * std::sqrt(1e4 * 1.0));
        const Trajectory reference = simulate(scene);
        std::printf("%-11s %-5g", std::string(shape_name(shape)).c_str(), zeta);
        for (mujoco::Mapping m : mappings) {
          const analysis::TrajectoryError e = compare(scene, reference, m);
          std::printf("  %10.3g / %-10.3g", e.max_pos, e.max_angle);
        }
        std::printf("\n");
        std::fflush(stdout);
      }
    }
    if (random <= 0) return 0;
    std::printf("\nRandom scenes (report/random_scenes.hpp, seed %llu, %s)\n", seed,
                keep_mu ? "mu as drawn" : "mu = 0");
    std::printf("%-5s %-11s %-8s", "scene", "body", "zeta");
    for (mujoco::Mapping m : mappings)
      std::printf("  %-23s", std::string(mujoco::mapping_name(m)).c_str());
    std::printf("\n");
    std::vector<std::vector<double>> pos(mappings.size()), ang(mappings.size());
    for (report::RandomScene& r : report::draw_random_scenes(seed, random)) {
      if (!keep_mu) r.scene.contact.mu = 0.0;
      const Trajectory reference = simulate(r.scene);
      const double zeta = r.scene.contact.c / (2 * std::sqrt(r.scene.contact.k * r.mass));
      std::printf("%-5s %-11s %-8.3g", r.name.c_str(),
                  std::string(shape_name(r.scene.shape)).c_str(), zeta);
      for (size_t j = 0; j < mappings.size(); ++j) {
        const analysis::TrajectoryError e = compare(r.scene, reference, mappings[j]);
        pos[j].push_back(e.max_pos);
        ang[j].push_back(e.max_angle);
        std::printf("  %10.3g / %-10.3g", e.max_pos, e.max_angle);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    for (size_t j = 0; j < mappings.size(); ++j) {
      std::sort(pos[j].begin(), pos[j].end());
      std::sort(ang[j].begin(), ang[j].end());
      std::printf("%-12s worst %.3g m / %.3g rad, median %.3g m / %.3g rad\n",
                  std::string(mujoco::mapping_name(mappings[j])).c_str(), pos[j].back(),
                  ang[j].back(), pos[j][pos[j].size() / 2], ang[j][ang[j].size() / 2]);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contact2d_compensation: %s\n", e.what());
    return 1;
  }
  return 0;
}
