#include "game/comparison_video.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <vector>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "game/draw2d.hpp"
#include "game/offscreen.hpp"
#include "game/video.hpp"

namespace contact2d::game {
namespace {

using draw::Color;

constexpr Color rgb(const int (&c)[3]) {
  return Color{static_cast<float>(c[0]) / 255.0f, static_cast<float>(c[1]) / 255.0f,
               static_cast<float>(c[2]) / 255.0f, 1.0f};
}
constexpr Color kReference = rgb(kReferenceRgb);
constexpr Color kReferenceEdge{0.55f, 0.29f, 0.03f, 1.0f};
constexpr Color kSecond = rgb(kSecondRgb);
constexpr Color kConverged = rgb(kConvergedRgb);
constexpr Color kBackground{0.96f, 0.96f, 0.94f, 1.0f};
constexpr Color kGround{0.47f, 0.44f, 0.40f, 1.0f};
constexpr Color kGroundLine{0.25f, 0.23f, 0.21f, 1.0f};
constexpr Color kObstacle{0.72f, 0.72f, 0.72f, 1.0f};
constexpr Color kObstacleEdge{0.45f, 0.45f, 0.45f, 1.0f};
constexpr Color kPanel{0.13f, 0.17f, 0.24f, 1.0f};  // the game's HUD panel
constexpr Color kText{1.0f, 1.0f, 1.0f, 1.0f};
constexpr Color kWarning{1.0f, 0.55f, 0.45f, 1.0f};

constexpr double kOutlinePx =
    4.0;  // the second run's outline; ≥ 4 px keeps whole 2×2 chroma blocks
constexpr double kThinPx = 1.5;     // the converged solution
constexpr double kMarginPx = 24.0;  // around the fitted trajectories

std::string lower_extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// State at t: linear between the samples around t (θ too), the first
// sample before it, the last one after it.
State state_at(const Trajectory& trajectory, double t) {
  const std::vector<Sample>& s = trajectory.samples;
  const auto after = std::upper_bound(s.begin(), s.end(), t,
                                      [](double time, const Sample& x) { return time < x.t; });
  if (after == s.begin()) return s.front().state;
  if (after == s.end()) return s.back().state;
  const Sample& a = *(after - 1);
  const Sample& b = *after;
  const double w = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
  State out;
  out.q = a.state.q + w * (b.state.q - a.state.q);
  out.v = a.state.v + w * (b.state.v - a.state.v);
  return out;
}

double com_distance(const State& a, const State& b) {
  return std::hypot(a.q.x() - b.q.x(), a.q.y() - b.q.y());
}

// Distances as text in a unit that suits them.
std::string distance_text(double d) {
  if (!std::isfinite(d)) return "-";
  if (d < 1e-9) return format_text("%.2e m", d);
  if (d < 1e-6) return format_text("%.3g nm", d * 1e9);
  if (d < 1e-3) return format_text("%.3g um", d * 1e6);
  if (d < 1.0) return format_text("%.3g mm", d * 1e3);
  return format_text("%.3g m", d);
}

// The body at state s as polygons (box, T: one per part) in world frame.
std::vector<std::vector<Vec2>> body_polygons(const RigidBody& body, const State& s) {
  const double th = shape_features(body.shape).turns ? s.q.z() : 0.0;
  const double c = std::cos(th), sn = std::sin(th);
  const Vec2 p(s.q.x(), s.q.y());
  const auto world = [&](const Vec2& r) {
    return Vec2(p.x() + c * r.x() - sn * r.y(), p.y() + sn * r.x() + c * r.y());
  };
  std::vector<std::vector<Vec2>> out;
  if (shape_features(body.shape).smooth) {  // the ellipse's rim, 48 points
    std::vector<Vec2> rim;
    for (int i = 0; i < 48; ++i) {
      const double phi = 6.283185307179586 * i / 48;
      rim.push_back(
          world(Vec2(body.semi_axes.x() * std::cos(phi), body.semi_axes.y() * std::sin(phi))));
    }
    out.push_back(std::move(rim));
  }
  for (const PartOutline& part : body.parts) {
    out.push_back({world(part.centre + Vec2(-part.hx, -part.hy)),
                   world(part.centre + Vec2(part.hx, -part.hy)),
                   world(part.centre + Vec2(part.hx, part.hy)),
                   world(part.centre + Vec2(-part.hx, part.hy))});
  }
  return out;
}

// Radius of a body drawn as a disc (circle, point mass), 0 for polygons.
double disc_radius(const RigidBody& body, const Scene& scene) {
  switch (body.shape) {
    case Shape::Circle: return body.roll_radius;
    case Shape::PointMass: return std::max(scene.half_height, 1e-3);
    case Shape::Box:
    case Shape::TShape:
    case Shape::Ellipse: break;  // polygons (body_polygons)
  }
  return 0.0;
}

enum class Style { Filled, Outlined, Thin };

void draw_body(const RigidBody& body, const Scene& scene, const State& s, Style style, double px) {
  const double r = disc_radius(body, scene);
  const Color& colour = style == Style::Filled     ? kReference
                        : style == Style::Outlined ? kSecond
                                                   : kConverged;
  const double width = (style == Style::Thin       ? kThinPx
                        : style == Style::Outlined ? kOutlinePx
                                                   : 1.0) *
                       px;
  if (r > 0.0) {
    const Vec2 centre(s.q.x(), s.q.y());
    if (style == Style::Filled) {
      draw::disc(centre.x(), centre.y(), r, r, colour, 48);
      draw::ring(centre.x(), centre.y(), r, width, kReferenceEdge, 48);
    } else {
      draw::ring(centre.x(), centre.y(), r, width, colour, 48);
    }
    // A spoke shows the rotation (a point mass does not rotate: none).
    if (shape_features(body.shape).turns) {
      const Vec2 u(std::cos(s.q.z()), std::sin(s.q.z()));
      draw::thick_line(centre, centre + r * u, std::max(width, 1.5 * px),
                       style == Style::Filled ? kReferenceEdge : colour);
    }
    return;
  }
  for (const std::vector<Vec2>& polygon : body_polygons(body, s)) {
    if (style == Style::Filled) {
      draw::convex_polygon(polygon, colour);
      draw::polygon_outline(polygon, width, kReferenceEdge);
    } else {
      draw::polygon_outline(polygon, width, colour);
    }
  }
}

// World-to-pixel mapping: the bounds fitted below the HUD, one scale.
struct Camera {
  double x0 = 0.0, x1 = 1.0, y0 = 0.0, y1 = 1.0;  // the whole frame, metres
  double scale = 1.0;                             // pixels per metre
};

struct Bounds {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  void add(const State& s, double extent) {
    if (!std::isfinite(s.q.x()) || !std::isfinite(s.q.y())) return;
    x0 = std::min(x0, s.q.x() - extent);
    x1 = std::max(x1, s.q.x() + extent);
    y0 = std::min(y0, s.q.y() - extent);
    y1 = std::max(y1, s.q.y() + extent);
  }
};

Camera fit_camera(const ComparisonVideoInput& in, const RigidBody& body, long long frames, int fps,
                  int width, int height) {
  const double extent = std::max(body_extent(body), disc_radius(body, *in.scene));
  Bounds b;
  for (const Sample& s : in.reference->samples) b.add(s.state, extent);
  if (in.converged) {
    for (long long i = 0; i < frames; ++i) {
      const double t = static_cast<double>(i) / fps;
      if (t <= in.converged->t_end()) b.add(in.converged->at(t), extent);
    }
  }
  // The second run's path widens the view by at most the reference's own size
  // (at least four body sizes) on each side: a run that blows up before
  // its divergence is caught leaves the frame instead of shrinking the
  // bodies to dots (the HUD says where it stopped).
  Bounds m;
  for (const Sample& s : in.second->samples) m.add(s.state, extent);
  if (b.x0 <= b.x1 && m.x0 <= m.x1) {
    const double reach = std::max({b.x1 - b.x0, b.y1 - b.y0, 4.0 * extent, 0.1});
    b.x0 = std::min(b.x0, std::max(m.x0, b.x0 - reach));
    b.x1 = std::max(b.x1, std::min(m.x1, b.x1 + reach));
    b.y0 = std::min(b.y0, std::max(m.y0, b.y0 - reach));
    b.y1 = std::max(b.y1, std::min(m.y1, b.y1 + reach));
  } else if (m.x0 <= m.x1) {
    b = m;
  }
  if (!(b.x0 <= b.x1)) b = Bounds{-1.0, 1.0, 0.0, 1.0};  // nothing finite: any view
  // The ground and a band of it below y = 0 are always in view; the view is
  // at least four body sizes across.
  b.y0 = std::min(b.y0, 0.0);
  const double min_span = std::max(4.0 * extent, 0.1);
  if (b.x1 - b.x0 < min_span) {
    const double c = 0.5 * (b.x0 + b.x1);
    b.x0 = c - 0.5 * min_span;
    b.x1 = c + 0.5 * min_span;
  }
  if (b.y1 - b.y0 < min_span) b.y1 = b.y0 + min_span;
  b.y0 -= 0.06 * std::max(b.x1 - b.x0, b.y1 - b.y0);

  const double area_w = width - 2.0 * kMarginPx;
  const double area_h = height - kComparisonHudHeight - 2.0 * kMarginPx;
  Camera cam;
  cam.scale = std::min(area_w / (b.x1 - b.x0), area_h / (b.y1 - b.y0));
  // Centred across; the bounds' bottom (the ground band) one margin above
  // the frame's bottom, so spare height goes to the sky, not the ground.
  const double cx = 0.5 * (b.x0 + b.x1);
  cam.x0 = cx - 0.5 * width / cam.scale;
  cam.x1 = cx + 0.5 * width / cam.scale;
  cam.y0 = b.y0 - kMarginPx / cam.scale;
  cam.y1 = cam.y0 + height / cam.scale;
  return cam;
}

void draw_world(const ComparisonVideoInput& in, const RigidBody& body, const Camera& cam,
                const State& ref, const State& mj, const State* conv) {
  glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const double px = 1.0 / cam.scale;
  draw::rect(cam.x0, cam.y0, cam.x1, 0.0, kGround);
  draw::thick_line(Vec2(cam.x0, -px), Vec2(cam.x1, -px), 2.0 * px, kGroundLine);
  for (const Obstacle& o : in.scene->obstacles) {
    if (o.shape == ObstacleShape::Box) {
      draw::rect(o.a.x(), o.a.y(), o.b.x(), o.b.y(), kObstacle);
      draw::rect_outline(o.a.x(), o.a.y(), o.b.x(), o.b.y(), px, kObstacleEdge);
    } else {
      const double w = std::max(2.0 * o.radius, 2.0 * px);
      draw::thick_line(o.a, o.b, w, kObstacle);
      draw::disc(o.a.x(), o.a.y(), 0.5 * w, 0.5 * w, kObstacle, 16);
      draw::disc(o.b.x(), o.b.y(), 0.5 * w, 0.5 * w, kObstacle, 16);
    }
  }
  // Reference below, the second run's outline over it, the converged line on top.
  draw_body(body, *in.scene, ref, Style::Filled, px);
  draw_body(body, *in.scene, mj, Style::Outlined, px);
  if (conv) draw_body(body, *in.scene, *conv, Style::Thin, px);
}

// Where a trajectory stopped early, as HUD text ("" when it ran to the end).
std::string stopped_text(const Trajectory& t, const std::string& label, double t_now) {
  if (!t.divergence || t.samples.empty() || t_now <= t.samples.back().t) return "";
  return format_text("%s STOPPED AT %.3f s (DIVERGED)", label.c_str(), t.samples.back().t);
}

// Text at scale 2, or smaller so that it fits the frame's width.
void fitted_text(double x, double y, const std::string& s, int width, const Color& c) {
  const double fit = (width - x - 10.0) / std::max(draw::text_width(s, 1.0), 1.0);
  draw::text(x, y, s, std::clamp(fit, 1.0, 2.0), c);
}

void draw_hud(const ComparisonVideoInput& in, double t, double duration, const State& ref,
              const State& mj, const State* conv, int width) {
  draw::rect(0, 0, width, kComparisonHudHeight, kPanel);
  fitted_text(10, 8, in.title, width, kText);
  const std::string& r = in.reference_label;
  const std::string& m = in.second_label;
  std::string line = format_text("t = %.3f / %.3f s", t, duration) + "   distance " + r + "-" + m +
                     " " + distance_text(com_distance(ref, mj));
  if (conv) {
    line += ", " + r + "-converged " + distance_text(com_distance(ref, *conv)) + ", " + m +
            "-converged " + distance_text(com_distance(mj, *conv));
  }
  fitted_text(10, 32, line, width, kText);

  // Legend: a swatch drawn like the body on the world's background, then
  // its name.
  double x = 10.0;
  const double y = 58.0, h = 14.0, w = 28.0;
  const auto entry = [&](Style style, const std::string& name) {
    draw::rect(x, y, x + w, y + h, style == Style::Filled ? kReference : kBackground);
    if (style != Style::Filled) {
      const double line_width = style == Style::Thin ? kThinPx : kOutlinePx;
      const double e = 0.5 * line_width;
      draw::rect_outline(x + e, y + e, x + w - e, y + h - e, line_width,
                         style == Style::Thin ? kConverged : kSecond);
    }
    draw::text(x + w + 8, y + 1, name, 1.5, kText);
    x += w + 8 + draw::text_width(name, 1.5) + 28;
  };
  entry(Style::Filled, r + " (filled)");
  entry(Style::Outlined, m + " (outline)");
  if (in.converged) entry(Style::Thin, "converged (thin line)");
  std::string warning = stopped_text(*in.reference, r, t);
  if (warning.empty()) warning = stopped_text(*in.second, m, t);
  if (warning.empty() && in.converged && t > in.converged->t_end())
    warning = format_text("CONVERGED ENDS AT %.3f s", in.converged->t_end());
  if (!warning.empty()) draw::text(x, y + 1, warning, 1.5, kWarning);
}

void draw_comparison_frame(const ComparisonVideoInput& in, const RigidBody& body, const Camera& cam,
                           double t, double duration, int width, int height) {
  const State ref = state_at(*in.reference, t);
  const State mj = state_at(*in.second, t);
  State conv_state;
  const State* conv = nullptr;
  if (in.converged && t <= in.converged->t_end()) {
    conv_state = in.converged->at(t);
    conv = &conv_state;
  }
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(cam.x0, cam.x1, cam.y0, cam.y1, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  draw_world(in, body, cam, ref, mj, conv);
  draw::flush_shapes();

  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0.0, width, height, 0.0, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  draw_hud(in, t, duration, ref, mj, conv, width);
  glDisable(GL_BLEND);
  draw::flush_shapes();
  draw::flush_text();
}

}  // namespace

long long comparison_video_frames(double duration, int fps) {
  return std::max(1LL, std::llround(duration * fps));
}

void check_video_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".mp4" && ext != ".gif") {
    throw InputError("--video " + path + ": must end in .mp4 or .gif (the extension chooses " +
                     "the format)");
  }
}

