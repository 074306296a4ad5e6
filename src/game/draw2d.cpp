#include "game/draw2d.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <stb_easy_font.h>

namespace contact2d::game::draw {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Every shape of a frame goes into one triangle list with a colour per
// vertex and is drawn with a single glDrawArrays per projection: llvmpipe
// (Mesa's software renderer) pays ~40 µs per draw call, so ~100 small
// glBegin/glEnd shapes cost more than the pixels (measured: 3.8 ms a frame
// for the pitch drawn shape by shape).
struct Batch {
  std::vector<float> v;  // x, y, r, g, b, a per vertex
  void vertex(double x, double y, const Color& c) {
    v.insert(v.end(), {static_cast<float>(x), static_cast<float>(y), c.r, c.g, c.b, c.a});
  }
  void triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& col) {
    vertex(a.x(), a.y(), col);
    vertex(b.x(), b.y(), col);
    vertex(c.x(), c.y(), col);
  }
  void quad(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, const Color& col) {
    triangle(a, b, c, col);
    triangle(a, c, d, col);
  }
  void flush() {
    if (v.empty()) return;
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, 6 * sizeof(float), v.data());
    glColorPointer(4, GL_FLOAT, 6 * sizeof(float), v.data() + 2);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size() / 6));
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    v.clear();
  }
};

Batch g_batch;  // reused: no allocation once it has grown

// Text. stb_easy_font draws a glyph as ~8 small rectangles; llvmpipe pays
// both per triangle and per pixel, so the glyphs are drawn once into an
// alpha texture and each character becomes one textured quad the size of
// its own bounding box (at most 7 × 9 px at scale 1), alpha-tested, without
// blending. Measured with the help overlay (~700 characters): rectangles cost
// ~5 ms a frame, quads over whole 16 px cells three times that (fill), tight
// quads the least.
constexpr int kCellW = 8, kCellH = 10, kAtlasColumns = 16;
constexpr int kAtlasWidth = kCellW * kAtlasColumns, kAtlasHeight = kCellH * 6;

struct TextBatch {
  std::vector<float> v;  // x, y, u, v, r, g, b, a per vertex
  GLuint texture = 0;
  std::vector<unsigned char> alpha;    // the atlas, once rasterised
  int box_w[95] = {}, box_h[95] = {};  // each glyph's extent from its origin, px

  // Glyph rectangles from stb_easy_font, rasterised on the CPU once (they
  // are axis-aligned with integer corners). Needs no GL context.
  void rasterise() {
    if (!alpha.empty()) return;
    alpha.assign(static_cast<size_t>(kAtlasWidth) * kAtlasHeight, 0);
    static char quads[4096];
    for (int c = 32; c < 127; ++c) {
      char one[2] = {static_cast<char>(c), 0};
      const int n = stb_easy_font_print(0.0f, 0.0f, one, nullptr, quads, sizeof quads);
      const int cx = ((c - 32) % kAtlasColumns) * kCellW, cy = ((c - 32) / kAtlasColumns) * kCellH;
      for (int q = 0; q < n; ++q) {
        float p0[2], p2[2];  // corners 0 and 2 of the rectangle
        std::memcpy(p0, quads + 64L * q, sizeof p0);
        std::memcpy(p2, quads + 64L * q + 32, sizeof p2);
        const int x0 = static_cast<int>(p0[0]), y0 = static_cast<int>(p0[1]);
        const int x1 = std::min(static_cast<int>(p2[0]), kCellW),
                  y1 = std::min(static_cast<int>(p2[1]), kCellH);
        box_w[c - 32] = std::max(box_w[c - 32], x1);
        box_h[c - 32] = std::max(box_h[c - 32], y1);
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x)
            alpha[static_cast<size_t>(cy + y) * kAtlasWidth + static_cast<size_t>(cx + x)] = 255;
        }
      }
    }
  }

  void glyph(double x, double y, int c, double scale, const Color& col) {
    rasterise();
    const int w = box_w[c - 32], h = box_h[c - 32];
    if (w == 0 || h == 0) return;
    const int cx = ((c - 32) % kAtlasColumns) * kCellW, cy = ((c - 32) / kAtlasColumns) * kCellH;
    const float u0 = static_cast<float>(cx) / kAtlasWidth,
                u1 = static_cast<float>(cx + w) / kAtlasWidth;
    const float v0 = static_cast<float>(cy) / kAtlasHeight,
                v1 = static_cast<float>(cy + h) / kAtlasHeight;
    const float x0 = static_cast<float>(x), y0 = static_cast<float>(y);
    const float x1 = static_cast<float>(x + scale * w), y1 = static_cast<float>(y + scale * h);
    const float corners[6][4] = {{x0, y0, u0, v0}, {x1, y0, u1, v0}, {x1, y1, u1, v1},
                                 {x0, y0, u0, v0}, {x1, y1, u1, v1}, {x0, y1, u0, v1}};
    for (const auto& k : corners)
      v.insert(v.end(), {k[0], k[1], k[2], k[3], col.r, col.g, col.b, col.a});
  }

  void flush() {
    if (!texture) {
      rasterise();
      glGenTextures(1, &texture);
      glBindTexture(GL_TEXTURE_2D, texture);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_ALPHA, kAtlasWidth, kAtlasHeight, 0, GL_ALPHA,
                   GL_UNSIGNED_BYTE, alpha.data());
    }
    if (v.empty()) return;
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, 8 * sizeof(float), v.data());
    glTexCoordPointer(2, GL_FLOAT, 8 * sizeof(float), v.data() + 2);
    glColorPointer(4, GL_FLOAT, 8 * sizeof(float), v.data() + 4);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size() / 8));
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisable(GL_ALPHA_TEST);
    glDisable(GL_TEXTURE_2D);
    v.clear();
  }
};

