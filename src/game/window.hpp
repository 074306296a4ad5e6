// The game's window: GLFW + OpenGL 2D drawing of the pitch from the side, a
// HUD, a help overlay (the game is paused while it is shown), and optional recording through an
// ffmpeg pipe.
//
// Time: physics runs at the scene's Δt from an accumulator fed by the frame
// time (clamped to 0.25 s so a stall does not trigger a burst of catch-up),
// so the ball moves in real time at any frame rate — while the engine keeps
// up: live play spends at most physics_budget a frame on physics and runs
// in slow motion beyond it (the HUD shows the factor). While recording, every
// frame advances exactly 1/fps of simulated time instead, so the video is
// real-time whatever the machine's speed. Keys arrive through GLFW's key
// callback (a tap shorter than a frame is still seen) and are applied
// between physics steps, stamped with the step index.
#pragma once

#include <string>

#include "game/session.hpp"

namespace contact2d::game {

// The title screen's time: long enough to read it and pick a level.
inline constexpr double kFirstPassDelay = 3.0;  // s

struct WindowOptions {
  int width = 800;
  int height = 600;
  bool vsync = true;        // swap interval 1 (ignored by Xvfb)
  std::string record_path;  // non-empty: write an H.264 MP4 through ffmpeg
  int record_fps = 60;
  long long max_frames = 0;  // > 0: close after this many frames (measuring)
  bool start_with_help = false;
  // Live play: at most this much wall clock a frame for physics, s (0: no
  // limit). 3 ms leaves a 120 fps frame (8.3 ms) room for the 2.4-4 ms that
  // llvmpipe takes to draw one under load (scripts/measure-fps).
  double physics_budget = 0.003;
  // Live play: wall clock (simulated time when recording) the window shows
  // the first pass frozen, with a countdown, before it starts rolling, so the
  // player can find the keys; game keys are ignored meanwhile. A replay has
  // no player and starts at once (its steps are the same either way).
  double first_pass_delay = kFirstPassDelay;
};

struct WindowStats {
  long long frames = 0;
  double seconds = 0.0;         // wall clock from the first to the last frame
  double render_seconds = 0.0;  // drawing and swapping alone
  long long steps = 0;
  std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
};

// Opens the window and plays until Esc, the window is closed, the replay is
// over (its last round ended and its result was shown), or max_frames.
// Throws InputError when no window can be opened or ffmpeg cannot start.
WindowStats run_window(Game& game, InputFeed& feed, const WindowOptions& options);

}  // namespace contact2d::game
