// Drawing one frame of the game with OpenGL 1.x/2.x fixed-function calls
// (a few hundred vertices a frame: the pitch, the goal, the ball, arrows and
// the HUD text, which stb_easy_font turns into quads). Needs a current GL
// context; window.cpp owns it.
#pragma once

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

void draw_frame(const Game& game, const Overlay& overlay, int width, int height);

}  // namespace contact2d::game
