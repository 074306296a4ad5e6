// The keeper: its rule (keeper.hpp) against hand-computed values, and the
// keeper in the physics on both engines: the ball bounces off it, it rises
// to a shot from far and saves it, a chip from close beats it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/impact.hpp"
#include "engines/engines.hpp"
#include "game/game.hpp"
#include "game/keeper.hpp"
#include "game/pitches.hpp"
#include "game/policy.hpp"
#include "game/session.hpp"

namespace contact2d::game {
namespace {

std::vector<std::string> keeper_engines() {
  std::vector<std::string> out{"ref"};
  if (engines::mujoco_available()) out.emplace_back("mujoco");
  return out;
}

// The built-in keeper: face at x = 9.45 m, centre 0.45 m, up to 1.54 m
// (its top from 0.9 m to the bar's underside at 2.44 m).
KeeperRule built_in_rule(double speed) {
  KeeperRule r;
  r.face_x = 9.45;
  r.centre_y = 0.45;
  r.max_offset = 1.54;
  r.speed = speed;
  r.gravity = 9.81;
  r.radius = 0.11;
  return r;
}

State ball_at(double x, double y, double vx, double vy) {
  State s;
  s.q = Vec3(x, y, 0.0);
  s.v = Vec3(vx, vy, 0.0);
  return s;
}

TEST(KeeperRule, ItHeadsForWhereTheBallWouldReachItsFace) {
  const KeeperRule r = built_in_rule(2.0);
  // 4 m from the face at 8 m/s: t = 0.5 s, y = 0.11 + 6·0.5 − 9.81·0.125
  // = 1.88375 m, an offset of 1.43375 m.
  EXPECT_NEAR(keeper_target(r, ball_at(5.45, 0.11, 8.0, 6.0)), 1.43375, 1e-12);
  // At 4 m/s: t = 1 s, y = 0.11 + 4 − 4.905 < R: it would bounce first;
  // the keeper stays down (offset of R − 0.45 < 0, clamped to 0).
  EXPECT_EQ(keeper_target(r, ball_at(5.45, 0.11, 4.0, 4.0)), 0.0);
  // Too high for it: up to the bar only.
  EXPECT_EQ(keeper_target(r, ball_at(5.45, 0.11, 8.0, 20.0)), 1.54);
  // Not coming: the ball's own height (1.2 − 0.45 = 0.75).
  EXPECT_NEAR(keeper_target(r, ball_at(5.45, 1.2, -1.0, 0.0)), 0.75, 1e-12);
  // Past the face: its own height too.
  EXPECT_NEAR(keeper_target(r, ball_at(9.6, 1.2, 3.0, 0.0)), 0.75, 1e-12);
}

TEST(KeeperRule, ItMovesAtMostItsSpeed) {
  const KeeperRule r = built_in_rule(2.0);
  const State high = ball_at(5.45, 0.11, 8.0, 6.0);  // target 1.43375
  const double dt = 1e-3;
  EXPECT_NEAR(keeper_step(r, 0.0, high, dt), 2.0 * dt, 1e-15);
  EXPECT_NEAR(keeper_step(r, 1.0, ball_at(5.0, 0.11, 0.0, 0.0), dt), 1.0 - 2.0 * dt, 1e-15);
  EXPECT_EQ(keeper_step(r, 1.43375 - 1e-4, high, dt), keeper_target(r, high)) << "no overshoot";
}

struct Shot {
  Outcome outcome = Outcome::None;
  bool touched = false;  // the ball touched the keeper
  double vx_in = 0.0;    // the step before the first touch
  double vx_out = 0.0;   // when the ball left the keeper's face (NaN if it never did)
  double highest = 0.0;  // the keeper's largest offset, m
};

Shot shoot(const std::string& engine, double x0, double angle, bool keeper = true) {
  Pitch p = testing::still_ball(x0, angle);
  if (keeper) {
    p = default_pitch();
    const Pitch still = testing::still_ball(x0, angle);
    p.rules = Rules(still.rules);
    p.rules.keeper = default_pitch().rules.keeper;
  }
  Game game(p, engine, 1);
  game.handle(Key::Kick, true);
  Shot s;
  s.vx_out = std::nan("");
  const double face = game.has_keeper() ? game.keeper().a.x() : 0.0;
  // Through the round and 0.05 s of its result phase (a save ends the round
  // as the ball turns back, inside the contact, which lasts π/√(k/m) =
  // 6.5 ms: pitch.toml).
  long long after = 0;
  while (game.phase() == Phase::Playing || after++ < 5000) {
    const double vx = game.ball().v.x();
    game.step();
    if (keeper) {
      s.highest = std::max(s.highest, game.keeper_offset());
      if (game.keeper_touched() && !s.touched) {
        s.touched = true;
        s.vx_in = vx;
      }
      if (s.touched && std::isnan(s.vx_out) && game.ball().q.x() < face - game.radius())
        s.vx_out = game.ball().v.x();
    }
  }
  s.outcome = game.rounds().at(0).outcome;
  return s;
}

// A flat kick along the grass from 3.6 m: the keeper stays down (the ball
// reaches its face on the grass) and the ball bounces back off it, on
// either engine, with the restitution of the scene's contact law: the
// keeper's face is vertical, so the normal is x and the bounce's closed
// form (test_engines.cpp, the crossbar's) applies to vx: compression-only
// damping on the reference, Kelvin–Voigt on calibrated MuJoCo.
TEST(BothEngines, TheBallBouncesOffTheKeeper) {
  const Pitch p = default_pitch();
  const double zeta = p.scene.contact.c / (2.0 * std::sqrt(p.scene.contact.k * p.scene.mass));
  for (const std::string& engine : keeper_engines()) {
    const Shot s = shoot(engine, 6.4, 0.0);
    const double e = -s.vx_out / s.vx_in;
    const double expected = engine == "ref" ? benchmarks::compression_restitution(zeta)
                                            : benchmarks::kelvin_voigt_restitution(zeta);
    std::printf(
        "%s: into the keeper at %.3f m/s, back at %.3f m/s (e = %.4f, closed form %.4f), "
        "keeper rose %.3f m\n",
        engine.c_str(), s.vx_in, s.vx_out, e, expected, s.highest);
    ASSERT_TRUE(s.touched) << engine;
    EXPECT_EQ(s.outcome, Outcome::Saved) << engine;
    EXPECT_GT(s.vx_in, 5.0) << engine;
    EXPECT_EQ(s.highest, 0.0) << engine << ": a ball on the grass keeps it down";
    // Tolerance: the step's share as for the crossbar (≈ ω·Δt·e = 4e-3),
    // plus the grass's friction on the sliding ball over the contact,
    // μ·g·6.5 ms = 0.026 m/s on the way in and again out, 5e-3 of 10 m/s.
    // Measured: 1e-5 (ref) and 3.4e-3 (MuJoCo).
    EXPECT_NEAR(e, expected, 1e-2) << engine;
    EXPECT_EQ(shoot(engine, 6.4, 0.0, false).outcome, Outcome::Goal)
        << engine << ": without the keeper the same kick scores";
  }
}

// From 7 m at 30° the ball needs ~0.7 s to arrive: the keeper rises to
// where it will pass and saves; without it, the same shot scores.
TEST(BothEngines, TheKeeperRisesToAShotFromFar) {
  for (const std::string& engine : keeper_engines()) {
    const Shot s = shoot(engine, 3.0, 30.0);
    std::printf("%s: keeper rose %.3f m, outcome %s\n", engine.c_str(), s.highest,
                std::string(outcome_name(s.outcome)).c_str());
    EXPECT_GT(s.highest, 0.5) << engine;
    EXPECT_TRUE(s.touched) << engine;
    EXPECT_EQ(s.outcome, Outcome::Saved) << engine;
    EXPECT_EQ(shoot(engine, 3.0, 30.0, false).outcome, Outcome::Goal) << engine;
  }
}

// From 2.5 m at 45° (what the scripted player picks there): the keeper
// starts up at once but the ball is over it first.
TEST(BothEngines, AChipFromCloseBeatsTheKeeper) {
  for (const std::string& engine : keeper_engines()) {
    const Shot s = shoot(engine, 7.5, 45.0);
    std::printf("%s: keeper rose %.3f m, outcome %s\n", engine.c_str(), s.highest,
                std::string(outcome_name(s.outcome)).c_str());
    EXPECT_GT(s.highest, 0.2) << engine << ": it did move";
    EXPECT_FALSE(s.touched) << engine;
    EXPECT_EQ(s.outcome, Outcome::Goal) << engine;
  }
}

}  // namespace
}  // namespace contact2d::game

namespace contact2d::game {
namespace {

// A policy's keys go through the InputFeed like a person's: what it
// recorded replays headless to the same kicks and the same final state
// (deterministic: the same seed and inputs, the same game). On the
// reference only: the policy and the feed know no engine, and MuJoCo's
// replays repeat exactly (test_play_cli.cpp, AMujocoReplayGivesTheSameJsonTwice).
TEST(Keeper, AScriptedRoundReplaysExactly) {
  for (const std::string engine : {"ref"}) {
    const Pitch pitch = default_pitch();
    Game game(pitch, engine, 3);
    InputFeed feed(game, nullptr);
    const Outcome outcome = play_policy_round(game, feed, Policy::Scripted);
    const std::string live = report_json(game);
    const ReplayRun replayed = run_replay(pitch, feed.recorded(), engine);
    std::printf("%s: %s, %zu key events\n", engine.c_str(),
                std::string(outcome_name(outcome)).c_str(), feed.recorded().events.size());
    EXPECT_EQ(replayed.outcome, outcome) << engine;
    EXPECT_EQ(replayed.json, live) << engine;
  }
}

}  // namespace
}  // namespace contact2d::game
