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
constexpr Color kKeeper{0.95f, 0.55f, 0.1f, 1.0f};  // the keeper's jersey
constexpr Color kTeam{0.15f, 0.25f, 0.75f, 1.0f};   // the player's and the teammate's
constexpr Color kSkin{0.93f, 0.76f, 0.6f, 1.0f};
constexpr Color kShorts{0.95f, 0.95f, 0.95f, 1.0f};
constexpr Color kPreview{1.0f, 0.95f, 0.3f, 0.85f};
// Text over the pitch: not pure white, which is the ball's alone (the window
// test finds the ball by it).
constexpr Color kPanelText{0.92f, 0.94f, 0.98f, 1.0f};

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
  return format_text(format, a, b, c);
}

// World-to-screen mapping: a camera that frames the ball and the whole goal
// (from kBehind metres behind the ball to kBeyond beyond the goal's back,
// never narrower than kMinViewWidth, within the pitch's ends), so the
// keeper, the goal and the pass are in view together; the grass line sits
// 90 px above the bottom. Near the goal it shows 7 m: the 0.22 m ball is
// 2R·800/7 = 25.1 px across; from the pass's start it shows the whole 13 m
// pitch (13.5 px; tests/game/test_window.cpp measures the white inside the
// outline).
constexpr double kMinViewWidth = 7.0;  // m
constexpr double kBehind = 1.5;        // m behind the ball
constexpr double kBeyond = 0.9;        // m beyond the goal's back

// The goal's back: the farthest face of the obstacles beyond the goal line
// on the goal's side (the net), 1 m beyond the line without one.
double goal_back(const Pitch& pitch) {
  const Rules& r = pitch.rules;
  const double dir = pitch.direction();
  double back = r.goal_line + dir * 1.0;
  for (const Obstacle& o : pitch.scene.obstacles) {
    if (o.shape != ObstacleShape::Box) continue;
    if (dir > 0 && o.a.x() >= r.goal_line) back = std::max(back, o.a.x());
    if (dir < 0 && o.b.x() <= r.goal_line) back = std::min(back, o.b.x());
  }
  return back;
}

