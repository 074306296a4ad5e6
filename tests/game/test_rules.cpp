// The game's rules on the built-in pitch, through the library (no window):
// each test sets up a ball and a kick, steps the game and checks what the
// rules decided and what the ball did to make them decide it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/obstacles.hpp"
#include "game/game.hpp"
#include "game/pitches.hpp"
#include "game/session.hpp"
#include "io/scene_file.hpp"

namespace contact2d::game {
namespace {

using testing::still_ball;
using testing::without_keeper;

// What happened to the ball on the way.
struct Watch {
  bool crossed_wholly = false;  // the whole ball got beyond the goal line at some point
  bool touched_bar = false;
  double vx_into_bar = 0.0;  // vx the step before the first contact with the crossbar
  double vx_off_bar = 0.0;   // vx the first step after it ended
  double y_at_line = -1.0;   // highest centre height within 1 cm of the goal line
};

Watch play_round(Game& game) {
  Watch w;
  const Pitch& p = game.pitch();
  // The ball against the crossbar alone (no ground, no other obstacle).
  Model bar = make_model(p.scene);
  bar.obstacles = {p.scene.obstacles[static_cast<size_t>(p.rules.crossbar)]};
  bar.body.points.clear();
  bool released = false;
  while (game.phase() == Phase::Playing) {
    const double vx = game.ball().v.x();
    game.step();
    const State& s = game.ball();
    const bool touching = max_penetration(bar, s.q) > 0.0;
    if (touching && !w.touched_bar) {
      w.touched_bar = true;
      w.vx_into_bar = vx;
    }
    if (w.touched_bar && !touching && !released) {
      released = true;
      w.vx_off_bar = s.v.x();
    }
    if (s.q.x() - p.rules.goal_line > p.scene.radius) w.crossed_wholly = true;
    if (std::abs(s.q.x() - p.rules.goal_line) < 0.01) w.y_at_line = std::max(w.y_at_line, s.q.y());
  }
  return w;
}

Outcome kick_from(const Pitch& pitch, Watch* watch = nullptr) {
  Game game(pitch, "ref", 1);
  game.handle(Key::Kick, true);
  const Watch w = play_round(game);
  if (watch) *watch = w;
  return game.current_round().outcome;
}

TEST(Rules, NoInputScoresNoGoal) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    Pitch pitch = default_pitch();
    pitch.rules.round_time = 4.0;  // the round waits for a kick: past the ~2 s the pass takes
    Game game(pitch, "ref", seed);
    play_round(game);
    EXPECT_EQ(game.goals(), 0) << "seed " << seed;
    EXPECT_TRUE(game.kicks().empty());
  }
}

TEST(Rules, APassThatRollsInByItselfIsNoGoal) {
  // A pass strong enough to roll over the line: the ball does go in, but
  // nobody kicked it.
  Pitch pitch = without_keeper();
  pitch.rules.pass_speed_min = pitch.rules.pass_speed_max = 7.0;
  pitch.rules.pass_lift_min = pitch.rules.pass_lift_max = 0.0;
  pitch.rules.pass_spin_min = pitch.rules.pass_spin_max = 1.0;
  Game game(pitch, "ref", 1);
  const Watch w = play_round(game);
  EXPECT_TRUE(w.crossed_wholly);
  EXPECT_EQ(game.current_round().outcome, Outcome::NotKicked);
  EXPECT_EQ(game.goals(), 0);
}

TEST(Rules, AKickInsideTheMinimumDistanceDoesNotCountEvenIfTheBallGoesIn) {
  const Pitch base = default_pitch();
  const double line = base.rules.goal_line, min = base.rules.min_kick_distance;
  Watch w;
  EXPECT_EQ(kick_from(still_ball(line - 0.6 * min), &w), Outcome::KickTooClose);
  EXPECT_TRUE(w.crossed_wholly) << "the ball must go in for the rule to matter";
  // The same kick from just beyond the minimum distance scores.
  EXPECT_EQ(kick_from(still_ball(line - 1.2 * min), &w), Outcome::Goal);

  Pitch pitch = still_ball(line - 0.6 * min);
  Game game(pitch, "ref", 1);
  game.handle(Key::Kick, true);
  play_round(game);
  ASSERT_EQ(game.kicks().size(), 1u);
  EXPECT_FALSE(game.kicks()[0].counted);
  EXPECT_NEAR(game.kicks()[0].distance, 0.6 * min, 1e-12);
}

