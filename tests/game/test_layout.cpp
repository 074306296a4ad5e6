// Where the game's text goes (game/render.hpp: frame_layout, a plain
// function, no GL): over the frames of scripted rounds, a goal and a save,
// no text covers the keeper, the ball or the kick's path; the messages sit
// in the band under the grass line. And the HUD's force has no "-0.0".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "game/policy.hpp"
#include "game/render.hpp"
#include "game/session.hpp"

namespace contact2d::game {
namespace {

struct Seen {
  int frames = 0;
  int aiming = 0;   // frames with the kick's preview
  int results = 0;  // frames with the round's result in the band
};

std::string where(const ScreenBox& b) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.0f, %.0f]-[%.0f, %.0f]", b.x0, b.y0, b.x1, b.y1);
  return text;
}

void check_frame(const Game& game, const Overlay& overlay, int width, int height, Seen& seen) {
  const FrameLayout l = frame_layout(game, overlay, width, height);
  ++seen.frames;
  seen.aiming += l.path.empty() ? 0 : 1;
  ASSERT_FALSE(l.ball.empty());
  ASSERT_FALSE(l.keeper.empty());
  EXPECT_GE(l.band.y0, l.pitch.y1) << "the band is below the grass line";
  const std::string result = outcome_text(game.current_round().outcome, 1.0);
  for (const TextItem& t : l.texts) {
    if (game.phase() == Phase::Over && t.text == result) ++seen.results;
    const std::string at = " at t = " + std::to_string(game.round_time()) + " s, " +
                           std::to_string(width) + "x" + std::to_string(height);
    EXPECT_FALSE(t.box.overlaps(l.keeper))
        << '"' << t.text << "\" " << where(t.box) << " covers the keeper " << where(l.keeper) << at;
    EXPECT_FALSE(t.box.overlaps(l.ball))
        << '"' << t.text << "\" " << where(t.box) << " covers the ball " << where(l.ball) << at;
    EXPECT_FALSE(t.box.overlaps(l.path)) << '"' << t.text << "\" " << where(t.box)
                                         << " covers the kick's path " << where(l.path) << at;
  }
}

// One round by the player from the pass to the next pass (its result
// shown), a frame every 1/30 s, in the window's size and a wide one, with
// and without the pause and replay marks.
Seen play_and_check(Policy policy, std::uint64_t seed, Outcome expected) {
  Game game(default_pitch(), "ref", seed);
  InputFeed feed(game, nullptr);
  PolicyPlayer player(policy);
  const long long stride = std::llround(1.0 / 30.0 / game.dt());
  Overlay marks;
  marks.paused = marks.replaying = true;
  marks.fps = 60.0;
  Seen seen;
  while (game.round() == 1 && !game.divergence()) {
    if (game.steps() % stride == 0) {
      check_frame(game, Overlay{}, 800, 600, seen);
      check_frame(game, marks, 1280, 720, seen);
      if (::testing::Test::HasFailure()) break;  // one frame's failures are enough to read
    }
    player.act(game, feed);
    game.step();
  }
  EXPECT_EQ(game.rounds().front().outcome, expected);
  return seen;
}

TEST(Layout, NoTextCoversTheKeeperTheBallOrTheKickInAScriptedGoal) {
  const Seen seen = play_and_check(Policy::Scripted, 1, Outcome::Goal);
  std::printf("%d frames checked, %d aiming, %d with the result\n", seen.frames, seen.aiming,
              seen.results);
  EXPECT_GT(seen.aiming, 0) << "the preview was on screen";
  EXPECT_GT(seen.results, 0) << "the GOAL! banner was on screen";
}

TEST(Layout, NoTextCoversTheKeeperOrTheBallInASave) {
  const Seen seen = play_and_check(Policy::Blind, 1, Outcome::Saved);
  std::printf("%d frames checked, %d with the result\n", seen.frames, seen.results);
  EXPECT_GT(seen.results, 0) << "the save's banner was on screen";
}

// The help is modal and its panel reaches the band: no text but the HUD's
// shows through it (the 1 m line's label did).
TEST(Layout, UnderTheHelpOnlyTheHudHasText) {
  const Game game(default_pitch(), "ref", 1);
  Overlay help;
  help.help = true;
  const FrameLayout l = frame_layout(game, help, 800, 600);
  ASSERT_FALSE(l.texts.empty());
  for (const TextItem& t : l.texts) EXPECT_LE(t.box.y1, l.hud.y1) << t.text;
}

// The issue: the HUD showed "FORCE (-0.0, 0.0) N".
TEST(Layout, TheForceHasNoNegativeZero) {
  EXPECT_EQ(force_text(-0.0, 0.0), "(0.0, 0.0)");
  EXPECT_EQ(force_text(-0.04, -0.049), "(0.0, 0.0)");
  EXPECT_EQ(force_text(-0.05, 0.05), "(-0.1, 0.1)");
  EXPECT_EQ(force_text(-1.26, 125.0), "(-1.3, 125.0)");
}

}  // namespace
}  // namespace contact2d::game