void write_comparison_video(const std::string& path, const ComparisonVideoInput& in, int fps,
                            int width, int height, OffscreenBackend backend) {
  const std::unique_ptr<AtomicFile> video =
      render_comparison_video(path, in, fps, width, height, backend);
  try {
    video->commit();
  } catch (const InputError& e) {
    throw InputError(std::string("--video ") + e.what());
  }
}

std::unique_ptr<AtomicFile> render_comparison_video(const std::string& path,
                                                    const ComparisonVideoInput& in, int fps,
                                                    int width, int height,
                                                    OffscreenBackend backend) {
  check_video_path(path);
  if (!in.scene || !in.reference || !in.second)
    throw InputError("--video " + path + ": needs a scene, a reference and a second trajectory");
  if (in.reference->samples.empty() || in.second->samples.empty())
    throw InputError("--video " + path + ": a trajectory has no samples");
  if (fps < 1 || fps > 240)
    throw InputError("--video " + path + ": fps " + std::to_string(fps) + " must be in [1, 240]");
  if (width < 64 || height < 64 || width > 4096 || height > 4096 || width % 2 || height % 2) {
    throw InputError("--video " + path + ": size " + std::to_string(width) + "x" +
                     std::to_string(height) + " must be even and in [64, 4096] (yuv420p)");
  }
  const double duration = in.scene->sim.duration;
  const long long frames = comparison_video_frames(duration, fps);
  const RigidBody body = make_body(*in.scene);

  const OffscreenContext context(width, height, backend, "--video");
  const int w = context.width(), h = context.height();
  const Camera cam = fit_camera(in, body, frames, fps, w, h);
  const VideoFormat format = lower_extension(path) == ".gif" ? VideoFormat::Gif : VideoFormat::Mp4;
  VideoWriter video(path, w, h, fps, format, "--video");
  std::vector<unsigned char> pixels;
  for (long long i = 0; i < frames; ++i) {
    const double t = static_cast<double>(i) / fps;
    draw_comparison_frame(in, body, cam, t, duration, w, h);
    context.read_pixels(pixels);
    if (!video.write(pixels)) break;  // ffmpeg is gone; finish() says why
  }
  return video.finish_uncommitted();
}

}  // namespace contact2d::game