TEST(Rules, APushAfterACountedKickTakesTheGoalAway) {
  // Last touch decides: kick from 3 m, then push the ball on its way in.
  Pitch pitch = still_ball(default_pitch().rules.goal_line - 3.0);
  Game game(pitch, "ref", 1);
  game.handle(Key::Kick, true);
  for (int i = 0; i < 10000; ++i) game.step();  // 0.1 s: the kick is over, the ball is on its way
  game.handle(Key::Right, true);
  play_round(game);
  EXPECT_EQ(game.current_round().outcome, Outcome::Pushed);
  EXPECT_TRUE(game.kicks().at(0).counted);
}

TEST(Rules, ABallThatStopsOnTheLineIsNoGoal) {
  // A flat kick from 3 m with an impulse found by bisection so that the ball
  // comes to rest with its centre on the goal line (half of it across).
  // Rolling distance grows with the impulse, so the bisection converges; the
  // ball must end straddling the line, and a 5 % harder kick must score,
  // so the line rule (not a short kick) is what decided.
  const Pitch base = default_pitch();
  const double line = base.rules.goal_line, R = base.scene.radius;
  auto final_x = [&](double impulse, Outcome* outcome) {
    Pitch pitch = still_ball(line - 3.0);
    pitch.rules.kick_impulse = impulse;
    Game game(pitch, "ref", 1);
    game.handle(Key::Kick, true);
    play_round(game);
    *outcome = game.current_round().outcome;
    return game.ball().q.x();
  };
  double lo = 0.1, hi = 3.0;  // N·s: the ball stops short / scores
  Outcome outcome = Outcome::None;
  ASSERT_LT(final_x(lo, &outcome), line);
  ASSERT_EQ((final_x(hi, &outcome), outcome), Outcome::Goal);
  // The final position moves ~4 m per N·s of impulse here, so 16 halvings
  // of the 2.9 N·s bracket (4e-5 N·s) put the centre within ~0.2 mm of the
  // line, far inside the ±R the test needs.
  for (int i = 0; i < 16; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double x = final_x(mid, &outcome);
    if (outcome == Outcome::Goal || x > line) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  const double x = final_x(lo, &outcome);
  EXPECT_EQ(outcome, Outcome::Stopped);
  EXPECT_GT(x, line - R) << "the ball must touch the line";
  EXPECT_LT(x, line + R) << "and not be wholly across";
  std::printf("stopped on the line: impulse %.6f N·s, centre %.4f m from the line\n", lo, x - line);
  EXPECT_EQ((final_x(1.05 * lo, &outcome), outcome), Outcome::Goal);
}

// Shots from 4 m in front of the goal line (x = 6) with the built-in kick;
// the angles were found by scanning 36-46° in 1° steps: 36-39° go under the
// bar, 40° hits it and goes in, 41-43° hit its front face and come back,
// 44° and more go over the goal.
TEST(Rules, TheBallBouncesOffTheCrossbar) {
  Watch w;
  const Outcome outcome = kick_from(still_ball(6.0, 41.0), &w);
  ASSERT_TRUE(w.touched_bar);
  EXPECT_GT(w.vx_into_bar, 5.0);
  EXPECT_LT(w.vx_off_bar, 0.0) << "the bar sends the ball back";
  EXPECT_LT(-w.vx_off_bar, w.vx_into_bar) << "with less speed: the contact is damped";
  EXPECT_FALSE(w.crossed_wholly);
  EXPECT_NE(outcome, Outcome::Goal);
}

TEST(Rules, OffTheCrossbarAndInIsAGoal) {
  Watch w;
  EXPECT_EQ(kick_from(still_ball(6.0, 40.0), &w), Outcome::Goal);
  EXPECT_TRUE(w.touched_bar);
}

TEST(Rules, OverTheCrossbarIsNoGoal) {
  const Pitch base = default_pitch();
  const double bar_top = base.scene.obstacles[0].b.y();
  Watch w;
  const Outcome outcome = kick_from(still_ball(6.0, 45.0), &w);
  EXPECT_GT(w.y_at_line, bar_top + base.scene.radius) << "the ball must clear the bar";
  EXPECT_FALSE(w.touched_bar);
  EXPECT_NE(outcome, Outcome::Goal);
  EXPECT_EQ(outcome, Outcome::Out) << "it flies over the goal and off the pitch";
}

TEST(Rules, TheKickAngleKeysStepAndClamp) {
  const Pitch pitch = default_pitch();
  Game game(pitch, "ref", 1);
  EXPECT_EQ(game.kick_angle(), 15.0);
  game.handle(Key::AngleUp, true);
  EXPECT_EQ(game.kick_angle(), 20.0);
  for (int i = 0; i < 20; ++i) game.handle(Key::AngleUp, true);
  EXPECT_EQ(game.kick_angle(), pitch.rules.kick_angle_max);
  for (int i = 0; i < 20; ++i) game.handle(Key::AngleDown, true);
  EXPECT_EQ(game.kick_angle(), pitch.rules.kick_angle_min);
}

TEST(Rules, TheKickDeliversItsImpulse) {
  // Without gravity, a kick changes the momentum by exactly kick_impulse
  // along the kick angle: the force is J/(n·Δt) for n
  // whole steps, and semi-implicit Euler adds F·Δt per step.
  Pitch pitch = still_ball(5.0, 30.0);
  pitch.scene.sim.gravity = 0.0;
  Game game(pitch, "ref", 1);
  game.handle(Key::Kick, true);
  for (int i = 0; i < 10000; ++i) game.step();  // 0.1 s > kick_duration
  const double m = pitch.scene.mass, J = pitch.rules.kick_impulse,
               a = 30.0 * 3.14159265358979323846 / 180.0;
  // With g = 0 the ball starts just touching the grass (no spring force),
  // the kick lifts it at once (no damper: compression only, no friction:
  // Fn = 0), so only rounding remains: tolerance 1e-9 m/s on ~11.6 m/s.
  EXPECT_NEAR(game.ball().v.x(), J / m * std::cos(a), 1e-9);
  EXPECT_NEAR(game.ball().v.y(), J / m * std::sin(a), 1e-9);
}

TEST(Rules, ResetStartsTheNextPass) {
  const Pitch pitch = default_pitch();
  Game game(pitch, "ref", 1);
  for (int i = 0; i < 1000; ++i) game.step();
  game.handle(Key::Reset, true);
  EXPECT_EQ(game.round(), 2);
  EXPECT_EQ(game.rounds()[0].outcome, Outcome::Reset);
  EXPECT_EQ(game.phase(), Phase::Playing);
  EXPECT_EQ(game.ball().q.x(), pitch.rules.pass_x);
  EXPECT_NE(game.rounds()[0].pass_speed, game.rounds()[1].pass_speed) << "a new draw";
}

TEST(Rules, TheSameSeedGivesTheSamePasses) {
  const Pitch pitch = default_pitch();
  Game a(pitch, "ref", 42), b(pitch, "ref", 42), c(pitch, "ref", 43);
  EXPECT_EQ(a.current_round().pass_speed, b.current_round().pass_speed);
  EXPECT_EQ(a.current_round().pass_spin, b.current_round().pass_spin);
  EXPECT_NE(a.current_round().pass_speed, c.current_round().pass_speed);
  EXPECT_GE(a.current_round().pass_speed, pitch.rules.pass_speed_min);
  EXPECT_LE(a.current_round().pass_speed, pitch.rules.pass_speed_max);
}

TEST(PitchFile, TheGameNeedsACircle) {
  try {
    parse_pitch("scene = \"box\"\n", "box.toml");
    FAIL() << "a box was accepted as a ball";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the game needs scene = \"circle\""), std::string::npos)
        << e.what();
  }
}