struct View {
  double x0, x1, y0, y1, scale;  // metres; pixels per metre
  View(const Pitch& pitch, double ball_x, int width, int height) {
    const Rules& r = pitch.rules;
    const double dir = pitch.direction();
    const double widest = r.pitch_max_x - r.pitch_min_x;
    const double end = goal_back(pitch) + dir * kBeyond;  // the goal's side of the view
    const double w = std::min(widest, std::max(kMinViewWidth, dir * (end - ball_x) + kBehind));
    x0 = dir > 0 ? end - w : end;
    x0 = std::clamp(x0, r.pitch_min_x, r.pitch_max_x - w);
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

// A person seen from the side, standing at x on the grass, `facing` +1 or
// −1; `kick` swings the front leg forward. Drawn only, not in the physics.
void person(double x, double facing, const Color& jersey, double kick = 0.0) {
  const double hip = 0.9, shoulder = 1.45, head = 1.65;
  const Vec2 h(x, hip);
  const double swing = 0.55 * kick;
  thick_line(h, Vec2(x - facing * 0.15, 0.0), 0.11, kSkin);  // back leg
  thick_line(h, Vec2(x + facing * (0.12 + swing), 0.05 + 0.3 * kick), 0.11, kSkin);
  rect(x - 0.13, hip - 0.2, x + 0.13, hip + 0.05, kShorts);
  thick_line(Vec2(x, hip), Vec2(x, shoulder), 0.3, jersey);
  thick_line(Vec2(x, shoulder - 0.05), Vec2(x + facing * 0.25, hip + 0.15), 0.08, jersey);
  disc(x, head, 0.13, 0.13, kSkin, 16);
}

// The keeper: its box is the whole solid keeper (what the ball bounces
// off), so the figure is drawn inside it: legs, shorts, jersey, head and
// both arms up with gloves at the top corners, the box's outline faint
// around it. When the game lifts the box (the keeper jumps) nothing joins
// it to the grass: it is in the air, its shadow on the grass below.
void draw_keeper(const Obstacle& k, const View& v) {
  const double x0 = k.a.x(), x1 = k.b.x(), y0 = k.a.y(), y1 = k.b.y();
  const double w = x1 - x0, h = y1 - y0, cx = 0.5 * (x0 + x1);
  auto at = [&](double fx, double fy) { return Vec2(x0 + fx * w, y0 + fy * h); };
  const double lift = std::max(0.0, y0);
  const double shadow = 0.5 * w * std::max(0.3, 1.0 - 0.3 * lift);
  disc(cx, 0.0, shadow, 0.25 * shadow, Color{0.0f, 0.0f, 0.0f, 0.3f}, 16);
  rect(x0, y0, x1, y1, Color{0.95f, 0.55f, 0.1f, 0.18f});  // the solid box, faint
  const double limb = 0.16 * w;
  thick_line(at(0.35, 0.02), at(0.35, 0.36), limb, kSkin);  // legs
  thick_line(at(0.65, 0.02), at(0.65, 0.36), limb, kSkin);
  rect(x0 + 0.2 * w, y0 + 0.32 * h, x1 - 0.2 * w, y0 + 0.44 * h, Color{0.1f, 0.1f, 0.1f, 1.0f});
  rect(x0 + 0.16 * w, y0 + 0.43 * h, x1 - 0.16 * w, y0 + 0.74 * h, kKeeper);  // jersey
  thick_line(at(0.22, 0.7), at(0.06, 0.95), limb, kKeeper);                   // arms up
  thick_line(at(0.78, 0.7), at(0.94, 0.95), limb, kKeeper);
  // (Gloves off-white: pure white is the ball's alone, which the window
  // test measures.)
  const Color glove{0.97f, 0.97f, 0.88f, 1.0f};
  disc(x0 + 0.08 * w, y0 + 0.95 * h, 0.09 * w, 0.09 * w, glove, 12);
  disc(x1 - 0.08 * w, y0 + 0.95 * h, 0.09 * w, 0.09 * w, glove, 12);
  disc(cx, y0 + 0.84 * h, 0.2 * w, 0.2 * w, kSkin, 16);  // head
  rect_outline(x0, y0, x1, y1, 1.0 / v.scale, Color{0.1f, 0.1f, 0.1f, 0.5f});
}

// The keeper (where the physics has it) and the player, drawn before the
// ball.
void draw_keeper_and_player(const Game& game, const View& v) {
  const Pitch& pitch = game.pitch();
  const Rules& r = pitch.rules;
  const double dir = pitch.direction();
  if (game.has_keeper()) draw_keeper(game.keeper(), v);

  // The player: behind the ball on the grass, at least 1.5 m in front of
  // the teammate (where the pass comes to him); after a kick, where it was
  // taken, the kicking leg swung while the kick acts.
  const State& s = game.ball();
  const double R = game.radius();
  double player = s.q.x() - dir * (R + 0.3);
  if (!game.kicks().empty() && game.kicks().back().round == game.round())
    player = r.goal_line - dir * game.kicks().back().distance - dir * (R + 0.3);
  player = dir > 0 ? std::max(player, r.pass_x + 1.5) : std::min(player, r.pass_x - 1.5);
  person(player, dir, kTeam, game.kicking() ? 1.0 : 0.0);
}

// The aim and the kick's preview while the ball is in reach, and the force
// being applied, over the ball.
void draw_aim_and_force(const Game& game) {
  const double dir = game.pitch().direction();
  const State& s = game.ball();
  const double R = game.radius();
  // Aim (the kick's direction) while the ball is in reach, and the force
  // being applied.
  const Vec2 c(s.q.x(), s.q.y());
  const bool aiming = game.phase() == Phase::Playing && game.in_reach() && !game.kicking();
  const double a = game.kick_angle() * kPi / 180.0;
  const Vec2 aim(dir * std::cos(a), std::sin(a));
  for (int i = 0; aiming && i < 5; ++i) {
    const double t0 = R + 0.1 + 0.2 * i;
    thick_line(c + t0 * aim, c + (t0 + 0.1) * aim, 0.025, kAim);
  }
  // The kick the player would take now, as dots every 0.03 s: the no-drag
  // path without spin or bounce (kick_preview), while the ball is in reach.
  if (aiming) {
    Vec2 path[64];
    const int n = kick_preview(game, 0.03, path, 64);
    for (int i = 1; i < n; ++i) disc(path[i].x(), path[i].y(), 0.035, 0.035, kPreview, 8);
  }
  const Vec3 f = game.applied();
  const double fn = std::hypot(f.x(), f.y());
  if (fn > 0.0) {
    // 0.15 m per N up to 1.5 m: a push (a few N) and a kick (~100 N) both show.
    const double len = std::min(1.5, 0.15 * fn);
    arrow(c, c + Vec2(f.x(), f.y()) * (len / fn), 0.05, kForce);
  }
}

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
  const double back = goal_back(pitch), roof = bar.b.y();
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

  // The teammate who passed, behind where the pass starts.
  person(r.pass_x - dir * 0.45, dir, kTeam, game.round_time() < 0.25 ? 1.0 : 0.0);

  for (size_t i = 0; i < pitch.scene.obstacles.size(); ++i) {
    const Obstacle& o = pitch.scene.obstacles[i];
    if (game.has_keeper() && static_cast<int>(i) == r.keeper) continue;  // drawn below
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

  draw_keeper_and_player(game, v);

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
}

// A panel of centred lines in the middle of the screen; the first line at
// `first_scale` in `first_colour`, the others at 2.
void centred_panel(const std::vector<std::string>& lines, double first_scale,
                   const Color& first_colour, int width, int height) {
  double widest = 0.0, tall = 0.0;
  for (size_t i = 0; i < lines.size(); ++i) {
    const double scale = i == 0 ? first_scale : 2.0;
    widest = std::max(widest, text_width(lines[i], scale));
    tall += 9.0 * scale + 8.0;
  }
  const double top = 0.34 * height;
  rect(0.5 * (width - widest) - 20, top - 14, 0.5 * (width + widest) + 20, top + tall + 4, kPanel);
  double y = top;
  for (size_t i = 0; i < lines.size(); ++i) {
    const double scale = i == 0 ? first_scale : 2.0;
    text(0.5 * (width - text_width(lines[i], scale)), y, lines[i], scale,
         i == 0 ? first_colour : kPanelText);
    y += 9.0 * scale + 8.0;
  }
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& ch : out) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return out;
}

// The screens of their own, over the middle: the start screen (before the
// first pass) and the end of a session (the game waits for Backspace).
void draw_screens(const Game& game, const Overlay& overlay, int width, int height) {
  const Rules& r = game.pitch().rules;
  if (overlay.get_ready > 0.0) {
    centred_panel(
        {"BEAT THE KEEPER", "Your teammate passes. Control the ball (C),",
         "bring it closer (arrows), aim (W/S angle, A/D power)",
         "and chip it over the keeper into the goal (K).",
         fmt("%.0f passes a session.", r.session_rounds),
         "Level " + upper(level_name(game.level())) + " (keys 1, 2, 3: easy, normal, hard)",
         fmt("THE PASS COMES IN %.1f s   (F1: HELP)", overlay.get_ready)},
        4.0, kGoal, width, height);
  } else if (game.session_finished()) {
    centred_panel(
        {"SESSION OVER", fmt("%.0f GOALS FROM %.0f PASSES", game.session_goals(), r.session_rounds),
         fmt("BEST SESSION SO FAR: %.0f GOALS", game.best_session_goals()),
         "NEXT LEVEL " + upper(level_name(game.level())) + " (KEYS 1, 2, 3: EASY, NORMAL, HARD)",
         "BACKSPACE: A NEW SESSION    ESC: QUIT"},
        4.0, kGoal, width, height);
  }
}

// The help panel: the rules and the keys.
void draw_help(int width, int height) {
  const char* lines[] = {
      "CONTACT2D PLAY - beat the keeper, score from at least 1 m",
      "",
      "A teammate passes: the ball comes rolling or bouncing.",
      "You reach it while it is below 0.9 m: control it, bring",
      "it closer, aim and kick. A kick counts only if the ball is",
      "at least 1 m from the goal line (the yellow line). The",
      "whole ball must cross the line under the crossbar, and the",
      "last touch must be a counted kick. The keeper moves up to",
      "where the ball will reach it: from far it gets there in",
      "time; a chip from close, high over it, beats it.",
      "The yellow dots: your kick's path (no spin, no bounce).",
      "",
      "C             control: brake the ball (a force)",
      "ARROWS        push the ball (a force)",
      "W / S         raise / lower the kick angle",
      "D / A         more / less kick power",
      "K / ENTER     kick towards the goal",
      "SPACE         pause (this help pauses too)",
      "BACKSPACE     next pass (after a session: a new one)",
      "1 / 2 / 3     level easy / normal / hard (at the start,",
      "              or after a session for the next one)",
      "F1 / H        this help",
      "ESC           quit",
  };
  double widest = 0.0;
  for (const char* line : lines) widest = std::max(widest, text_width(line, 2.0));
  const double x0 = std::max(16.0, 0.5 * (width - widest)), y0 = 100;
  // The panel is a scissored clear (the world is already drawn and the HUD
  // not yet): llvmpipe clears far faster than it shades a large quad.
  const int top = static_cast<int>(y0 - 16),
            bottom = static_cast<int>(y0 + 22 * static_cast<double>(std::size(lines)) + 8);
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

// Glyphs' height at `scale` (stb_easy_font: 7 units above the baseline, 2
// below for descenders, and a unit to spare).
double glyph_height(double scale) { return 10.0 * scale; }

TextItem text_item(std::string what, double x, double y, double scale, const Color& colour) {
  TextItem t;
  t.box = {x, y, x + text_width(what, scale), y + glyph_height(scale)};
  t.text = std::move(what);
  t.x = x;
  t.y = y;
  t.scale = scale;
  t.colour = colour;
  return t;
}

// The HUD's lines along the top, on its panel.
void hud_texts(const Game& game, const Overlay& overlay, int width, FrameLayout& out) {
  const Rules& r = game.pitch().rules;
  const State& s = game.ball();
  const Vec3 f = game.applied();
  out.texts.push_back(text_item(fmt("PASS %.0f/%.0f   GOALS %.0f", game.session_round(),
                                    r.session_rounds, game.session_goals()) +
                                    fmt("   BEST %.0f   ", game.best_session_goals()) +
                                    upper(level_name(game.level())),
                                10, 8, 2.0, kText));
  const std::string reach = !game.in_reach()     ? "   OUT OF REACH"
                            : game.controlling() ? "   CONTROL"
                                                 : "";
  out.texts.push_back(
      text_item(fmt("TIME %.1f s   SPEED %.2f m/s   TO GOAL %.2f m", game.round_time(),
                    std::hypot(s.v.x(), s.v.y()), game.distance_to_goal()) +
                    reach,
                10, 30, 2.0, game.in_reach() ? kText : kNoGoal));
  out.texts.push_back(text_item(
      fmt("KICK ANGLE %.0f deg   POWER %.0f %%", game.kick_angle(), 100.0 * game.kick_power()) +
          "   FORCE " + force_text(f.x(), f.y()) + " N",
      10, 52, 2.0, kText));
  // A recording shows neither the frame rate (that of the encoder, not the
  // game) nor a REC mark.
  std::string right = "ENGINE " + upper(game.engine_name()) + "   F1/H: HELP";
  if (overlay.fps > 0.0 && !overlay.recording) right = fmt("%.0f FPS", overlay.fps) + "   " + right;
  if (overlay.replaying) right = "REPLAY   " + right;
  out.texts.push_back(text_item(right, width - 10 - text_width(right, 1.5), 10, 1.5,
                                overlay.replaying ? kGoal : kText));
  // The engine cannot keep up at this frame rate: the game runs slower.
  if (!overlay.recording && overlay.speed < 0.97) {
    const std::string slow = fmt("SLOW MOTION x%.2f", overlay.speed);
    out.texts.push_back(text_item(slow, width - 10 - text_width(slow, 1.5), 58, 1.5, kNoGoal));
  }
}

struct BandLine {
  std::string text;
  double scale;
  Color colour;
};

// What the band says now, most important first: the round's result, a
// kick key that did nothing (for a second), the last kick (for 2 s), the
// preview's legend while aiming, the pause.
std::vector<BandLine> band_lines(const Game& game, const Overlay& overlay) {
  const Rules& r = game.pitch().rules;
  std::vector<BandLine> lines;
  if (game.phase() == Phase::Over && !game.session_finished()) {
    const Outcome outcome = game.current_round().outcome;
    lines.push_back({outcome_text(outcome, r.min_kick_distance), 4.0,
                     outcome == Outcome::Goal ? kGoal : kNoGoal});
    lines.push_back({fmt("PASS %.0f OF %.0f: %.0f GOALS   ", game.session_round(), r.session_rounds,
                         game.session_goals()) +
                         fmt(game.session_round() >= r.session_rounds ? "THE SESSION ENDS IN %.1f s"
                                                                      : "NEXT PASS IN %.1f s",
                             static_cast<double>(game.steps_to_next_pass()) * game.dt()),
                     2.0, kPanelText});
  }
  if (game.ignored_kick() != IgnoredKick::None &&
      static_cast<double>(game.steps_since_ignored_kick()) * game.dt() < 1.0) {
    std::string what;
    switch (game.ignored_kick()) {
      case IgnoredKick::RoundOver:
        what = game.session_finished()
                   ? std::string("KICK IGNORED: THE SESSION IS OVER (BACKSPACE: A NEW ONE)")
                   : fmt("KICK IGNORED: THE ROUND IS OVER, NEXT PASS IN %.1f s",
                         static_cast<double>(game.steps_to_next_pass()) * game.dt());
        break;
      case IgnoredKick::StillKicking: what = "KICK IGNORED: THE LAST KICK IS STILL ACTING"; break;
      case IgnoredKick::OutOfReach:
        what = fmt("KICK IGNORED: OUT OF REACH (THE BALL IS ABOVE %.1f m)", r.reach_height);
        break;
      case IgnoredKick::None: break;
    }
    lines.push_back({what, 2.0, kNoGoal});
  }
  if (!game.kicks().empty() && game.phase() == Phase::Playing) {
    const KickRecord& k = game.kicks().back();
    if (k.round == game.round() && game.time() - k.time < 2.0) {
      lines.push_back({k.counted ? fmt("KICK FROM %.2f m", k.distance)
                                 : fmt("KICK FROM %.2f m: INSIDE %g m, DOES NOT COUNT", k.distance,
                                       r.min_kick_distance),
                       2.0, k.counted ? kGoal : kNoGoal});
    }
  }
  if (game.phase() == Phase::Playing && game.in_reach() && !game.kicking())
    lines.push_back({"YELLOW DOTS: THE KICK'S PATH WITHOUT DRAG, SPIN OR BOUNCE", 1.5, kPreview});
  if (overlay.paused) lines.push_back({"PAUSED (SPACE: GO ON)", 2.0, kPanelText});
  return lines;
}

// The band's lines, centred, stacked from its top; scaled down together
// when they do not fit its height, each also to the screen's width.
void band_texts(const std::vector<BandLine>& lines, const ScreenBox& band, FrameLayout& out) {
  constexpr double kGap = 4.0;
  double tall = 0.0;
  for (const BandLine& l : lines) tall += glyph_height(l.scale);
  const double room = (band.y1 - band.y0) - kGap * static_cast<double>(lines.size() + 1);
  const double shrink = tall > room && tall > 0.0 ? std::max(0.0, room) / tall : 1.0;
  double y = band.y0 + kGap;
  for (const BandLine& l : lines) {
    double scale = l.scale * shrink;
    const double w = text_width(l.text, scale);
    if (w > band.x1 - band.x0 - 16.0) scale *= (band.x1 - band.x0 - 16.0) / w;
    const double x = 0.5 * (band.x0 + band.x1 - text_width(l.text, scale));
    out.texts.push_back(text_item(l.text, x, y, scale, l.colour));
    y += glyph_height(l.scale * shrink) + kGap;
  }
}

ScreenBox pixel_box(const View& v, double x0, double y0, double x1, double y1, int height) {
  const Vec2 a = v.pixel(x0, y1, height), b = v.pixel(x1, y0, height);
  return {std::min(a.x(), b.x()), a.y(), std::max(a.x(), b.x()), b.y()};
}

// Where the keeper, the ball and the aim with the kick's preview are.
void play_boxes(const Game& game, const View& v, int height, FrameLayout& out) {
  const State& s = game.ball();
  const double R = game.radius();
  if (game.has_keeper()) {
    const Obstacle& k = game.keeper();
    out.keeper = pixel_box(v, k.a.x(), k.a.y(), k.b.x(), k.b.y(), height);
  }
  out.ball = pixel_box(v, s.q.x() - R, s.q.y() - R, s.q.x() + R, s.q.y() + R, height);
  if (game.phase() == Phase::Playing && game.in_reach() && !game.kicking()) {
    // The aim's dashes reach R + 1 m from the centre; the dots 0.035 m wide.
    const double dir = game.pitch().direction(), a = game.kick_angle() * kPi / 180.0;
    double x0 = s.q.x(), x1 = s.q.x(), y0 = s.q.y(), y1 = s.q.y();
    const auto widen = [&](double x, double y, double r) {
      x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
      y0 = std::min(y0, y - r), y1 = std::max(y1, y + r);
    };
    widen(s.q.x() + (R + 1.0) * dir * std::cos(a), s.q.y() + (R + 1.0) * std::sin(a), 0.02);
    Vec2 path[64];
    const int n = kick_preview(game, 0.03, path, 64);
    for (int i = 1; i < n; ++i) widen(path[i].x(), path[i].y(), 0.035);
    out.path = pixel_box(v, x0, y0, x1, y1, height);
  }
}

FrameLayout layout_in(const Game& game, const Overlay& overlay, const View& v, int width,
                      int height) {
  const Rules& r = game.pitch().rules;
  FrameLayout out;
  out.hud = {0.0, 0.0, static_cast<double>(width), 78.0};
  const double grass = v.pixel(v.x0, 0.0, height).y();
  out.pitch = {0.0, out.hud.y1, static_cast<double>(width), grass};
  hud_texts(game, overlay, width, out);
  // The 1 m line's label, at its foot under the grass line; the band below
  // it down to the bottom (at least 24 px: then over the grass under the
  // line, where nothing is played either).
  const Vec2 zone =
      v.pixel(r.goal_line - game.pitch().direction() * r.min_kick_distance, 0.0, height);
  const std::string zone_label = fmt("%g m", r.min_kick_distance);
  TextItem label =
      text_item(zone_label, zone.x() - 0.5 * text_width(zone_label, 1.5), zone.y() + 8, 1.5, kZone);
  const double band_top = std::max(grass + 4.0, std::min(label.box.y1 + 3.0, height - 24.0));
  out.band = {0.0, band_top, static_cast<double>(width), static_cast<double>(height)};
  // The help is modal and drawn over the middle down to the band: the label
  // and the messages wait under it (text is drawn at the frame's end, it
  // would show through).
  if (!overlay.help) {
    out.texts.push_back(std::move(label));
    band_texts(band_lines(game, overlay), out.band, out);
  }
  play_boxes(game, v, height, out);
  return out;
}

void draw_hud(const Game& game, const Overlay& overlay, const FrameLayout& layout, int width,
              int height) {
  rect(layout.hud.x0, layout.hud.y0, layout.hud.x1, layout.hud.y1, kPanel);
  // (Shapes and text are drawn at the frame's end, after the help's panel,
  // which is a clear: the band would cover its last lines.)
  if (!overlay.help) rect(layout.band.x0, layout.band.y0, layout.band.x1, layout.band.y1, kPanel);
  for (const TextItem& t : layout.texts) {
    if (t.panel) rect(t.box.x0, t.box.y0, t.box.x1, t.box.y1, kPanel);
    text(t.x, t.y, t.text, t.scale, t.colour);
  }
  // The help overlay is modal: the screens would show through it (the HUD's
  // text is drawn after its panel is cleared).
  if (overlay.help) {
    draw_help(width, height);
  } else {
    draw_screens(game, overlay, width, height);
  }
}

}  // namespace

std::string force_text(double fx, double fy) {
  // Rounded to 0.1 first: −0.04 prints as "-0.0" otherwise; + 0.0 turns −0 into 0.
  const auto tenth = [](double v) { return std::round(v * 10.0) / 10.0 + 0.0; };
  return fmt("(%.1f, %.1f)", tenth(fx), tenth(fy));
}

FrameLayout frame_layout(const Game& game, const Overlay& overlay, int width, int height) {
  return layout_in(game, overlay, View(game.pitch(), game.ball().q.x(), width, height), width,
                   height);
}

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
  draw_aim_and_force(game);
  draw::flush_shapes();

  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0.0, width, height, 0.0, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  draw_hud(game, overlay, layout_in(game, overlay, v, width, height), width, height);
  glDisable(GL_BLEND);  // the HUD is opaque: blending would read every pixel back
  draw::flush_shapes();
  draw::flush_text();
}

}  // namespace contact2d::game
