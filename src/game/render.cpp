#include "game/render.hpp"

#include "core/format.hpp"
#include "game/draw2d.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

namespace contact2d::game {
namespace {

constexpr double kPi = 3.14159265358979323846;

using draw::arrow;
using draw::Color;
using draw::disc;
using draw::rect;
using draw::rect_outline;
using draw::ring;
using draw::text;
using draw::text_width;
using draw::thick_line;

constexpr Color kSky{0.55f, 0.75f, 0.92f, 1.0f};
constexpr Color kGrassA{0.20f, 0.55f, 0.22f, 1.0f};
constexpr Color kGrassB{0.24f, 0.60f, 0.25f, 1.0f};
constexpr Color kTurfShade{0.16f, 0.44f, 0.18f, 1.0f};  // opaque: drawn without blending
constexpr Color kWhite{1.0f, 1.0f, 1.0f, 1.0f};
constexpr Color kPost{1.0f, 1.0f, 1.0f, 0.45f};
constexpr Color kNet{1.0f, 1.0f, 1.0f, 0.35f};
constexpr Color kObstacle{0.93f, 0.93f, 0.93f, 1.0f};
constexpr Color kOutline{0.1f, 0.1f, 0.1f, 1.0f};
constexpr Color kZone{1.0f, 0.85f, 0.1f, 0.9f};
constexpr Color kForce{0.9f, 0.12f, 0.1f, 1.0f};
constexpr Color kAim{1.0f, 0.9f, 0.2f, 0.9f};
constexpr Color kPanel{0.13f, 0.17f, 0.24f, 1.0f};  // opaque: the HUD is drawn without blending
constexpr Color kText{1.0f, 1.0f, 1.0f, 1.0f};
constexpr Color kGoal{1.0f, 0.85f, 0.1f, 1.0f};
constexpr Color kNoGoal{1.0f, 0.55f, 0.45f, 1.0f};

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
  return format_text(format, a, b, c);
}

// World-to-screen mapping: a camera kViewWidth metres wide (the whole pitch
// if it is narrower) that follows the ball, the ball kLead of the width from
// its left edge for a goal towards +x (mirrored for −x), and stops at the
// pitch's ends, so the whole goal is in view once the ball is within ~3 m of
// it; the grass line sits 90 px above the bottom. The whole 13 m pitch in
// 800 px drew the 0.22 m ball 13.5 px across; 7 m draw it 25 px across
// (2R·800/7 = 25.1 px; tests/game/test_window.cpp measures 22 px of white
// inside the outline).
constexpr double kViewWidth = 7.0;  // m
constexpr double kLead = 0.4;

struct View {
  double x0, x1, y0, y1, scale;  // metres; pixels per metre
  View(const Pitch& pitch, double ball_x, int width, int height) {
    const Rules& r = pitch.rules;
    const double w = std::min(kViewWidth, r.pitch_max_x - r.pitch_min_x);
    const double lead = pitch.direction() > 0 ? kLead : 1.0 - kLead;
    x0 = std::clamp(ball_x - lead * w, r.pitch_min_x, r.pitch_max_x - w);
    x1 = x0 + w;
    scale = width / w;
    y0 = -90.0 / scale;
    y1 = y0 + height / scale;
  }
  // Pixel position (y down) of a world point, for labels.
  Vec2 pixel(double x, double y, int height) const {
    return {(x - x0) * scale, height - (y - y0) * scale};
  }
};

void draw_world(const Game& game, const View& v) {
  const Pitch& pitch = game.pitch();
  const Rules& r = pitch.rules;
  const double dir = pitch.direction();

  // Sky: one glClear (a plain colour; llvmpipe clears at memset speed but
  // shades a window-sized gradient slowly: measured under load, 6 ms a
  // frame for the sky as triangles against ~1 ms as a clear). Grass: mowing
  // stripes one metre wide, opaque, drawn without blending.
  glClearColor(kSky.r, kSky.g, kSky.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  for (auto i = static_cast<long long>(std::floor(v.x0)); static_cast<double>(i) < v.x1; ++i) {
    const auto x = static_cast<double>(i);
    rect(x, v.y0, x + 1.0, 0.0, i % 2 == 0 ? kGrassA : kGrassB);
  }
  rect(v.x0, v.y0, v.x1, v.y0 + 0.35 * (0.0 - v.y0), kTurfShade);
  glDisable(GL_BLEND);
  draw::flush_shapes();
  glEnable(GL_BLEND);

  // The goal: net (behind everything), the near post (beside the plane of
  // play, so not solid here), the goal line, the obstacles.
  const Obstacle& bar = pitch.scene.obstacles[static_cast<size_t>(r.crossbar)];
  double back = r.goal_line + dir * 1.0, roof = bar.b.y();
  for (const Obstacle& o : pitch.scene.obstacles) {
    if (o.shape != ObstacleShape::Box) continue;
    if (dir > 0 && o.a.x() >= r.goal_line) back = std::max(back, o.a.x());
    if (dir < 0 && o.b.x() <= r.goal_line) back = std::min(back, o.b.x());
  }
  for (int i = 0; i <= 12; ++i) {
    const double x = r.goal_line + (back - r.goal_line) * i / 12.0;
    thick_line(Vec2(x, 0.0), Vec2(x, roof), 0.012, kNet);
  }
  for (int i = 0; i <= 12; ++i) {
    const double y = roof * i / 12.0;
    thick_line(Vec2(r.goal_line, y), Vec2(back, y), 0.012, kNet);
  }
  const double bar_width = bar.b.x() - bar.a.x();
  const double post0 = dir > 0 ? r.goal_line - bar_width : r.goal_line;
  rect(post0, 0.0, post0 + bar_width, bar.a.y(), kPost);
  rect(post0, -0.05, post0 + bar_width, 0.0, kWhite);  // the goal line on the grass

  // The line beyond which kicks do not count.
  const double zone = r.goal_line - dir * r.min_kick_distance;
  for (int dash = 0; dash < 14; ++dash) {  // 0.12 m dashes every 0.2 m up to 2.8 m
    const double y = 0.2 * dash;
    thick_line(Vec2(zone, y), Vec2(zone, y + 0.12), 0.03, kZone);
  }
  rect(std::min(zone, r.goal_line), -0.05, std::max(zone, r.goal_line), 0.0,
       Color{1.0f, 0.85f, 0.1f, 0.35f});

  for (const Obstacle& o : pitch.scene.obstacles) {
    if (o.shape == ObstacleShape::Box) {
      rect(o.a.x(), o.a.y(), o.b.x(), o.b.y(), kObstacle);
      rect_outline(o.a.x(), o.a.y(), o.b.x(), o.b.y(), 1.0 / v.scale,
                   Color{0.5f, 0.5f, 0.5f, 1.0f});
    } else {
      const double w = std::max(2.0 * o.radius, 2.0 / v.scale);
      thick_line(o.a, o.b, w, kObstacle);
      disc(o.a.x(), o.a.y(), 0.5 * w, 0.5 * w, kObstacle, 16);
      disc(o.b.x(), o.b.y(), 0.5 * w, 0.5 * w, kObstacle, 16);
    }
  }

  // The ball: a shadow that shrinks with height, the disc, two spokes that
  // show its spin.
  const State& s = game.ball();
  const double R = game.radius();
  const double lift = std::max(0.0, s.q.y() - R);
  const double shadow = R * std::max(0.3, 1.0 - 0.15 * lift);
  disc(s.q.x(), 0.0, shadow, 0.25 * shadow, Color{0.0f, 0.0f, 0.0f, 0.3f}, 20);
  disc(s.q.x(), s.q.y(), R, R, kWhite);
  ring(s.q.x(), s.q.y(), R, 1.5 / v.scale, kOutline);
  for (int i = 0; i < 2; ++i) {
    const double a = s.q.z() + i * kPi / 2.0;
    const Vec2 d(std::cos(a) * R, std::sin(a) * R);
    thick_line(Vec2(s.q.x(), s.q.y()) - d, Vec2(s.q.x(), s.q.y()) + d, 0.018, kOutline);
  }
  disc(s.q.x() + 0.45 * R * std::cos(s.q.z() + 0.8), s.q.y() + 0.45 * R * std::sin(s.q.z() + 0.8),
       0.25 * R, 0.25 * R, kOutline, 10);

  // Aim (the kick's direction) and the force being applied.
  const Vec2 c(s.q.x(), s.q.y());
  const double a = game.kick_angle() * kPi / 180.0;
  const Vec2 aim(dir * std::cos(a), std::sin(a));
  for (int i = 0; i < 5; ++i) {
    const double t0 = R + 0.1 + 0.2 * i;
    thick_line(c + t0 * aim, c + (t0 + 0.1) * aim, 0.025, kAim);
  }
  const Vec3 f = game.applied();
  const double fn = std::hypot(f.x(), f.y());
  if (fn > 0.0) {
    // 0.15 m per N up to 1.5 m: a push (a few N) and a kick (~100 N) both show.
    const double len = std::min(1.5, 0.15 * fn);
    arrow(c, c + Vec2(f.x(), f.y()) * (len / fn), 0.05, kForce);
  }
}

// "REF" or "MUJOCO" (with a mapping: "MUJOCO:EXACT"), as the HUD names it.
std::string engine_label(std::string_view name) {
  std::string out(name);
  for (char& ch : out) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return out;
}

// The messages and banners in the middle of the screen: an ignored kick,
// the round's result, the pause and the countdown before the first pass.
void draw_banners(const Game& game, const Overlay& overlay, int width, int height) {
  const Rules& r = game.pitch().rules;
  // A kick key that did nothing, for a second: why.
  if (game.ignored_kick() != IgnoredKick::None &&
      static_cast<double>(game.steps_since_ignored_kick()) * game.dt() < 1.0) {
    const std::string what = game.ignored_kick() == IgnoredKick::RoundOver
                                 ? fmt("KICK IGNORED: THE ROUND IS OVER, NEXT PASS IN %.1f s",
                                       static_cast<double>(game.steps_to_next_pass()) * game.dt())
                                 : std::string("KICK IGNORED: THE LAST KICK IS STILL ACTING");
    const double w = text_width(what, 2.0);
    rect(0.5 * (width - w) - 10, 0.38 * height + 70, 0.5 * (width + w) + 10, 0.38 * height + 98,
         kPanel);
    text(0.5 * (width - w), 0.38 * height + 76, what, 2.0, kNoGoal);
  }

  // Result of the round.
  if (game.phase() == Phase::Over) {
    const Outcome outcome = game.current_round().outcome;
    const std::string what = outcome_text(outcome, r.min_kick_distance);
    const double scale = outcome == Outcome::Goal ? 6.0 : 2.5;
    const double w = text_width(what, scale);
    rect(0.5 * (width - w) - 20, 0.38 * height - 14, 0.5 * (width + w) + 20,
         0.38 * height + 9 * scale, kPanel);
    text(0.5 * (width - w), 0.38 * height, what, scale, outcome == Outcome::Goal ? kGoal : kNoGoal);
  }
  if (overlay.paused) {
    const double w = text_width("PAUSED", 4.0);
    text(0.5 * (width - w), 0.25 * height, "PAUSED", 4.0, kText);
  }
  // Before the first pass: the countdown.
  if (overlay.get_ready > 0.0) {
    const std::string what = fmt("GET READY: THE PASS COMES IN %.1f s", overlay.get_ready);
    const double w = text_width(what, 2.5);
    rect(0.5 * (width - w) - 20, 0.38 * height - 14, 0.5 * (width + w) + 20,
         0.38 * height + 9 * 2.5, kPanel);
    text(0.5 * (width - w), 0.38 * height, what, 2.5, kText);
  }
}

// The help panel: the rules and the keys.
void draw_help(int width, int height) {
  const char* lines[] = {
      "CONTACT2D PLAY - score from at least 1 m",
      "",
      "A teammate passes: the ball rolls in towards the goal.",
      "Kick it into the goal. A kick counts only if the ball",
      "is at least 1 m from the goal line (the yellow line).",
      "The whole ball must cross the line under the crossbar,",
      "and the last touch must be a counted kick.",
      "The crossbar, the roof and the back of the goal are solid.",
      "",
      "ARROWS        push the ball (a force)",
      "K / ENTER     kick towards the goal",
      "W / S         raise / lower the kick angle",
      "SPACE         pause (this help pauses too)",
      "BACKSPACE     next pass",
      "F1 / H        this help",
      "ESC           quit",
  };
  double widest = 0.0;
  for (const char* line : lines) widest = std::max(widest, text_width(line, 2.0));
  const double x0 = std::max(16.0, 0.5 * (width - widest)), y0 = 120;
  // The panel is a scissored clear (the world is already drawn and the HUD
  // not yet): llvmpipe clears far faster than it shades a large quad.
  const int top = static_cast<int>(y0 - 16), bottom = static_cast<int>(y0 + 16 * 22 + 8);
  glEnable(GL_SCISSOR_TEST);
  glScissor(static_cast<int>(x0 - 16), height - bottom, static_cast<int>(widest + 32),
            bottom - top);
  glClearColor(0.06f, 0.08f, 0.11f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  double y = y0;
  for (const char* line : lines) {
    text(x0, y, line, 2.0, kText);
    y += 22;
  }
}

void draw_hud(const Game& game, const Overlay& overlay, const View& v, int width, int height) {
  const Pitch& pitch = game.pitch();
  const Rules& r = pitch.rules;
  const State& s = game.ball();
  const Vec3 f = game.applied();

  rect(0, 0, width, 78, kPanel);
  text(10, 8,
       fmt("ROUND %.0f   GOALS %.0f   TIME %.1f s", game.round(), game.goals(), game.round_time()),
       2.0, kText);
  text(10, 30,
       fmt("SPEED %.2f m/s   DISTANCE TO GOAL %.2f m", std::hypot(s.v.x(), s.v.y()),
           game.distance_to_goal()),
       2.0, kText);
  text(10, 52, fmt("KICK ANGLE %.0f deg   FORCE (%.1f, %.1f) N", game.kick_angle(), f.x(), f.y()),
       2.0, kText);
  // A recording shows neither the frame rate (that of the encoder, not the
  // game) nor a REC mark.
  std::string right = "ENGINE " + engine_label(game.engine_name()) + "   F1/H: HELP";
  if (overlay.fps > 0.0 && !overlay.recording) right = fmt("%.0f FPS", overlay.fps) + "   " + right;
  text(width - 10 - text_width(right, 1.5), 10, right, 1.5, kText);
  if (overlay.replaying) text(width - 10 - text_width("REPLAY", 2.0), 34, "REPLAY", 2.0, kGoal);
  // The engine cannot keep up at this frame rate: the game runs slower.
  if (!overlay.recording && overlay.speed < 0.97) {
    const std::string slow = fmt("SLOW MOTION x%.2f", overlay.speed);
    text(width - 10 - text_width(slow, 1.5), 58, slow, 1.5, kNoGoal);
  }

  // Label of the 1 m line, at its foot.
  const Vec2 zone = v.pixel(r.goal_line - pitch.direction() * r.min_kick_distance, 0.0, height);
  const std::string zone_label = fmt("%g m", r.min_kick_distance);
  text(zone.x() - 0.5 * text_width(zone_label, 1.5), zone.y() + 8, zone_label, 1.5, kZone);

  // The last kick, while it is recent.
  if (!game.kicks().empty()) {
    const KickRecord& k = game.kicks().back();
    if (k.round == game.round() && game.time() - k.time < 2.0) {
      const std::string what = k.counted ? fmt("KICK FROM %.2f m", k.distance)
                                         : fmt("KICK FROM %.2f m: INSIDE %g m, DOES NOT COUNT",
                                               k.distance, r.min_kick_distance);
      text(10, 88, what, 2.0, k.counted ? kGoal : kNoGoal);
    }
  }

  // The help overlay is modal: the banners would show through it (the HUD's
  // text is drawn after its panel is cleared).
  if (overlay.help) {
    draw_help(width, height);
  } else {
    draw_banners(game, overlay, width, height);
  }
}

}  // namespace

void draw_frame(const Game& game, const Overlay& overlay, int width, int height) {
  const View v(game.pitch(), game.ball().q.x(), width, height);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(v.x0, v.x1, v.y0, v.y1, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  draw_world(game, v);
  draw::flush_shapes();

  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0.0, width, height, 0.0, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  draw_hud(game, overlay, v, width, height);
  glDisable(GL_BLEND);  // the HUD is opaque: blending would read every pixel back
  draw::flush_shapes();
  draw::flush_text();
}

}  // namespace contact2d::game