TEST(PitchFile, TheBuiltInPitchIsTheShippedFile) {
  const Pitch built_in = default_pitch();
  const Pitch file = load_pitch(CONTACT2D_SOURCE_DIR "/validation/scenes/game/pitch.toml");
  EXPECT_EQ(built_in.fingerprint, file.fingerprint);
  EXPECT_EQ(built_in.scene.obstacles.size(), 4u);
  EXPECT_EQ(built_in.crossbar_bottom(), 2.44);
  ASSERT_EQ(built_in.rules.keeper, 3);
  EXPECT_TRUE(built_in.scene.obstacles[3].moves) << "the keeper moves";
  EXPECT_FALSE(built_in.scene.obstacles[0].moves) << "the crossbar does not";
}

}  // namespace
}  // namespace contact2d::game

namespace contact2d::game {
namespace {

// A pass rolling at 3 m/s (no lift, rolling spin) braked by the control key
// from the start: m·|v|/control_time is above control_force until the last
// 0.14 m/s, so the centre decelerates by at least control_force/m = 14 m/s²
// (the grass's rolling resistance, 0.9 m/s², adds): still after 3/14 =
// 0.21 s plus the exponential tail (control_time = 0.05 s: 0.14 m/s to
// 0.02 m/s in 0.1 s). The spin it keeps is the grass's business: friction
// turns it into a slow roll, which the key brakes as well.
TEST(Rules, TheControlKeyBrakesThePass) {
  Pitch pitch = without_keeper();
  pitch.rules.pass_speed_min = pitch.rules.pass_speed_max = 3.0;
  pitch.rules.pass_spin_min = pitch.rules.pass_spin_max = 1.0;
  pitch.rules.pass_lift_min = pitch.rules.pass_lift_max = 0.0;
  Game held(pitch, "ref", 1), free(pitch, "ref", 1);
  held.handle(Key::Control, true);
  for (int i = 0; i < 50000; ++i) {  // 0.5 s
    held.step();
    free.step();
  }
  const double v_held = std::hypot(held.ball().v.x(), held.ball().v.y());
  std::printf("after 0.5 s: %.4f m/s controlled, %.3f m/s free\n", v_held, free.ball().v.x());
  EXPECT_LT(v_held, 0.05);
  EXPECT_GT(free.ball().v.x(), 2.0) << "without the key it rolls on";
  EXPECT_EQ(held.last_touch(), Touch::None) << "control is no touch";
}

// Reach: a pass lifted at 5 m/s is at 0.11 + 5·0.3 − g·0.3²/2 = 1.17 m at
// 0.3 s, above reach_height (0.9 m): the kick key does nothing, and says why.
TEST(Rules, AKickOutOfReachIsIgnored) {
  Pitch pitch = without_keeper();
  pitch.rules.pass_lift_min = pitch.rules.pass_lift_max = 5.0;
  Game game(pitch, "ref", 1);
  for (int i = 0; i < 30000; ++i) game.step();
  ASSERT_GT(game.ball().q.y(), pitch.rules.reach_height);
  game.handle(Key::Kick, true);
  EXPECT_EQ(game.ignored_kick(), IgnoredKick::OutOfReach);
  EXPECT_TRUE(game.kicks().empty());
  EXPECT_FALSE(game.kicking());
}

TEST(Rules, ThePowerKeysStepClampAndScaleTheKick) {
  Pitch pitch = still_ball(5.0, 0.0);
  pitch.rules.kick_power = 0.5;
  pitch.scene.sim.gravity = 0.0;  // as in TheKickDeliversItsImpulse: no grass force
  Game game(pitch, "ref", 1);
  game.handle(Key::Kick, true);
  for (int i = 0; i < 10000; ++i) game.step();
  EXPECT_NEAR(game.ball().v.x(), 0.5 * pitch.rules.kick_impulse / pitch.scene.mass, 1e-9);
  for (int i = 0; i < 20; ++i) game.handle(Key::PowerUp, true);
  EXPECT_EQ(game.kick_power(), 1.0);
  for (int i = 0; i < 20; ++i) game.handle(Key::PowerDown, true);
  EXPECT_EQ(game.kick_power(), pitch.rules.kick_power_min);
}

// The level keys act before the first step and while a session is
// finished, not during one (the keeper's speed would change under a shot).
TEST(Rules, TheLevelKeysActOnlyBeforeASession) {
  Pitch pitch = still_ball(7.0, 15.0);
  pitch.rules.session_rounds = 1;
  Game game(pitch, "ref", 1);
  game.handle(Key::LevelHard, true);
  EXPECT_EQ(game.level(), Level::Hard);
  game.step();
  game.handle(Key::LevelEasy, true);
  EXPECT_EQ(game.level(), Level::Hard) << "ignored once the session has started";
  game.handle(Key::Kick, true);
  while (!game.session_finished()) game.step();
  game.handle(Key::LevelEasy, true);
  EXPECT_EQ(game.level(), Level::Easy) << "for the next session";
}

// A session of one pass: after its result the game waits (no new pass);
// the reset key starts session 2, whose score starts at 0 while the best
// keeps session 1's goal.
TEST(Rules, ASessionEndsAndTheBestScoreStays) {
  Pitch pitch = still_ball(7.0, 15.0);
  pitch.rules.session_rounds = 1;
  Game game(pitch, "ref", 1);
  game.handle(Key::Kick, true);
  while (game.phase() == Phase::Playing) game.step();
  ASSERT_EQ(game.current_round().outcome, Outcome::Goal);
  for (long long i = 0; i < game.result_steps() + 1000; ++i) game.step();
  EXPECT_TRUE(game.session_finished());
  EXPECT_EQ(game.round(), 1) << "no next pass";
  EXPECT_EQ(game.session_goals(), 1);
  game.handle(Key::Reset, true);
  EXPECT_FALSE(game.session_finished());
  EXPECT_EQ(game.session(), 2);
  EXPECT_EQ(game.round(), 2);
  EXPECT_EQ(game.session_round(), 1);
  EXPECT_EQ(game.session_goals(), 0);
  EXPECT_EQ(game.best_session_goals(), 1);
  EXPECT_EQ(game.phase(), Phase::Playing);
}

}  // namespace
}  // namespace contact2d::game

