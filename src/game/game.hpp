// The game's rules on top of the physics, advanced one physics step at a
// time. Nothing here knows about windows or wall-clock time: inputs arrive
// between steps (stamped with the step index), so the same inputs give the
// same game, in a window or headless.
//
// A round:
//   * starts with the teammate's pass: the ball rests on the grass at
//     rules.pass_x and rolls towards the goal with a speed drawn uniformly
//     from [pass_speed_min, pass_speed_max] and a spin of s times the rolling
//     spin, s uniform in [pass_spin_min, pass_spin_max] (s ≠ 1: it slides
//     until friction makes it roll). The draws come from a SplitMix64 stream
//     seeded with the session's seed: the same seed gives the same passes on
//     every machine.
//   * arrows push the ball with rules.push_force (a force, not a teleport);
//     the kick key applies a force of kick_impulse/kick_duration for
//     kick_duration towards the goal at the current kick angle above the
//     horizontal. A kick pressed while one is still acting, or after the
//     round has ended, is ignored, and the game says so (ignored_kick()).
//   * a kick counts when the ball's centre is at least min_kick_distance
//     from the goal line when it is taken.
//   * the last touch decides: a push or a kick replaces the previous one.
//   * the ball crosses the goal line when its whole disc gets beyond the line
//     (centre more than R past it) in a step where it was not wholly beyond
//     before — i.e. through the mouth, not by dropping behind the goal — with
//     its centre below the crossbar's underside (the bar is solid, so a ball
//     crossing there passes under it). That is a goal when the last touch
//     was a counted kick, and otherwise "no goal" with the reason.
//   * other ends: the ball at rest (speed and rim speed below rest_speed for
//     rest_time, e.g. stopped on the line), out of play (centre beyond
//     pitch_min_x or pitch_max_x), round_time elapsed, the reset key, or the
//     physics diverged (the core's rule, with the player's work).
//   * rules.result_time after the end, the next pass starts (or at once on
//     the reset key).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/divergence.hpp"
#include "core/run.hpp"
#include "game/pitch.hpp"
#include "game/replay.hpp"

namespace contact2d::game {

enum class Outcome {
  None,  // still playing
  Goal,
  NotKicked,     // crossed the line, but nobody kicked it
  KickTooClose,  // crossed the line after a kick taken inside min_kick_distance
  Pushed,        // crossed the line, but the last touch was a push
  Stopped,       // came to rest in play (on the line, short, on the roof)
  Out,           // left the pitch
  TimeUp,
  Reset,  // the player asked for the next pass
  Diverged,
};

std::string_view outcome_name(Outcome outcome);  // "goal", "kick_too_close", … (JSON)
std::string outcome_text(Outcome outcome, double min_kick_distance);  // for the screen

enum class Phase { Playing, Over };
enum class IgnoredKick { None, RoundOver, StillKicking };
enum class Touch { None, Push, Kick };

struct KickRecord {
  int round = 0;            // 1-based
  long long step = 0;       // session step at which it was taken
  double time = 0.0;        // session time, s
  double round_time = 0.0;  // time since the pass, s
  double distance = 0.0;    // ball centre to the goal line, m (negative: beyond it)
  double angle = 0.0;       // degrees above the horizontal
  bool counted = false;
};

struct RoundRecord {
  int round = 0;
  long long start_step = 0;
  double pass_speed = 0.0;  // m/s towards the goal
  double pass_spin = 0.0;   // multiple of rolling spin
  Outcome outcome = Outcome::None;
  double end_time = 0.0;  // round time when it was decided, s
};

class Game {
 public:
  // `engine`: a name of the engine registry (engines/engines.hpp): ref or
  // mujoco[:MAPPING]. Throws InputError.
  Game(Pitch pitch, const std::string& engine, std::uint64_t seed);

  // Input between steps (applies from the next step on).
  void handle(Key key, bool down);
  // One physics step and the rules after it. Does nothing once diverged.
  void step();

  const Pitch& pitch() const { return pitch_; }
  std::string_view engine_name() const { return engine_name_; }
  std::uint64_t seed() const { return seed_; }
  long long steps() const { return steps_; }
  double dt() const { return pitch_.scene.sim.dt; }
  double time() const { return static_cast<double>(steps_) * dt(); }
  double round_time() const { return static_cast<double>(steps_ - round_start_) * dt(); }
  const State& ball() const { return stepper_->state(); }
  double radius() const { return pitch_.scene.radius; }
  double distance_to_goal() const;           // ball centre to the goal line, m
  Vec3 applied() const { return applied_; }  // the force of the last step
  Vec3 push_force() const;                   // from the arrows held now
  bool kicking() const { return kick_steps_left_ > 0; }
  double kick_angle() const { return kick_angle_; }
  Phase phase() const { return phase_; }
  Touch last_touch() const { return last_touch_; }
  int round() const { return static_cast<int>(rounds_.size()); }  // 1-based, current
  const RoundRecord& current_round() const { return rounds_.back(); }
  const std::vector<RoundRecord>& rounds() const { return rounds_; }
  const std::vector<KickRecord>& kicks() const { return kicks_; }
  int goals() const;
  long long steps_since_end() const { return over_steps_; }
  long long result_steps() const { return result_steps_; }
  const std::optional<Divergence>& divergence() const { return divergence_; }
  double applied_work() const { return work_; }
  // The last kick key that did nothing: why, and how many steps ago (for
  // the screen); None when no kick was ignored.
  IgnoredKick ignored_kick() const { return ignored_kick_why_; }
  long long steps_since_ignored_kick() const { return steps_ - ignored_kick_step_; }
  // Steps until the next pass starts (0 while playing).
  long long steps_to_next_pass() const {
    return phase_ == Phase::Over ? std::max(0LL, result_steps_ - over_steps_) : 0;
  }

 private:
  void start_round();
  void end_round(Outcome outcome);
  void apply_rules();
  double next_uniform();

  Pitch pitch_;
  std::string engine_name_;
  std::unique_ptr<Stepper> stepper_;
  std::uint64_t seed_;
  std::uint64_t rng_;
  long long steps_ = 0;
  long long round_start_ = 0;
  long long kick_steps_ = 1;  // kick duration in steps
  long long rest_steps_needed_ = 0;
  long long result_steps_ = 0;
  long long round_steps_ = 0;                    // round_time in steps
  bool held_[4] = {false, false, false, false};  // left, right, up, down
  double kick_angle_ = 0.0;
  Vec3 kick_force_ = Vec3::Zero();
  long long kick_steps_left_ = 0;
  Vec3 applied_ = Vec3::Zero();
  Phase phase_ = Phase::Playing;
  Touch last_touch_ = Touch::None;
  bool last_kick_counted_ = false;
  bool wholly_beyond_ = false;
  long long rest_steps_ = 0;
  long long over_steps_ = 0;
  double work_ = 0.0;
  IgnoredKick ignored_kick_why_ = IgnoredKick::None;
  long long ignored_kick_step_ = 0;
  std::unique_ptr<DivergenceMonitor> monitor_;
  std::optional<Divergence> divergence_;
  std::vector<RoundRecord> rounds_;
  std::vector<KickRecord> kicks_;
};

}  // namespace contact2d::game
