// The pitch: a circle scene (the ball, its contact law, the goal's obstacles)
// plus the game's rules, read from the scene file's [game] table.
//
// The goal is at the +x or −x side, whichever the goal line is on as seen
// from the pass's start. The crossbar is one of the scene's [[obstacle]]
// boxes (game.crossbar is its index); its underside is the height below which
// a ball crossing the goal line is a goal. The crossbar, the goal's roof and
// its back are ordinary obstacles: the ball bounces off them with the contact
// law, in the same physics as the ground.
//
// The keeper (game.keeper, optional) is one more box obstacle, marked as
// moving (Obstacle::moves): the game moves it up and down between steps
// (game/keeper.hpp), from where the scene puts it (on the grass) up to the
// crossbar's underside; the ball bounces off it with its contact law.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene.hpp"
#include "game/replay.hpp"

namespace contact2d::game {

struct Rules {
  double goal_line = 10.0;         // x of the goal line (its rear edge), m
  int crossbar = 0;                // index of the crossbar obstacle (a box)
  int keeper = -1;                 // index of the keeper obstacle (a box); −1: no keeper
  double keeper_speed_easy = 1.5;  // m/s: the keeper's top speed at each level
  double keeper_speed_normal = 2.2;
  double keeper_speed_hard = 3.0;
  double reach_height = 0.9;   // m: the player reaches the ball (push, control, kick) below this
  double control_force = 6.0;  // N: the most the control key brakes the ball with...
  double control_time = 0.05;  // s: ...a force m·|v|/control_time up to control_force
  double min_kick_distance = 1.0;  // a kick counts from this far from the goal line, m
  double kick_impulse = 5.0;       // N·s, spread over kick_duration
  double kick_duration = 0.04;     // s
  double kick_angle = 15.0;        // initial kick angle above the horizontal, degrees
  double kick_angle_min = 0.0;     // degrees
  double kick_angle_max = 60.0;    // degrees
  double kick_angle_step = 5.0;    // degrees per key press
  double kick_power = 0.8;         // initial fraction of kick_impulse
  double kick_power_min = 0.3;     // the power keys step it within [min, 1]
  double kick_power_step = 0.1;
  // The push: holding an arrow key pushes the ball with a constant force,
  // derived (push_force_for) so that a ball at rest held push_time and then
  // left to roll travels push_distance in all; at most push_force. Replays
  // recorded before the derived push (no `push` line) push with push_force.
  double push_force = 4.0;      // N: the most an arrow pushes with
  double push_distance = 1.25;  // m: how far a ball at rest goes, pushed push_time and let roll...
  double push_time = 0.7;       // s: ...this long
  double pass_x = 0.5;          // where the pass starts (ball centre), m
  double pass_speed_min = 2.5;  // m/s, drawn uniformly from [min, max]
  double pass_speed_max = 3.5;
  double pass_spin_min = 0.5;  // spin as a multiple of rolling spin (1 = rolling, 0 = none)
  double pass_spin_max = 1.5;
  double pass_lift_min = 0.0;  // m/s upwards at the start, uniform in [min, max]: the pass bounces
  double pass_lift_max = 0.0;
  double round_time = 20.0;   // s, then the round is over
  double rest_speed = 0.02;   // m/s: the ball is at rest below this (centre and rim speed)...
  double rest_time = 0.5;     // ...for this long, s
  double result_time = 2.0;   // s between the end of a round and the next pass
  int session_rounds = 10;    // passes in a session; then its end (reset: a new session)
  double pitch_min_x = -0.5;  // the ball is out of play beyond these, m
  double pitch_max_x = 12.5;
};

struct Pitch {
  Scene scene;  // shape circle; sim.dt is the physics step
  Rules rules;
  std::string path;                 // where it was read from
  std::uint64_t fingerprint = 0;    // FNV-1a of the file's bytes (stamped into replays)
  bool goal_from_built_in = false;  // the file had no [game]: the built-in goal and rules

  // Derived: +1 when the goal is towards +x from the pass.
  double direction() const { return rules.goal_line >= rules.pass_x ? 1.0 : -1.0; }
  double crossbar_bottom() const;  // underside of the crossbar, m
  bool has_keeper() const { return rules.keeper >= 0; }
  double keeper_speed(Level level) const;
};

// The built-in pitch (validation/scenes/game/pitch.toml has the same values).
Pitch default_pitch();

// Reads and checks a pitch file: the scene (parse_scene) and its [game]
// table. A circle scene without [game] is played on the built-in pitch's
// goal (its obstacles, then the scene's) with the built-in rules. Throws
// InputError with one line naming the key and its range.
Pitch load_pitch(const std::string& path);
Pitch parse_pitch(const std::string& toml_text, const std::string& origin);

}  // namespace contact2d::game
