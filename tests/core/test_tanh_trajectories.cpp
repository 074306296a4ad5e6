// The vector tanh path (SLEEF, core/vector_math.hpp) and the bounded one
// (contact2d's own tanh, the default) against glibc's on the built-in
// scenes: their trajectories must stay within what one ulp of tanh
// does to them (the perturbation study, bench/tanh_study.hpp, printed by
// build/bench/contact2d_tanh_perturbation and quoted in docs/speed.md).
//
// The envelope P is the largest distance from the glibc run (position and
// angle, over every step) of the runs with every tanh one ulp up, one ulp
// down, and up or down at random (8 seeds). Value by value the vector path
// differs from glibc by at most 1 + 2.161 ≈ 3.2 ulps (SLEEF's bound plus
// glibc's worst found, 2.1608 ULP at x = 0.23442163446192277, docs/speed.md;
// tests/core/test_tanh.cpp's grid sees 2.021), so for a trajectory that
// responds linearly to tanh's errors the margin is 3.2: the check is
// D ≤ 3.2·P, position and angle. The bounded path differs from glibc by at
// most 1.27 + 2.161 < 3.5 ulps (its derived bound plus glibc's worst found),
// so its margin is 3.5. Where no ulp of tanh moves a trajectory at all
// (P = 0: every difference rounds away), D must be 0 too. Measured
// (docs/speed.md): D/P ≤ 1.0 for both paths on every scene and integrator.
// One study per scene and integrator serves both paths.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_file.hpp"
#include "tanh_study.hpp"

namespace contact2d {
namespace {

TEST(TanhTrajectories, VectorAndBoundedPathsWithinOneUlpPerturbation) {
  const bool vector = vector_tanh_available();  // else only the bounded path is checked
  int moved = 0, bounded_moved = 0;
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    for (Integrator integrator :
         {Integrator::SemiImplicitEuler, Integrator::RK4, Integrator::ImplicitEuler}) {
      Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + name + ".toml");
      scene.sim.integrator = integrator;
      const study::Perturbation p = study::perturbation(scene);
      SCOPED_TRACE(std::string(name) + " " + std::string(integrator_name(integrator)));
      EXPECT_TRUE(p.ulp.same_length && p.bounded.same_length);
      EXPECT_LE(p.bounded.position, 3.5 * p.ulp.position);
      EXPECT_LE(p.bounded.angle, 3.5 * p.ulp.angle);
      if (vector) {
        EXPECT_TRUE(p.vector.same_length);
        EXPECT_LE(p.vector.position, 3.2 * p.ulp.position);
        EXPECT_LE(p.vector.angle, 3.2 * p.ulp.angle);
      }
      if (p.ulp.position > 0.0) ++moved;
      if (p.bounded.position > 0.0) ++bounded_moved;
    }
  }
  EXPECT_GT(moved, 0) << "one ulp of tanh must move some trajectory, or the check is empty";
  EXPECT_GT(bounded_moved, 0)
      << "the bounded path must differ from glibc somewhere, or the check is empty";
}

}  // namespace
}  // namespace contact2d
