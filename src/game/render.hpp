// Drawing one frame of the game with OpenGL 1.x/2.x fixed-function calls
// (a few hundred vertices a frame: the pitch, the goal, the ball, arrows and
// the HUD text, which stb_easy_font turns into quads). Needs a current GL
// context; window.cpp owns it.
//
// Where the text goes is a plain function (frame_layout, no GL): the HUD
// along the top, and every message (a round's result, an ignored kick, the
// last kick, the preview's legend, the pause) in a banner band along the
// bottom, under the grass line, where nothing is played: no text covers
// the keeper, the ball or the kick's path (tests/game/test_layout.cpp
// checks it over scripted rounds). The title screen, the help and the end
// of a session are screens of their own, drawn over the middle.
#pragma once

#include <string>
#include <vector>

#include "game/draw2d.hpp"
#include "game/game.hpp"

namespace contact2d::game {

struct Overlay {
  bool paused = false;
  bool help = false;
  bool replaying = false;
  bool recording = false;
  double fps = 0.0;        // measured, 0 = unknown
  double speed = 1.0;      // simulated seconds per wall-clock second (< 1: slow motion)
  double get_ready = 0.0;  // s before the first pass starts (> 0: the game waits)
};

// A rectangle on the screen: pixels, y down.
struct ScreenBox {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  bool overlaps(const ScreenBox& o) const {
    return !empty() && !o.empty() && x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
};

// One line of text: its top-left corner and scale, and what it covers (its
// glyphs' box, or the opaque panel drawn behind it).
struct TextItem {
  std::string text;
  double x = 0.0, y = 0.0, scale = 2.0;
  draw::Color colour{1.0f, 1.0f, 1.0f, 1.0f};
  ScreenBox box;
  bool panel = false;  // box is a panel drawn behind the text
};

// One frame's layout: the play on the screen and the text around it.
struct FrameLayout {
  ScreenBox hud;     // the HUD's panel along the top
  ScreenBox pitch;   // the pitch above the grass line, below the HUD
  ScreenBox band;    // the banner band below the grass line (messages)
  ScreenBox keeper;  // the keeper (empty without one)
  ScreenBox ball;
  ScreenBox path;  // the aim and the kick preview's dots (empty while not aiming)
  // Every text over the game (the title screen, the help and the session's
  // end are not: they are screens of their own).
  std::vector<TextItem> texts;
};

FrameLayout frame_layout(const Game& game, const Overlay& overlay, int width, int height);

// The HUD's force, "(1.2, -0.5)": one decimal, and never "-0.0" (a
// component that rounds to zero is 0.0, whatever its sign).
std::string force_text(double fx, double fy);

void draw_frame(const Game& game, const Overlay& overlay, int width, int height);

}  // namespace contact2d::game
