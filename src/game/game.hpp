// The game's rules on top of the physics, advanced one physics step at a
// time. Nothing here knows about windows or wall-clock time: inputs arrive
// between steps (stamped with the step index), so the same inputs give the
// same game, in a window or headless.
//
// A round:
//   * starts with the teammate's pass: the ball rests on the grass at
//     rules.pass_x and leaves towards the goal with a speed drawn uniformly
//     from [pass_speed_min, pass_speed_max], a lift (upward speed: it
//     bounces) from [pass_lift_min, pass_lift_max] and a spin of s times the
//     rolling spin, s from [pass_spin_min, pass_spin_max] (s ≠ 1: it slides
//     until friction makes it roll). The draws come from a SplitMix64 stream
//     seeded with the session's seed: the same seed gives the same passes on
//     every machine.
//   * the player reaches the ball while its centre is below
//     rules.reach_height (a bouncing pass must come down first). Within
//     reach: the arrows push it with push_force_for(pitch) (the force that
//     sends a ball at rest rules.push_distance when held rules.push_time),
//     the control key
//     brakes it with a force against its velocity, m·|v|/control_time at
//     most control_force (forces, not teleports); the kick key applies a
//     force of power·kick_impulse/kick_duration for kick_duration towards
//     the goal at the kick angle above the horizontal (power and angle set
//     by their keys, in steps). A kick pressed while one is still acting,
//     after the round has ended or out of reach is ignored, and the game
//     says so (ignored_kick()).
//   * the keeper (game/keeper.hpp), when the pitch has one, moves before
//     every step by its rule at the level's speed.
//   * a kick counts when the ball's centre is at least min_kick_distance
//     from the goal line when it is taken.
//   * the last touch decides: a push or a kick replaces the previous one
//     (control does not: braking a kicked ball is no touch).
//   * the ball crosses the goal line when its whole disc gets beyond the line
//     (centre more than R past it) in a step where it was not wholly beyond
//     before — i.e. through the mouth, not by dropping behind the goal — with
//     its centre below the crossbar's underside (the bar is solid, so a ball
//     crossing there passes under it). That is a goal when the last touch
//     was a counted kick, and otherwise "no goal" with the reason.
//   * other ends: saved (after a kick the ball touched the keeper and then
//     moves away from the goal), the ball at rest after a kick (speed and
//     rim speed below rest_speed for rest_time, e.g. stopped on the line;
//     before the kick a ball at rest waits for the player), out of play
//     (centre beyond pitch_min_x or pitch_max_x), round_time elapsed, the
//     reset key, or the physics diverged (the core's rule, with the work of
//     the player and of the keeper).
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
#include "game/keeper.hpp"
#include "game/pitch.hpp"
#include "game/replay.hpp"

namespace contact2d::game {

enum class Outcome {
  None,  // still playing
  Goal,
  NotKicked,     // crossed the line, but nobody kicked it
  KickTooClose,  // crossed the line after a kick taken inside min_kick_distance
  Pushed,        // crossed the line, but the last touch was a push
  Saved,         // the keeper sent it back
  Stopped,       // came to rest in play after a kick (on the line, short, on the roof)
  Out,           // left the pitch
  TimeUp,
  Reset,  // the player asked for the next pass
  Diverged,
};

// The push an arrow key applies: the constant force F that sends a ball at
// rest, rolling on the grass, rules.push_distance in all when held for
// rules.push_time and then let go, by the scene's rolling resistance
// (physics.md): rolling without slipping, the ball accelerates at
// a = F/(k·m) − d while pushed and slows at d = mu_roll·g/(k·R) after,
// k = 1 + I/(m·R²) (1.5 for the disc), so D = a·T²/2 + (a·T)²/(2·d); F =
// k·m·(a + d) with a the positive root. Without rolling resistance (d = 0)
// the ball would roll on forever: a = 2·D/T², the distance while pushed. At
// most rules.push_force. N.
double push_force_for(const Pitch& pitch);

std::string_view outcome_name(Outcome outcome);  // "goal", "kick_too_close", … (JSON)
std::string outcome_text(Outcome outcome, double min_kick_distance);  // for the screen

enum class Phase { Playing, Over };
enum class IgnoredKick { None, RoundOver, StillKicking, OutOfReach };
enum class Touch { None, Push, Kick };

struct KickRecord {
  int round = 0;            // 1-based
  long long step = 0;       // session step at which it was taken
  double time = 0.0;        // session time, s
  double round_time = 0.0;  // time since the pass, s
  double distance = 0.0;    // ball centre to the goal line, m (negative: beyond it)
  double angle = 0.0;       // degrees above the horizontal
  double power = 0.0;       // fraction of kick_impulse
  bool counted = false;
};

struct RoundRecord {
  int round = 0;
  long long start_step = 0;
  double pass_speed = 0.0;  // m/s towards the goal
  double pass_spin = 0.0;   // multiple of rolling spin
  double pass_lift = 0.0;   // m/s upwards
  Outcome outcome = Outcome::None;
  double end_time = 0.0;  // round time when it was decided, s
};

class Game {
 public:
  // `engine`: a name of the engine registry (engines/engines.hpp): ref or
  // mujoco[:MAPPING]. Throws InputError (also when the engine cannot move
  // the keeper).
  Game(Pitch pitch, const std::string& engine, std::uint64_t seed, Level level = Level::Normal);

