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
long long steps_for(double seconds, double dt) {
  return std::max(0LL, static_cast<long long>(std::llround(seconds / dt)));
}

}  // namespace

std::string_view outcome_name(Outcome outcome) {
  switch (outcome) {
    case Outcome::None: return "playing";
    case Outcome::Goal: return "goal";
    case Outcome::NotKicked: return "not_kicked";
    case Outcome::KickTooClose: return "kick_too_close";
    case Outcome::Pushed: return "last_touch_a_push";
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

Game::Game(Pitch pitch, const std::string& engine, std::uint64_t seed)
    : pitch_(std::move(pitch)),
      engine_name_(engine),
      stepper_(make_game_stepper(engine, pitch_)),
      seed_(seed),
      rng_(seed) {
  const Rules& r = pitch_.rules;
  const double h = dt();
  kick_steps_ = std::max(1LL, steps_for(r.kick_duration, h));
  rest_steps_needed_ = std::max(1LL, steps_for(r.rest_time, h));
  result_steps_ = steps_for(r.result_time, h);
  round_steps_ = std::max(1LL, steps_for(r.round_time, h));
  kick_angle_ = r.kick_angle;
  start_round();
}

double Game::next_uniform() {
  return contact2d::next_uniform(rng_);  // [0, 1)
}

double Game::distance_to_goal() const {
  return pitch_.direction() * (pitch_.rules.goal_line - ball().q.x());
}

Vec3 Game::push_force() const {
  const double f = pitch_.rules.push_force;
  const double fx = (held_[1] ? f : 0.0) - (held_[0] ? f : 0.0);
  const double fy = (held_[2] ? f : 0.0) - (held_[3] ? f : 0.0);
  return {fx, fy, 0.0};
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
  rounds_.push_back(record);

  const double dir = pitch_.direction();
  const double rest_depth =
      scene.contact.k > 0.0 ? scene.mass * scene.sim.gravity / scene.contact.k : 0.0;
  State s;
  s.q = Vec3(r.pass_x, scene.radius - std::min(rest_depth, 0.5 * scene.radius), 0.0);
  // Rolling towards +x turns clockwise: ω = −v/R.
  s.v = Vec3(dir * record.pass_speed, 0.0,
             -dir * record.pass_spin * record.pass_speed / scene.radius);
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
    case Key::Reset:
      if (phase_ == Phase::Playing) end_round(Outcome::Reset);
      start_round();
      return;
    case Key::Kick: {
      if (phase_ != Phase::Playing || kick_steps_left_ > 0) {
        // Shown on screen (ignored_kick()): the key was seen, and why nothing happened.
        ignored_kick_step_ = steps_;
        ignored_kick_why_ =
            phase_ != Phase::Playing ? IgnoredKick::RoundOver : IgnoredKick::StillKicking;
        return;
      }
      KickRecord kick;
      kick.round = round();
      kick.step = steps_;
      kick.time = time();
      kick.round_time = round_time();
      kick.distance = distance_to_goal();
      kick.angle = kick_angle_;
      kick.counted = kick.distance >= r.min_kick_distance;
      kicks_.push_back(kick);
      const double a = kick_angle_ * kPi / 180.0;
      // The whole impulse over kick_steps_ steps.
      const double force = r.kick_impulse / (static_cast<double>(kick_steps_) * dt());
      kick_force_ = Vec3(pitch_.direction() * force * std::cos(a), force * std::sin(a), 0.0);
      kick_steps_left_ = kick_steps_;
      last_touch_ = Touch::Kick;
      last_kick_counted_ = kick.counted;
      return;
    }
    default: return;
  }
}

void Game::step() {
  if (divergence_) return;
  Vec3 force = push_force();
  const bool pushing = force.x() != 0.0 || force.y() != 0.0;
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
  divergence_ = check_step(status, *stepper_, *monitor_, round_time(), work_);
  if (divergence_) {
    if (phase_ == Phase::Playing) end_round(Outcome::Diverged);
    return;
  }

  if (phase_ == Phase::Over) {
    if (++over_steps_ >= result_steps_) start_round();
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
  if (s.q.x() < r.pitch_min_x || s.q.x() > r.pitch_max_x) {
    end_round(Outcome::Out);
    return;
  }
  const bool still =
      std::hypot(s.v.x(), s.v.y()) < r.rest_speed && std::abs(s.v.z()) * radius < r.rest_speed;
  // A ball being pushed or kicked is not at rest, however slow.
  rest_steps_ = still && applied_.isZero() ? rest_steps_ + 1 : 0;
  if (rest_steps_ >= rest_steps_needed_) {
    end_round(Outcome::Stopped);
    return;
  }
  if (steps_ - round_start_ >= round_steps_) end_round(Outcome::TimeUp);
}

}  // namespace contact2d::game
