// The session's JSON line agrees with itself: "goal" and "outcome" are the
// last round's, "goals" counts them all.
#include <gtest/gtest.h>

#include <string>

#include "game/game.hpp"
#include "game/policy.hpp"
#include "game/session.hpp"

namespace contact2d::game {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Two rounds of one session, by the built-in players in this order.
std::string two_rounds(Policy first, Policy second) {
  Game game(default_pitch(), "ref", 1);
  InputFeed feed(game, nullptr);
  play_policy_round(game, feed, first);
  while (game.round() == 1) game.step();  // the result's 2 s, then the next pass
  play_policy_round(game, feed, second);
  return report_json(game);
}

// The issue: a goal, then a miss, printed "goal":true beside "outcome":"saved".
// (The blind kick keeps the scripted player's 45° at full power here: it
// goes out of play.)
TEST(SessionJson, GoalIsTheLastRoundsOutcomeAsOutcomeIs) {
  const std::string goal_then_miss = two_rounds(Policy::Scripted, Policy::Blind);
  EXPECT_TRUE(contains(goal_then_miss, "\"goal\":false,\"goals\":1,\"outcome\":\""))
      << goal_then_miss;
  EXPECT_FALSE(contains(goal_then_miss, "\"outcome\":\"goal\",\"kicks\"")) << goal_then_miss;
  const std::string save_then_goal = two_rounds(Policy::Blind, Policy::Scripted);
  EXPECT_TRUE(contains(save_then_goal, "\"goal\":true,\"goals\":1,\"outcome\":\"goal\""))
      << save_then_goal;
}

}  // namespace
}  // namespace contact2d::game
