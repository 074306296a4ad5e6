// Players without a keyboard, for measuring how hard the game is (`contact2d
// play --headless --policy blind|scripted --seeds N`) and for the tests.
// They press keys through the InputFeed, stamped with the physics step like
// a person's, so a policy's round is also a replay (--record-input).
//
//   blind     presses the kick key once, 0.1 s after the pass starts, and
//             nothing else (what a new player tries first).
//   scripted  receives the pass, controls it, dribbles it to
//             kScriptedDribbleTo (2.5 m) from the goal line, stops it there and chips it over the
//             keeper: among the angle and power levels it picks the one whose no-drag path
//             (kick_preview's) clears the keeper's top, as high as the keeper can have risen by
//             then at its speed, and passes under the crossbar with the largest margin at both.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "game/game.hpp"
#include "game/session.hpp"

namespace contact2d::game {

// Where the scripted player stops the ball to chip it, m from the goal line:
// close enough to beat the keeper. The one source of the number (`play
// --help` prints it; tests/game/test_play_cli.cpp checks docs/game.md's).
inline constexpr double kScriptedDribbleTo = 2.5;

enum class Policy { Blind, Scripted };
std::string_view policy_name(Policy policy);
std::optional<Policy> parse_policy(std::string_view name);

// One player for one game: call act() before every step.
class PolicyPlayer {
 public:
  explicit PolicyPlayer(Policy policy) : policy_(policy) {}
  void act(const Game& game, InputFeed& feed);
  // The scripted kick's predicted clearance (the smallest of over the
  // keeper and under the bar, m); NaN before it chose one.
  double margin() const { return margin_; }

 private:
  enum class Stage { Receive, Dribble, Settle, Aim, Done };
  void press(Key key, bool down, InputFeed& feed);
  void hold(Key key, bool down, InputFeed& feed);
  void choose_kick(const Game& game);

  Policy policy_;
  Stage stage_ = Stage::Receive;
  bool held_[static_cast<int>(Key::PowerDown) + 1] = {};
  int want_angle_steps_ = 0;  // presses of angle_up (> 0) or angle_down (< 0) still to do
  int want_power_steps_ = 0;
  bool kicked_ = false;
  double margin_ = std::numeric_limits<double>::quiet_NaN();
};

// Plays the game's current round with the policy until it ends (or the
// physics diverges); its keys go through `feed` (recorded there). `margin`:
// the scripted kick's predicted clearance (PolicyPlayer::margin).
Outcome play_policy_round(Game& game, InputFeed& feed, Policy policy, double* margin = nullptr);

// One round per seed (seeds first, first + 1, …): the policy plays until
// the round ends. Returns the rounds' outcomes in seed order.
struct PolicyRun {
  std::uint64_t seed = 0;
  Outcome outcome = Outcome::None;
  double kick_distance = -1.0;  // m from the line, −1 without a kick
  double margin = 0.0;          // scripted: the kick's predicted clearance, m (NaN: none)
};
std::vector<PolicyRun> run_policy(const Pitch& pitch, const std::string& engine, Level level,
                                  Policy policy, std::uint64_t first_seed, int seeds);

// {"policy":…,"engine":…,"level":…,"seeds":n,"goals":k,"rate":k/n,"outcomes":{…}}
// and, for the scripted player, the smallest and the median of its kicks'
// predicted clearance ("margin_min", "margin_median", m): the room for
// error the level leaves.
std::string policy_json(const std::vector<PolicyRun>& runs, Policy policy,
                        const std::string& engine, Level level);

}  // namespace contact2d::game
