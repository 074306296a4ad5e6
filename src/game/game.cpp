#include "game/game.hpp"

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "engines/engines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contact2d::game {
namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64 (Steele, Lea, Flood 2014): a fixed, portable sequence, unlike
// the standard library's distributions.
long long steps_for(double seconds, double dt) { return std::max(0LL, std::llround(seconds / dt)); }

}  // namespace

double push_force_for(const Pitch& pitch) {
  const Scene& scene = pitch.scene;
  const Rules& r = pitch.rules;
  const double m = scene.mass, radius = scene.radius;
  const double k = 1.0 + make_body(scene).inertia / (m * radius * radius);
  const double d = scene.contact.mu_roll * scene.sim.gravity / (k * radius);
  const double t2 = r.push_time * r.push_time, distance = r.push_distance;
  // a·T²/2 + a²·T²/(2·d) = D: the positive root.
  const double a =
      d > 0.0 ? (-0.5 * t2 + std::sqrt(0.25 * t2 * t2 + 2.0 * t2 * distance / d)) / (t2 / d)
              : 2.0 * distance / t2;
  return std::min(r.push_force, k * m * (a + d));
}

std::string_view outcome_name(Outcome outcome) {
  switch (outcome) {
    case Outcome::None: return "playing";
    case Outcome::Goal: return "goal";
    case Outcome::NotKicked: return "not_kicked";
    case Outcome::KickTooClose: return "kick_too_close";
    case Outcome::Pushed: return "last_touch_a_push";
    case Outcome::Saved: return "saved";
    case Outcome::Stopped: return "ball_stopped";
    case Outcome::Out: return "out_of_play";
    case Outcome::TimeUp: return "time_up";
    case Outcome::Reset: return "reset";
    case Outcome::Diverged: return "diverged";
  }
  return "?";
}

std::string outcome_text(Outcome outcome, double min_kick_distance) {
  const std::string distance = format_number("%g m", min_kick_distance);
  switch (outcome) {
    case Outcome::None: return "";
    case Outcome::Goal: return "GOAL!";
    case Outcome::NotKicked: return "No goal: nobody kicked it in";
    case Outcome::KickTooClose: return std::string("No goal: the kick was inside ") + distance;
    case Outcome::Pushed: return "No goal: the last touch was a push, not a kick";
    case Outcome::Saved: return "Saved by the keeper";
    case Outcome::Stopped: return "No goal: the ball stopped";
    case Outcome::Out: return "No goal: out of play";
    case Outcome::TimeUp: return "No goal: time up";
    case Outcome::Reset: return "Reset";
    case Outcome::Diverged: return "The simulation diverged";
  }
  return "";
}

namespace {

// Either engine: the MuJoCo model carries the goal's obstacles with their
// own laws (mujoco/mjcf.hpp) and takes the player's force as xfrc_applied on
// the ball (MujocoStepper::set_applied), the same force profile step by step.
std::unique_ptr<Stepper> make_game_stepper(const std::string& engine, const Pitch& pitch) {
  engines::EngineSpec spec = engines::parse_engine(engine);
  spec.source = pitch.path;
  return engines::make_stepper(spec, pitch.scene);
}

}  // namespace

Game::Game(Pitch pitch, const std::string& engine, std::uint64_t seed, Level level)
    : pitch_(std::move(pitch)),
      engine_name_(engine),
      stepper_(make_game_stepper(engine, pitch_)),
      seed_(seed),
      level_(level),
      rng_(seed) {
  push_ = push_force_for(pitch_);
  const Rules& r = pitch_.rules;
  const double h = dt();
  kick_steps_ = std::max(1LL, steps_for(r.kick_duration, h));
  rest_steps_needed_ = std::max(1LL, steps_for(r.rest_time, h));
  result_steps_ = steps_for(r.result_time, h);
  round_steps_ = std::max(1LL, steps_for(r.round_time, h));
  kick_angle_ = r.kick_angle;
  kick_power_ = r.kick_power;
  if (pitch_.has_keeper()) {
    if (!stepper_->move_obstacle(r.keeper, Vec2::Zero())) {
      throw InputError("--engine " + engine +
                       ": this engine cannot move the keeper (game.keeper = " +
                       std::to_string(r.keeper) + "); play on ref or mujoco");
    }
    const Obstacle& k = pitch_.scene.obstacles[keeper_index()];
    keeper_rule_.direction = pitch_.direction();
    keeper_rule_.face_x = keeper_rule_.direction > 0.0 ? k.a.x() : k.b.x();
    keeper_rule_.centre_y = 0.5 * (k.a.y() + k.b.y());
    keeper_rule_.max_offset = std::max(0.0, pitch_.crossbar_bottom() - k.b.y());
    keeper_rule_.speed = pitch_.keeper_speed(level_);
    keeper_rule_.gravity = pitch_.scene.sim.gravity;
    keeper_rule_.radius = pitch_.scene.radius;
  }
  start_round();
}