TextBatch g_text;

}  // namespace

void triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& col) {
  g_batch.triangle(a, b, c, col);
}

void quad(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, const Color& col) {
  g_batch.quad(a, b, c, d, col);
}

void rect(double x0, double y0, double x1, double y1, const Color& c) {
  g_batch.quad(Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1), c);
}

void thick_line(const Vec2& a, const Vec2& b, double width, const Color& c) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len <= 0.0) return;
  const Vec2 n = Vec2(-d.y(), d.x()) * (0.5 * width / len);
  g_batch.quad(a + n, b + n, b - n, a - n, c);
}

void rect_outline(double x0, double y0, double x1, double y1, double width, const Color& c) {
  thick_line(Vec2(x0, y0), Vec2(x1, y0), width, c);
  thick_line(Vec2(x1, y0), Vec2(x1, y1), width, c);
  thick_line(Vec2(x1, y1), Vec2(x0, y1), width, c);
  thick_line(Vec2(x0, y1), Vec2(x0, y0), width, c);
}

void disc(double x, double y, double rx, double ry, const Color& c, int segments) {
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2.0 * kPi * i / segments, a1 = 2.0 * kPi * (i + 1) / segments;
    g_batch.triangle(Vec2(x, y), Vec2(x + rx * std::cos(a0), y + ry * std::sin(a0)),
                     Vec2(x + rx * std::cos(a1), y + ry * std::sin(a1)), c);
  }
}

void ring(double x, double y, double r, double width, const Color& c, int segments) {
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2.0 * kPi * i / segments, a1 = 2.0 * kPi * (i + 1) / segments;
    const Vec2 u0(std::cos(a0), std::sin(a0)), u1(std::cos(a1), std::sin(a1)), p(x, y);
    g_batch.quad(p + (r - width) * u0, p + r * u0, p + r * u1, p + (r - width) * u1, c);
  }
}

void arrow(const Vec2& from, const Vec2& to, double width, const Color& c) {
  const Vec2 d = to - from;
  const double len = d.norm();
  if (len < 1e-9) return;
  const Vec2 u = d / len;
  const Vec2 n(-u.y(), u.x());
  const double head = std::min(0.4 * len + 2.0 * width, 4.0 * width);
  const Vec2 base = to - head * u;
  thick_line(from, base, width, c);
  g_batch.triangle(to, base + 0.75 * head * n, base - 0.75 * head * n, c);
}

void polygon_outline(const std::vector<Vec2>& corners, double width, const Color& c) {
  const size_t n = corners.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = corners[i];
    const Vec2& b = corners[(i + 1) % n];
    const Vec2 d = b - a;
    const double len = d.norm();
    if (len <= 0.0) continue;
    const Vec2 e = d * (0.5 * width / len);
    thick_line(a - e, b + e, width, c);
  }
}

void convex_polygon(const std::vector<Vec2>& corners, const Color& c) {
  for (size_t i = 1; i + 1 < corners.size(); ++i)
    g_batch.triangle(corners[0], corners[i], corners[i + 1], c);
}

void flush_shapes() { g_batch.flush(); }

void text(double x, double y, const std::string& s, double scale, const Color& c) {
  double pen = 0.0;
  for (const char ch : s) {
    const int code = static_cast<unsigned char>(ch);
    if (code < 32 || code > 126) continue;
    if (code != ' ') g_text.glyph(x + scale * pen, y, code, scale, c);
    char one[2] = {ch, 0};
    pen += stb_easy_font_width(one);
  }
}

double text_width(const std::string& s, double scale) {
  return scale * stb_easy_font_width(const_cast<char*>(s.c_str()));
}

void flush_text() { g_text.flush(); }

void forget_gl_objects() { g_text.texture = 0; }

}  // namespace contact2d::game::draw
