// The keeper's rule: a box obstacle (game.keeper) that the game moves up and
// down between physics steps, on both engines the same way (it is scene
// geometry: Stepper::move_obstacle; a mocap body on MuJoCo). The ball
// bounces off it with its contact law; the keeper's own velocity does not
// enter that law (core/stepper.hpp says why), it pushes through its spring.
//
// The rule, every step: the keeper's centre heads for the height at which
// the ball's centre, flying from where it is now without drag, would reach
// the keeper's front face, y + vy·t − g·t²/2 with t = (distance to the
// face)/vx, raised to the ball's radius when that is below the grass (it
// would bounce first); the ball's present height when it is not moving
// towards the goal or is past the face. The centre moves towards it by at
// most speed·Δt a step, between where the scene put the keeper (on the
// grass) and the crossbar's underside. It sees only the ball's state: a
// shot it cannot reach in time (high from close) beats it; one from far it
// reaches.
#pragma once

#include "core/model.hpp"

namespace contact2d::game {

struct KeeperRule {
  double face_x = 0.0;      // x of the face towards the pass, m
  double centre_y = 0.0;    // the centre's height where the scene puts it, m
  double max_offset = 0.0;  // how far it can rise: its top reaches the crossbar's underside, m
  double speed = 0.0;       // m/s
  double direction = 1.0;   // +1: the goal is towards +x
  double gravity = 9.81;    // m/s²
  double radius = 0.0;      // the ball's, m
};

// The offset (upwards, from where the scene put it) the keeper heads for.
double keeper_target(const KeeperRule& rule, const State& ball);

// The keeper's offset after one step of dt from `offset`.
double keeper_step(const KeeperRule& rule, double offset, const State& ball, double dt);

}  // namespace contact2d::game