double Game::next_uniform() {
  return contact2d::next_uniform(rng_);  // [0, 1)
}

double Game::distance_to_goal() const {
  return pitch_.direction() * (pitch_.rules.goal_line - ball().q.x());
}

Vec3 Game::push_force() const {
  const double f = push_;
  const double fx = (held_[1] ? f : 0.0) - (held_[0] ? f : 0.0);
  const double fy = (held_[2] ? f : 0.0) - (held_[3] ? f : 0.0);
  return {fx, fy, 0.0};
}

Vec2 Game::kick_velocity() const {
  const double a = kick_angle_ * kPi / 180.0;
  const double dv = kick_power_ * pitch_.rules.kick_impulse / pitch_.scene.mass;
  return {pitch_.direction() * dv * std::cos(a), dv * std::sin(a)};
}

Vec3 Game::control_force() const {
  if (!held_control_) return Vec3::Zero();
  const State& s = ball();
  const double speed = std::hypot(s.v.x(), s.v.y());
  if (speed == 0.0) return Vec3::Zero();
  const double r =
      std::min(pitch_.rules.control_force, pitch_.scene.mass * speed / pitch_.rules.control_time);
  return {-r * s.v.x() / speed, -r * s.v.y() / speed, 0.0};
}

int Game::session_goals() const {
  return static_cast<int>(
      std::count_if(rounds_.begin() + (session_first_round_ - 1), rounds_.end(),
                    [](const RoundRecord& r) { return r.outcome == Outcome::Goal; }));
}

int Game::goals() const {
  return static_cast<int>(std::count_if(rounds_.begin(), rounds_.end(), [](const RoundRecord& r) {
    return r.outcome == Outcome::Goal;
  }));
}

void Game::start_round() {
  const Rules& r = pitch_.rules;
  const Scene& scene = pitch_.scene;
  RoundRecord record;
  record.round = static_cast<int>(rounds_.size()) + 1;
  record.start_step = steps_;
  record.pass_speed = r.pass_speed_min + (r.pass_speed_max - r.pass_speed_min) * next_uniform();
  record.pass_spin = r.pass_spin_min + (r.pass_spin_max - r.pass_spin_min) * next_uniform();
  record.pass_lift = r.pass_lift_min + (r.pass_lift_max - r.pass_lift_min) * next_uniform();
  rounds_.push_back(record);

  const double dir = pitch_.direction();
  const double rest_depth =
      scene.contact.k > 0.0 ? scene.mass * scene.sim.gravity / scene.contact.k : 0.0;
  State s;
  s.q = Vec3(r.pass_x, scene.radius - std::min(rest_depth, 0.5 * scene.radius), 0.0);
  // Rolling towards +x turns clockwise: ω = −v/R.
  s.v = Vec3(dir * record.pass_speed, record.pass_lift,
             -dir * record.pass_spin * record.pass_speed / scene.radius);
  keeper_offset_ = 0.0;  // back on its spot for each pass
  if (pitch_.has_keeper()) stepper_->move_obstacle(r.keeper, Vec2::Zero());
  keeper_touched_ = false;
  stepper_->reset(s);
  monitor_ = std::make_unique<DivergenceMonitor>(stepper_->model(), s, stepper_->contacts());
  round_start_ = steps_;
  work_ = 0.0;
  kick_steps_left_ = 0;
  phase_ = Phase::Playing;
  last_touch_ = Touch::None;
  last_kick_counted_ = false;
  wholly_beyond_ = dir * (s.q.x() - r.goal_line) > scene.radius;
  rest_steps_ = 0;
  over_steps_ = 0;
}

