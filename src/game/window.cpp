#include "game/window.hpp"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "core/input_error.hpp"
#include "game/draw2d.hpp"
#include "game/render.hpp"
#include "game/video.hpp"

namespace contact2d::game {
namespace {

std::string g_glfw_error;

void on_glfw_error(int, const char* description) {
  g_glfw_error = description ? description : "unknown error";
}

// Key callback → queue, drained once per frame: a press and release within
// one frame are both seen, in order.
struct KeyQueue {
  std::vector<std::pair<int, int>> events;  // (GLFW key, GLFW action)
};

void on_key(GLFWwindow* window, int key, int, int action, int) {
  auto* queue = static_cast<KeyQueue*>(glfwGetWindowUserPointer(window));
  queue->events.emplace_back(key, action);
}

// Game keys; UI keys (pause, help, quit) are handled by the loop.
std::optional<Key> game_key(int key) {
  switch (key) {
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_RIGHT: return Key::Right;
    case GLFW_KEY_UP: return Key::Up;
    case GLFW_KEY_DOWN: return Key::Down;
    case GLFW_KEY_K:
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER: return Key::Kick;
    case GLFW_KEY_W:
    case GLFW_KEY_PAGE_UP: return Key::AngleUp;
    case GLFW_KEY_S:
    case GLFW_KEY_PAGE_DOWN: return Key::AngleDown;
    case GLFW_KEY_BACKSPACE: return Key::Reset;
    case GLFW_KEY_C: return Key::Control;
    case GLFW_KEY_D: return Key::PowerUp;
    case GLFW_KEY_A: return Key::PowerDown;
    case GLFW_KEY_1: return Key::LevelEasy;
    case GLFW_KEY_2: return Key::LevelNormal;
    case GLFW_KEY_3: return Key::LevelHard;
    default: return std::nullopt;
  }
}

struct GlfwSession {
  GlfwSession() {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
      throw InputError("play: cannot open a window (" + g_glfw_error +
                       "); run it on a display, under xvfb-run, or with --headless");
    }
  }
  ~GlfwSession() { glfwTerminate(); }
};

// The UI keys of one frame's queued events (quit, pause, help) and the game
// keys handed to the feed (none before the first pass); true: quit.
bool handle_keys(KeyQueue& queue, InputFeed& feed, Overlay& overlay) {
  bool quit = false;
  for (const auto& [key, action] : queue.events) {
    if (action == GLFW_PRESS) {
      if (key == GLFW_KEY_ESCAPE) quit = true;
      if (key == GLFW_KEY_SPACE) overlay.paused = !overlay.paused;
      if (key == GLFW_KEY_F1 || key == GLFW_KEY_H) overlay.help = !overlay.help;
    }
    const auto k = game_key(key);
    if (!k) continue;
    // Before the first pass only the level keys (nothing has stepped yet).
    const bool level = *k == Key::LevelEasy || *k == Key::LevelNormal || *k == Key::LevelHard;
    if (overlay.get_ready > 0.0 && !level) continue;
    const bool stepped = *k == Key::AngleUp || *k == Key::AngleDown || *k == Key::PowerUp ||
                         *k == Key::PowerDown;  // held: repeats, one step each
    if (action == GLFW_PRESS || (action == GLFW_REPEAT && stepped)) feed.live(*k, true);
    if (action == GLFW_RELEASE) feed.live(*k, false);
  }
  queue.events.clear();
  return quit;
}

// Steps the game through the frame's `accumulator` of simulated time, for
// at most `physics_budget` seconds of wall clock (0: no limit; what is left
// is then dropped). True: a replay is over and the window closes.
bool step_physics(Game& game, InputFeed& feed, double physics_budget, double& accumulator) {
  const double dt = game.dt();
  const auto physics_start = std::chrono::steady_clock::now();
  long long stepped = 0;
  while (accumulator >= dt) {
    feed.apply_due();
    // A replay ends once its last round has been decided and its result
    // shown for result_time (just before the next pass would start).
    if (feed.replaying() && session_over(game, feed) &&
        (game.divergence() || game.steps_since_end() + 1 >= game.result_steps())) {
      return true;
    }
    if (game.divergence()) break;
    game.step();
    accumulator -= dt;
    if (physics_budget > 0.0 && ++stepped % 16 == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - physics_start).count() >
            physics_budget) {
      accumulator = 0.0;  // what is left of this frame's time is not simulated
      break;
    }
  }
  return false;
}

}  // namespace

