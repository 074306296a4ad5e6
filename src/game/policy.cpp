#include "game/policy.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/format.hpp"
#include "io/json.hpp"

namespace contact2d::game {
namespace {

constexpr double kBlindKickTime = 0.1;             // s after the pass
constexpr double kDribbleTo = kScriptedDribbleTo;  // m from the goal line
constexpr double kDribbleTolerance = 0.05;         // m
constexpr double kDribbleSpeed = 1.5;              // m/s at most while dribbling
constexpr double kStill = 0.02;                    // m/s: ball and rim slower than this: settled

double speed(const State& s) { return std::hypot(s.v.x(), s.v.y()); }
bool still(const Game& game) {
  const State& s = game.ball();
  return speed(s) < kStill && std::abs(s.v.z()) * game.radius() < kStill;
}

// How well a kick of velocity v from p beats the keeper and the bar, by its
// no-drag path: the smallest of its clearance over the keeper's top (at the
// keeper's front and back faces, the keeper rising at its speed from the
// kick on until its centre reaches the height the ball will pass at) and
// under the bar (at the bar's front face and at the goal line), m.
double kick_margin(const Game& game, const Vec2& p, const Vec2& v) {
  const Pitch& pitch = game.pitch();
  const double g = pitch.scene.sim.gravity, radius = pitch.scene.radius;
  const double dir = pitch.direction();
  const double vx = dir * v.x();
  if (vx <= 0.0) return -1e9;
  auto height = [&](double x) {
    const double t = dir * (x - p.x()) / vx;
    return std::pair<double, double>{t, p.y() + v.y() * t - 0.5 * g * t * t};
  };
  const Obstacle& bar = pitch.scene.obstacles[static_cast<size_t>(pitch.rules.crossbar)];
  const double bar_front = dir > 0.0 ? bar.a.x() : bar.b.x();
  const double under = pitch.crossbar_bottom() - radius;
  double margin =
      std::min(under - height(bar_front).second, under - height(pitch.rules.goal_line).second);
  margin = std::min(margin, height(pitch.rules.goal_line).second - radius);  // not on the grass
  if (game.has_keeper()) {
    const Obstacle& k = game.keeper();
    const double front = dir > 0.0 ? k.a.x() : k.b.x(), back = dir > 0.0 ? k.b.x() : k.a.x();
    const double half = 0.5 * (k.b.y() - k.a.y());
    const double centre = 0.5 * (k.a.y() + k.b.y());
    const double highest = pitch.crossbar_bottom() - half;       // the centre's highest
    const double aim = std::min(highest, height(front).second);  // where it heads
    const double speed = pitch.keeper_speed(game.level());
    for (double x : {front, back}) {
      const auto [t, y] = height(x);
      const double c = std::min(std::max(centre, aim), centre + speed * t);
      margin = std::min(margin, y - radius - (c + half));
    }
  }
  return margin;
}

}  // namespace

std::string_view policy_name(Policy policy) {
  return policy == Policy::Blind ? "blind" : "scripted";
}

std::optional<Policy> parse_policy(std::string_view name) {
  if (name == "blind") return Policy::Blind;
  if (name == "scripted") return Policy::Scripted;
  return std::nullopt;
}

void PolicyPlayer::hold(Key key, bool down, InputFeed& feed) {
  bool& held = held_[static_cast<int>(key)];
  if (held == down) return;
  held = down;
  feed.live(key, down);
}

void PolicyPlayer::press(Key key, bool down, InputFeed& feed) { hold(key, down, feed); }

void PolicyPlayer::choose_kick(const Game& game) {
  const Rules& r = game.pitch().rules;
  const State& s = game.ball();
  const Vec2 p(s.q.x(), s.q.y());
  const double mass = game.pitch().scene.mass;
  const double dir = game.pitch().direction();
  double best = -1e18;
  // The angles and powers the keys reach from the present ones.
  for (int i = -40; i <= 40; ++i) {
    const double angle =
        std::clamp(game.kick_angle() + i * r.kick_angle_step, r.kick_angle_min, r.kick_angle_max);
    if (i != 0 &&
        angle == std::clamp(game.kick_angle() + (i > 0 ? i - 1 : i + 1) * r.kick_angle_step,
                            r.kick_angle_min, r.kick_angle_max))
      continue;  // clamped: the same angle as one press fewer
    for (int j = -20; j <= 20; ++j) {
      const double power =
          std::clamp(game.kick_power() + j * r.kick_power_step, r.kick_power_min, 1.0);
      if (j != 0 &&
          power == std::clamp(game.kick_power() + (j > 0 ? j - 1 : j + 1) * r.kick_power_step,
                              r.kick_power_min, 1.0))
        continue;
      const double a = angle * 3.14159265358979323846 / 180.0;
      const double dv = power * r.kick_impulse / mass;
      const Vec2 v(s.v.x() + dir * dv * std::cos(a), s.v.y() + dv * std::sin(a));
      const double m = kick_margin(game, p, v);
      if (m > best) {
        best = m;
        margin_ = m;
        want_angle_steps_ = i;
        want_power_steps_ = j;
      }
    }
  }
}

void PolicyPlayer::act(const Game& game, InputFeed& feed) {
  if (game.phase() != Phase::Playing) return;
  // A tap's key goes up the step after it went down.
  for (Key key : {Key::Kick, Key::AngleUp, Key::AngleDown, Key::PowerUp, Key::PowerDown}) {
    if (held_[static_cast<int>(key)]) {
      hold(key, false, feed);
      return;
    }
  }
  if (policy_ == Policy::Blind) {
    if (!kicked_ && game.round_time() >= kBlindKickTime) {
      press(Key::Kick, true, feed);
      kicked_ = true;
    }
    return;
  }
  const double dir = game.pitch().direction();
  const Key towards = dir > 0.0 ? Key::Right : Key::Left;
  const Key away = dir > 0.0 ? Key::Left : Key::Right;
  const State& s = game.ball();
  switch (stage_) {
    case Stage::Receive:
      // Brake the pass as soon as it is in reach; once it is still, dribble.
      hold(Key::Control, game.in_reach(), feed);
      if (game.in_reach() && still(game)) {
        hold(Key::Control, false, feed);
        stage_ = Stage::Dribble;
      }
      return;
    case Stage::Dribble: {
      // Towards kDribbleTo at a speed that the control key can brake in
      // the distance left (half its deceleration, for margin).
      const double gap = game.distance_to_goal() - kDribbleTo;  // > 0: still too far
      const double brake = 0.5 * game.pitch().rules.control_force / game.pitch().scene.mass;
      const double want =
          std::copysign(std::min(kDribbleSpeed, std::sqrt(2.0 * brake * std::abs(gap))), gap);
      const double v = dir * s.v.x();  // towards the goal
      // With hysteresis (start 0.1 m/s off the wanted speed, stop at it): a
      // key held for a while, not toggled every step.
      const bool push_towards = held_[static_cast<int>(towards)];
      const bool push_away = held_[static_cast<int>(away)];
      const bool braking = held_[static_cast<int>(Key::Control)];
      hold(towards, push_towards ? v < want : v < want - 0.1, feed);
      hold(away, want < 0.0 && (push_away ? v > want : v > want + 0.1), feed);
      hold(Key::Control, want >= 0.0 && (braking ? v > want : v > want + 0.1), feed);
      if (std::abs(gap) < kDribbleTolerance) {
        hold(towards, false, feed);
        hold(away, false, feed);
        stage_ = Stage::Settle;
      }
      return;
    }
    case Stage::Settle:
      hold(Key::Control, true, feed);
      if (still(game)) {
        hold(Key::Control, false, feed);
        choose_kick(game);
        stage_ = Stage::Aim;
      }
      return;
    case Stage::Aim:
      if (want_angle_steps_ != 0) {
        press(want_angle_steps_ > 0 ? Key::AngleUp : Key::AngleDown, true, feed);
        want_angle_steps_ += want_angle_steps_ > 0 ? -1 : 1;
      } else if (want_power_steps_ != 0) {
        press(want_power_steps_ > 0 ? Key::PowerUp : Key::PowerDown, true, feed);
        want_power_steps_ += want_power_steps_ > 0 ? -1 : 1;
      } else {
        press(Key::Kick, true, feed);
        kicked_ = true;
        stage_ = Stage::Done;
      }
      return;
    case Stage::Done: return;
  }
}

Outcome play_policy_round(Game& game, InputFeed& feed, Policy policy, double* margin) {
  PolicyPlayer player(policy);
  const int round = game.round();
  while (!game.divergence() && game.round() == round && game.phase() == Phase::Playing) {
    player.act(game, feed);
    game.step();
  }
  if (margin) *margin = player.margin();
  return game.rounds().at(static_cast<size_t>(round - 1)).outcome;
}

std::vector<PolicyRun> run_policy(const Pitch& pitch, const std::string& engine, Level level,
                                  Policy policy, std::uint64_t first_seed, int seeds) {
  std::vector<PolicyRun> runs;
  for (int i = 0; i < seeds; ++i) {
    const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
    Game game(pitch, engine, seed, level);
    InputFeed feed(game, nullptr);
    PolicyRun run;
    run.seed = seed;
    run.outcome = play_policy_round(game, feed, policy, &run.margin);
    if (!game.kicks().empty()) run.kick_distance = game.kicks().back().distance;
    runs.push_back(run);
  }
  return runs;
}

std::string policy_json(const std::vector<PolicyRun>& runs, Policy policy,
                        const std::string& engine, Level level) {
  std::map<std::string, int> outcomes;
  int goals = 0;
  for (const PolicyRun& r : runs) {
    ++outcomes[std::string(outcome_name(r.outcome))];
    goals += r.outcome == Outcome::Goal ? 1 : 0;
  }
  const int n = static_cast<int>(runs.size());
  std::string out = "{\"policy\":" + json::string(std::string(policy_name(policy)));
  out += ",\"engine\":" + json::string(engine);
  out += ",\"level\":" + json::string(std::string(level_name(level)));
  out += ",\"first_seed\":" + std::to_string(runs.empty() ? 0 : runs.front().seed);
  out += ",\"seeds\":" + std::to_string(n) + ",\"goals\":" + std::to_string(goals);
  out += ",\"rate\":" + json::number(n > 0 ? static_cast<double>(goals) / n : 0.0, 4);
  out += ",\"outcomes\":{";
  bool first = true;
  for (const auto& [name, count] : outcomes) {
    out += (first ? "" : ",") + json::string(name) + ":" + std::to_string(count);
    first = false;
  }
  out += "}";
  std::vector<double> margins;
  for (const PolicyRun& r : runs) {
    if (!std::isnan(r.margin)) margins.push_back(r.margin);
  }
  if (!margins.empty()) {
    std::sort(margins.begin(), margins.end());
    out += ",\"margin_min\":" + json::number(margins.front(), 4) +
           ",\"margin_median\":" + json::number(margins[margins.size() / 2], 4);
  }
  out += "}";
  return out;
}

}  // namespace contact2d::game