void Game::end_round(Outcome outcome) {
  phase_ = Phase::Over;
  over_steps_ = 0;
  rounds_.back().outcome = outcome;
  rounds_.back().end_time = round_time();
}

void Game::handle(Key key, bool down) {
  switch (key) {
    case Key::Left: held_[0] = down; return;
    case Key::Right: held_[1] = down; return;
    case Key::Up: held_[2] = down; return;
    case Key::Down: held_[3] = down; return;
    case Key::Control: held_control_ = down; return;
    default: break;
  }
  if (!down || divergence_) return;
  const Rules& r = pitch_.rules;
  switch (key) {
    case Key::AngleUp:
      kick_angle_ = std::min(r.kick_angle_max, kick_angle_ + r.kick_angle_step);
      return;
    case Key::AngleDown:
      kick_angle_ = std::max(r.kick_angle_min, kick_angle_ - r.kick_angle_step);
      return;
    case Key::PowerUp: kick_power_ = std::min(1.0, kick_power_ + r.kick_power_step); return;
    case Key::PowerDown:
      kick_power_ = std::max(r.kick_power_min, kick_power_ - r.kick_power_step);
      return;
    case Key::LevelEasy:
    case Key::LevelNormal:
    case Key::LevelHard:
      if (level_open()) {
        level_ = key == Key::LevelEasy     ? Level::Easy
                 : key == Key::LevelNormal ? Level::Normal
                                           : Level::Hard;
        keeper_rule_.speed = pitch_.keeper_speed(level_);
      }
      return;
    case Key::Reset:
      if (phase_ == Phase::Playing) end_round(Outcome::Reset);
      if (session_finished_ || session_round() >= r.session_rounds) {
        // A new session (the reset of a last round ends its session too).
        best_goals_ = best_session_goals();
        ++session_;
        session_first_round_ = round() + 1;
        session_finished_ = false;
      }
      start_round();
      return;
    case Key::Kick: {
      if (phase_ != Phase::Playing || kick_steps_left_ > 0 || !in_reach()) {
        // Shown on screen (ignored_kick()): the key was seen, and why nothing happened.
        ignored_kick_step_ = steps_;
        ignored_kick_why_ = phase_ != Phase::Playing ? IgnoredKick::RoundOver
                            : kick_steps_left_ > 0   ? IgnoredKick::StillKicking
                                                     : IgnoredKick::OutOfReach;
        return;
      }
      KickRecord kick;
      kick.round = round();
      kick.step = steps_;
      kick.time = time();
      kick.round_time = round_time();
      kick.distance = distance_to_goal();
      kick.angle = kick_angle_;
      kick.power = kick_power_;
      kick.counted = kick.distance >= r.min_kick_distance;
      kicks_.push_back(kick);
      // The whole impulse over kick_steps_ steps.
      const Vec2 dv = kick_velocity();
      const double per_step = pitch_.scene.mass / (static_cast<double>(kick_steps_) * dt());
      kick_force_ = Vec3(dv.x() * per_step, dv.y() * per_step, 0.0);
      kick_steps_left_ = kick_steps_;
      keeper_touched_ = false;
      last_touch_ = Touch::Kick;
      last_kick_counted_ = kick.counted;
      return;
    }
    default: return;
  }
}

void Game::move_keeper() {
  keeper_offset_ = keeper_step(keeper_rule_, keeper_offset_, ball(), dt());
  stepper_->move_obstacle(pitch_.rules.keeper, Vec2(0.0, keeper_offset_));
}