WindowStats run_window(Game& game, InputFeed& feed, const WindowOptions& o) {
  GlfwSession glfw;
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, "contact2d play", nullptr, nullptr);
  if (!window) throw InputError("play: cannot create an OpenGL 2.1 window (" + g_glfw_error + ")");
  KeyQueue queue;
  glfwSetWindowUserPointer(window, &queue);
  glfwSetKeyCallback(window, on_key);
  glfwMakeContextCurrent(window);
  draw::forget_gl_objects();  // a text atlas uploaded to an earlier context is gone
  glfwSwapInterval(o.vsync ? 1 : 0);

  int fb_width = o.width, fb_height = o.height;
  glfwGetFramebufferSize(window, &fb_width, &fb_height);
  std::unique_ptr<VideoWriter> video;
  std::vector<unsigned char> pixels;
  if (!o.record_path.empty()) {
    video = std::make_unique<VideoWriter>(o.record_path, fb_width, fb_height, o.record_fps);
    pixels.resize(static_cast<size_t>(fb_width) * static_cast<size_t>(fb_height) * 3);
  }

  Overlay overlay;
  overlay.replaying = feed.replaying();
  overlay.recording = video != nullptr;
  overlay.help = o.start_with_help;
  overlay.get_ready = feed.replaying() ? 0.0 : o.first_pass_delay;
  const double dt = game.dt();
  double accumulator = 0.0;
  double last = glfwGetTime();
  const double start = last;
  double fps_window_start = last;
  long long fps_window_frames = 0;
  WindowStats stats;
  if (const GLubyte* name = glGetString(GL_RENDERER))
    stats.renderer = reinterpret_cast<const char*>(name);
  bool quit = false;
  long long steps_before = game.steps();
  double sim_advanced = 0.0, wall_advanced = 0.0;  // for the real-time factor

  while (!quit && !glfwWindowShouldClose(window)) {
    glfwPollEvents();
    if (handle_keys(queue, feed, overlay)) quit = true;

    const double now = glfwGetTime();
    // Recording: exactly one video frame of simulated time per frame.
    const double frame_time = video ? 1.0 / o.record_fps : now - last;
    last = now;
    // The help overlay pauses the game too: nobody plays while reading it.
    if (!overlay.paused && !overlay.help && overlay.get_ready > 0.0) {
      // Wall clock, not the physics' capped frame time: a slow first frame
      // (a loaded machine) must not stretch the wait.
      overlay.get_ready = std::max(0.0, overlay.get_ready - frame_time);
      steps_before = game.steps();
    } else if (!overlay.paused && !overlay.help) {
      accumulator += std::min(frame_time, 0.25);
      // Live play spends at most o.physics_budget of wall clock a frame on
      // physics, so the frame rate holds when an engine cannot step in real
      // time (MuJoCo at the pitch's Δt = 1e-5 s): the game then runs in slow
      // motion and the HUD says how slow. A recording steps every frame's
      // simulated time whatever it costs.
      if (step_physics(game, feed, video ? 0.0 : o.physics_budget, accumulator)) quit = true;
      sim_advanced += static_cast<double>(game.steps() - steps_before) * dt;
      steps_before = game.steps();
      wall_advanced += std::min(frame_time, 0.25);
    } else {
      steps_before = game.steps();
    }
    if (game.divergence()) quit = true;

    const auto render_start = std::chrono::steady_clock::now();
    draw_frame(game, overlay, fb_width, fb_height);
    if (video) {
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadBuffer(GL_BACK);
      glReadPixels(0, 0, fb_width, fb_height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
      if (!video->write(pixels)) quit = true;  // ffmpeg is gone; finish() reports it
    }
    glfwSwapBuffers(window);
    stats.render_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
    ++stats.frames;
    ++fps_window_frames;
    if (now - fps_window_start >= 0.5) {
      overlay.fps = static_cast<double>(fps_window_frames) / (now - fps_window_start);
      overlay.speed = wall_advanced > 0.0 ? sim_advanced / wall_advanced : 1.0;
      sim_advanced = wall_advanced = 0.0;
      fps_window_start = now;
      fps_window_frames = 0;
    }
    if (o.max_frames > 0 && stats.frames >= o.max_frames) quit = true;
  }
  stats.seconds = glfwGetTime() - start;
  stats.steps = game.steps();
  glfwDestroyWindow(window);
  if (video) video->finish();
  return stats;
}

}  // namespace contact2d::game
