// What the MuJoCo 3 suites share: whether MuJoCo 3 can run here. Without
// Node or the package a test is skipped with the reason, unless
// CONTACT2D_REQUIRE_MUJOCO3 is set (scripts/test sets it: CI installs both,
// so there a skip would hide a broken install), where it fails.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "io/scene_file.hpp"
#include "mujoco3/node_mujoco.hpp"

#define CONTACT2D_NEEDS_MUJOCO3()                                                     \
  do {                                                                                \
    const std::string why_missing = ::contact2d::mujoco3::missing();                  \
    if (!why_missing.empty()) {                                                       \
      if (std::getenv("CONTACT2D_REQUIRE_MUJOCO3") != nullptr) FAIL() << why_missing; \
      GTEST_SKIP() << why_missing;                                                    \
    }                                                                                 \
  } while (false)

namespace contact2d::test {

// Drops the shipped scenes do not have: each body, other masses, damping
// and friction, thrown sideways and spinning.
inline std::vector<Scene> other_drops(double mu) {
  const std::string contact =
      "[contact]\nk = 3e4\nc = 40\nalpha = 150\nmu = " + std::to_string(mu) +
      "\ndamping = \"kelvin_voigt\"\n";
  const std::string sim = "[sim]\ndt = 2e-4\nduration = 1.5\n";
  return {
      parse_scene("scene = \"point_mass\"\n[body]\nmass = 2.5\nhalf_height = 0.02\n" + contact +
                      "[initial]\ny = 0.4\nvx = -1.2\n" + sim,
                  "test scene"),
      parse_scene("scene = \"box\"\n[body]\nmass = 0.7\nwidth = 0.3\nheight = 0.12\n" + contact +
                      "[initial]\ny = 0.45\ntheta = -0.5\nvx = 0.8\nomega = -3\n" + sim,
                  "test scene"),
      parse_scene(
          "scene = \"tshape\"\n" + contact + "[initial]\ny = 0.7\ntheta = 0.9\nvx = -0.4\n" + sim,
          "test scene"),
      parse_scene("scene = \"circle\"\n[body]\nmass = 3\nradius = 0.15\n" + contact +
                      "[initial]\ny = 0.3\nvx = 2\nomega = 5\n" + sim,
                  "test scene")};
}

}  // namespace contact2d::test