  // Input between steps (applies from the next step on).
  void handle(Key key, bool down);
  // One physics step and the rules after it. Does nothing once diverged.
  void step();

  const Pitch& pitch() const { return pitch_; }
  std::string_view engine_name() const { return engine_name_; }
  std::uint64_t seed() const { return seed_; }
  Level level() const { return level_; }
  // Whether the level keys act now.
  bool level_open() const { return steps_ == 0 || session_finished_; }
  long long steps() const { return steps_; }
  double dt() const { return pitch_.scene.sim.dt; }
  double time() const { return static_cast<double>(steps_) * dt(); }
  double round_time() const { return static_cast<double>(steps_ - round_start_) * dt(); }
  const State& ball() const { return stepper_->state(); }
  double radius() const { return pitch_.scene.radius; }
  double distance_to_goal() const;           // ball centre to the goal line, m
  Vec3 applied() const { return applied_; }  // the force of the last step
  Vec3 push_force() const;                   // from the arrows held now (in reach or not)
  // The force one arrow pushes with: push_force_for(pitch()), or a replay's
  // own (use_push: a replay plays with the push it was recorded with).
  double push_strength() const { return push_; }
  void use_push(double newtons) { push_ = newtons; }
  bool in_reach() const { return ball().q.y() < pitch_.rules.reach_height; }
  bool controlling() const { return held_control_; }
  bool kicking() const { return kick_steps_left_ > 0; }
  double kick_angle() const { return kick_angle_; }
  double kick_power() const { return kick_power_; }
  // The velocity a kick taken now adds to the ball, m/s.
  Vec2 kick_velocity() const;
  // The keeper: whether there is one, its box now, and whether it touched
  // the ball since the last kick.
  bool has_keeper() const { return pitch_.has_keeper(); }
  const Obstacle& keeper() const { return stepper_->model().obstacles.at(keeper_index()); }
  double keeper_offset() const { return keeper_offset_; }
  bool keeper_touched() const { return keeper_touched_; }
  Phase phase() const { return phase_; }
  Touch last_touch() const { return last_touch_; }
  int round() const { return static_cast<int>(rounds_.size()); }  // 1-based, current
  const RoundRecord& current_round() const { return rounds_.back(); }
  const std::vector<RoundRecord>& rounds() const { return rounds_; }
  const std::vector<KickRecord>& kicks() const { return kicks_; }
  int goals() const;
  // The session: its number (1-based), its rounds so far, its goals, the
  // most goals of any session so far (this one included), and whether its
  // last round's result has been shown (the game then waits for reset).
  int session() const { return session_; }
  int session_round() const { return round() - session_first_round_ + 1; }
  int session_goals() const;
  int best_session_goals() const { return std::max(best_goals_, session_goals()); }
  bool session_finished() const { return session_finished_; }
  long long steps_since_end() const { return over_steps_; }
  long long result_steps() const { return result_steps_; }
  const std::optional<Divergence>& divergence() const { return divergence_; }
  double applied_work() const { return work_; }
  // The last kick key that did nothing: why, and how many steps ago (for
  // the screen); None when no kick was ignored.
  IgnoredKick ignored_kick() const { return ignored_kick_why_; }
  long long steps_since_ignored_kick() const { return steps_ - ignored_kick_step_; }
  // Steps until the next pass starts (0 while playing, or once the session
  // is finished).
  long long steps_to_next_pass() const {
    return phase_ == Phase::Over && !session_finished_ ? std::max(0LL, result_steps_ - over_steps_)
                                                       : 0;
  }

 private:
  size_t keeper_index() const { return static_cast<size_t>(pitch_.rules.keeper); }
  void move_keeper();
  Vec3 control_force() const;
  void start_round();
  void end_round(Outcome outcome);
  void apply_rules();
  double next_uniform();

  Pitch pitch_;
  std::string engine_name_;
  std::unique_ptr<Stepper> stepper_;
  std::uint64_t seed_;
  Level level_;
  std::uint64_t rng_;
  long long steps_ = 0;
  long long round_start_ = 0;
  long long kick_steps_ = 1;  // kick duration in steps
  long long rest_steps_needed_ = 0;
  long long result_steps_ = 0;
  long long round_steps_ = 0;                    // round_time in steps
  bool held_[4] = {false, false, false, false};  // left, right, up, down
  bool held_control_ = false;
  double push_ = 0.0;  // N
  double kick_angle_ = 0.0;
  double kick_power_ = 1.0;
  KeeperRule keeper_rule_;
  double keeper_offset_ = 0.0;
  bool keeper_touched_ = false;
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
  int session_ = 1;
  int session_first_round_ = 1;
  int best_goals_ = 0;  // of the sessions before this one
  bool session_finished_ = false;
};

// The path of the kick the player would take now: the ball's centre flying
// from where it is with its velocity plus kick_velocity(), without drag,
// spin or bounce (a preview, not the physics), sampled every `dt` until it
// reaches the goal line, falls back to the grass (centre at R) or `out` is
// full. Returns how many points it wrote.
int kick_preview(const Game& game, double dt, Vec2* out, int capacity);

}  // namespace contact2d::game
