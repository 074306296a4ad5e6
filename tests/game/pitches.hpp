// Pitches the game's tests set up: the built-in one without its keeper (for
// the rules and the goal, tests/game/test_keeper.cpp has the keeper's), and
// with a ball at rest where a kick is taken.
#pragma once

#include <gtest/gtest.h>

#include "game/pitch.hpp"

namespace contact2d::game::testing {

inline Pitch without_keeper() {
  Pitch p = default_pitch();
  EXPECT_GT(p.rules.keeper, p.rules.crossbar) << "the crossbar keeps its index";
  p.scene.obstacles.erase(p.scene.obstacles.begin() + p.rules.keeper);
  p.rules.keeper = -1;
  return p;
}

// Without the keeper, the ball at rest at x0 (no pass), the kick at full
// power and the angle set to `angle` (any value, not only the 5° steps of
// the keys).
inline Pitch still_ball(double x0, double angle = 0.0) {
  Pitch p = without_keeper();
  p.rules.pass_speed_min = p.rules.pass_speed_max = 0.0;
  p.rules.pass_lift_min = p.rules.pass_lift_max = 0.0;
  p.rules.kick_power = 1.0;
  p.rules.pass_x = x0;
  p.rules.kick_angle_min = -90.0;
  p.rules.kick_angle_max = 90.0;
  p.rules.kick_angle = angle;
  return p;
}

}  // namespace contact2d::game::testing
