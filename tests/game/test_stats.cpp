// How hard the game is, measured by the built-in players (game/policy.hpp)
// on the seeds 1, 2, …, n at the default level: one blind kick at 0.1 s
// must score on at most 5 % of the passes, the scripted player (controls,
// dribbles to 2.5 m, chips the keeper) on at least 50 %, on both engines.
// The full measure is 100 seeds per engine (`contact2d play --headless
// --policy blind|scripted --seeds 100 [--engine mujoco]`, docs/game.md has
// its figures). Here the reference plays the same 100 seeds (6 s in
// Release) and MuJoCo, ~25× slower per step at the pitch's Δt, fewer
// (15 s); label game_stats, which scripts/test leaves out of the sanitizer
// stage (there they would cost ten times as much).
//
// What n seeds show: every seed here is a different pass, and a policy is
// deterministic, so the rate is exact for these seeds; as an estimate of
// the rate over all passes, 0 goals in n blind kicks puts it below 3/n at
// 95 % confidence (the rule of three: 3 % for n = 100, 7.5 % for n = 40),
// and n goals in n scripted rounds above 0.05^(1/n) (97 % for 100, 69 %
// for 8).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "engines/engines.hpp"
#include "game/policy.hpp"
#include "support/needs.hpp"

namespace contact2d::game {
namespace {

double goal_rate(const std::string& engine, Policy policy, int seeds) {
  const auto runs = run_policy(default_pitch(), engine, Level::Normal, policy, 1, seeds);
  std::printf("%s\n", policy_json(runs, policy, engine, Level::Normal).c_str());
  int goals = 0;
  for (const PolicyRun& r : runs) goals += r.outcome == Outcome::Goal ? 1 : 0;
  return static_cast<double>(goals) / seeds;
}

TEST(GameStats, ABlindKickRarelyScoresOnTheReference) {
  EXPECT_LE(goal_rate("ref", Policy::Blind, 100), 0.05);
}

TEST(GameStats, TheScriptedPlayerScoresOnTheReference) {
  EXPECT_GE(goal_rate("ref", Policy::Scripted, 100), 0.5);
}

TEST(GameStats, ABlindKickRarelyScoresOnMujoco) {
  CONTACT2D_NEEDS(engines::mujoco_available(), "MuJoCo not built in");
  EXPECT_LE(goal_rate("mujoco", Policy::Blind, 40), 0.05);
}

TEST(GameStats, TheScriptedPlayerScoresOnMujoco) {
  CONTACT2D_NEEDS(engines::mujoco_available(), "MuJoCo not built in");
  EXPECT_GE(goal_rate("mujoco", Policy::Scripted, 8), 0.5);
}

}  // namespace
}  // namespace contact2d::game