void Game::step() {
  if (divergence_) return;
  // The player reaches the ball only within reach; a kick already started
  // goes on (it is the foot's follow-through).
  const bool reach = in_reach();
  Vec3 force = reach ? push_force() : Vec3::Zero();
  const bool pushing = force.x() != 0.0 || force.y() != 0.0;
  if (reach) force += control_force();
  const double keeper_before = keeper_offset_;
  if (pitch_.has_keeper()) move_keeper();
  if (kick_steps_left_ > 0) {
    force += kick_force_;
    --kick_steps_left_;
  }
  applied_ = force;
  stepper_->set_applied(force);
  const State before = stepper_->state();
  const StepStatus status = stepper_->step();
  ++steps_;
  const State& s = stepper_->state();
  // |work| of the applied force over the step, summed as an upper bound of
  // the net work the divergence rule may credit.
  work_ += std::abs(force.x() * (s.q.x() - before.q.x()) + force.y() * (s.q.y() - before.q.y()) +
                    force.z() * (s.q.z() - before.q.z()));
  if (pitch_.has_keeper()) {
    // The keeper's contacts, and a bound of the work its move did on the ball: its
    // contact force (spring, damper and friction, |F| ≤ (1 + μ)(k·d + c·|v_n|)) times
    // how far it moved.
    const double moved = std::abs(keeper_offset_ - keeper_before);
    for (const Contact& c : stepper_->contacts()) {
      if (c.obstacle != pitch_.rules.keeper) continue;
      keeper_touched_ = true;
      const ContactParams& law = stepper_->model().law(c);
      const double vn = (s.v.x() - s.v.z() * c.ry) * c.nx + (s.v.y() + s.v.z() * c.rx) * c.ny;
      work_ += (1.0 + law.mu) * (law.k * c.depth + law.c * std::abs(vn)) * moved;
    }
  }
  divergence_ = check_step(status, *stepper_, *monitor_, round_time(), work_);
  if (divergence_) {
    if (phase_ == Phase::Playing) end_round(Outcome::Diverged);
    return;
  }

  if (phase_ == Phase::Over) {
    if (++over_steps_ >= result_steps_ && !session_finished_) {
      if (session_round() >= pitch_.rules.session_rounds) {
        session_finished_ = true;  // the ball stays where it is until reset
      } else {
        start_round();
      }
    }
    return;
  }
  if (pushing) last_touch_ = Touch::Push;
  apply_rules();
}

void Game::apply_rules() {
  const Rules& r = pitch_.rules;
  const State& s = ball();
  const double radius = pitch_.scene.radius;
  const bool beyond = pitch_.direction() * (s.q.x() - r.goal_line) > radius;
  const bool crossed = beyond && !wholly_beyond_;
  wholly_beyond_ = beyond;
  if (crossed && s.q.y() < pitch_.crossbar_bottom()) {
    if (last_touch_ == Touch::Kick) {
      end_round(last_kick_counted_ ? Outcome::Goal : Outcome::KickTooClose);
    } else {
      end_round(last_touch_ == Touch::Push ? Outcome::Pushed : Outcome::NotKicked);
    }
    return;
  }
  if (last_touch_ == Touch::Kick && keeper_touched_ && pitch_.direction() * s.v.x() < 0.0) {
    end_round(Outcome::Saved);
    return;
  }
  if (s.q.x() < r.pitch_min_x || s.q.x() > r.pitch_max_x) {
    end_round(Outcome::Out);
    return;
  }
  const bool still =
      std::hypot(s.v.x(), s.v.y()) < r.rest_speed && std::abs(s.v.z()) * radius < r.rest_speed;
  // A ball being pushed or kicked is not at rest, however slow.
  rest_steps_ = still && applied_.isZero() ? rest_steps_ + 1 : 0;
  // Before a kick a ball at rest waits for the player.
  if (rest_steps_ >= rest_steps_needed_ && last_touch_ == Touch::Kick) {
    end_round(Outcome::Stopped);
    return;
  }
  if (steps_ - round_start_ >= round_steps_) end_round(Outcome::TimeUp);
}

int kick_preview(const Game& game, double dt, Vec2* out, int capacity) {
  const Pitch& pitch = game.pitch();
  const State& s = game.ball();
  const Vec2 v = Vec2(s.v.x(), s.v.y()) + game.kick_velocity();
  const double g = pitch.scene.sim.gravity, radius = pitch.scene.radius;
  int n = 0;
  for (; n < capacity; ++n) {
    const double t = n * dt;
    const Vec2 p(s.q.x() + v.x() * t, s.q.y() + v.y() * t - 0.5 * g * t * t);
    out[n] = p;
    if (n > 0 && (pitch.direction() * (p.x() - pitch.rules.goal_line) > 0.0 || p.y() < radius)) {
      return n + 1;
    }
  }
  return n;
}

}  // namespace contact2d::game