namespace contact2d::game {
namespace {

// Every key of the enum has a name in replay files that reads back as it
// (a key left out of the parser's list could be pressed but not replayed).
TEST(ReplayFile, EveryKeyHasANameThatReadsBack) {
  for (int k = 0; k <= static_cast<int>(Key::LevelHard); ++k) {
    const auto key = static_cast<Key>(k);
    const auto parsed = parse_key(key_name(key));
    ASSERT_TRUE(parsed.has_value()) << key_name(key);
    EXPECT_EQ(*parsed, key) << key_name(key);
  }
}

TEST(ReplayFile, TheLevelIsWrittenAndReadBack) {
  Replay replay;
  replay.seed = 9;
  replay.dt = 1e-5;
  replay.level = Level::Hard;
  replay.events = {{0, Key::LevelEasy, true}, {5, Key::Control, true}};
  const Replay back = parse_replay(format_replay(replay), "test");
  EXPECT_EQ(back.level, Level::Hard);
  ASSERT_EQ(back.events.size(), 2u);
  EXPECT_EQ(back.events[0].key, Key::LevelEasy);
  EXPECT_EQ(parse_replay("contact2d-replay 1\nseed 1\ndt 1e-05\n", "old").level, Level::Normal)
      << "a replay without a level line plays at normal";
}

}  // namespace
}  // namespace contact2d::game
