// Helpers of the MuJoCo tests: scenes written as TOML text (read by the
// project's own parser, so a test states its scene the way a user would),
// runs of both engines, and the generated MJCF as a tinyxml2 document.
#pragma once

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <string>

#include "analysis/trajectory_error.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/stepper.hpp"

namespace contact2d::test {

// Scene from TOML text.
inline Scene scene_from(const std::string& toml) { return parse_scene(toml, "test scene"); }

// A drop of one of the four bodies at dt = 1e-4 with the Kelvin–Voigt law,
// k = 1e4 N/m, m = 1 kg, the given damping c and friction μ (α = 100 s/m).
// The bodies fall from rest heights of 0.5–1 m with a sideways velocity and,
// for the box and the T, a tilt, so that they land on a corner and rock.
inline Scene drop_scene(Shape shape, double c, double mu) {
  const std::string contact = "[contact]\nk = 1e4\nc = " + std::to_string(c) +
                              "\nmu = " + std::to_string(mu) +
                              "\nalpha = 100\ndamping = \"kelvin_voigt\"\n";
  const std::string sim =
      "[sim]\ndt = 1e-4\nduration = 2.0\nintegrator = \"semi_implicit_euler\"\n";
  switch (shape) {
    case Shape::PointMass:
      return scene_from("scene = \"point_mass\"\n[body]\nmass = 1.0\nhalf_height = 0.05\n" +
                        contact + "[initial]\ny = 1.0\nvx = 0.5\n" + sim);
    case Shape::Box:
      return scene_from("scene = \"box\"\n[body]\nmass = 1.0\nwidth = 0.4\nheight = 0.2\n" +
                        contact + "[initial]\ny = 0.6\ntheta = 0.3\nvx = 0.5\nomega = 1.0\n" + sim);
    case Shape::TShape:
      return scene_from("scene = \"tshape\"\n" + contact +
                        "[initial]\ny = 0.8\ntheta = 0.2\nvx = 0.3\n" + sim);
    case Shape::Circle:
      return scene_from("scene = \"circle\"\n[body]\nmass = 1.0\nradius = 0.1\n" + contact +
                        "[initial]\ny = 0.5\nvx = 1.0\n" + sim);
    case Shape::Ellipse:
      return scene_from("scene = \"ellipse\"\n[body]\nmass = 1.0\na = 0.2\nb = 0.1\n" + contact +
                        "[initial]\ny = 0.6\ntheta = 0.3\nvx = 0.5\nomega = 1.0\n" + sim);
  }
  return {};
}

// A MuJoCo run through the one run loop, with what the tests read of it.
struct MujocoRun {
  Trajectory trajectory;
  std::vector<std::string> warnings;
  mujoco::SolverSettings settings;
};

inline MujocoRun finish(mujoco::MujocoStepper& stepper, const Scene& scene) {
  MujocoRun run;
  run.trajectory = simulate(stepper, scene.sim);
  run.warnings = stepper.warnings();
  run.settings = stepper.settings();
  return run;
}

inline MujocoRun run_mujoco(const Scene& scene, const mujoco::MjcfOptions& options) {
  mujoco::MujocoStepper stepper(scene, options);
  return finish(stepper, scene);
}

inline MujocoRun run_mujoco_xml(const Scene& scene, const std::string& xml,
                                const std::string& origin) {
  mujoco::MujocoStepper stepper(scene, xml, origin);
  return finish(stepper, scene);
}

struct BothRuns {
  Trajectory ref;
  MujocoRun mj;
  analysis::TrajectoryError errors;
};

inline BothRuns run_both(const Scene& scene,
                         mujoco::Mapping mapping = mujoco::Mapping::Calibrated) {
  BothRuns out;
  mujoco::MjcfOptions options;
  options.mapping = mapping;
  out.mj = run_mujoco(scene, options);
  out.ref = simulate(scene);
  EXPECT_FALSE(out.ref.divergence.has_value());
  EXPECT_FALSE(out.mj.trajectory.divergence.has_value());
  EXPECT_TRUE(out.mj.warnings.empty()) << out.mj.warnings.front();
  EXPECT_EQ(out.ref.samples.size(), out.mj.trajectory.samples.size());
  out.errors = analysis::error_between(out.ref, out.mj.trajectory);
  return out;
}

inline std::string source_dir() { return CONTACT2D_SOURCE_DIR; }

}  // namespace contact2d::test
