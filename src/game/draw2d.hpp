// The drawing primitives of the game's renderer (render.cpp), shared with
// the comparison video (comparison_video.cpp): shapes go into one triangle
// list with a colour per vertex and are drawn with a single glDrawArrays per
// flush; text (stb_easy_font's glyphs, rasterised once into an alpha
// texture) goes into one textured-quad list. Coordinates are those of the
// current projection; needs a current GL context (OpenGL 1.x/2.x fixed
// function).
#pragma once

#include <string>
#include <vector>

#include "core/body.hpp"

namespace contact2d::game::draw {

struct Color {
  float r, g, b, a;
};

void triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& col);
void quad(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, const Color& col);
void rect(double x0, double y0, double x1, double y1, const Color& c);
// A thick line as a quad (width in the projection's units).
void thick_line(const Vec2& a, const Vec2& b, double width, const Color& c);
void rect_outline(double x0, double y0, double x1, double y1, double width, const Color& c);
// A closed polygon's outline, `width` wide, centred on the edges, with
// square joints (each edge extended by half the width at both ends).
void polygon_outline(const std::vector<Vec2>& corners, double width, const Color& c);
// A convex polygon, filled (a fan from its first corner).
void convex_polygon(const std::vector<Vec2>& corners, const Color& c);
void disc(double x, double y, double rx, double ry, const Color& c, int segments = 32);
void ring(double x, double y, double r, double width, const Color& c, int segments = 32);
void arrow(const Vec2& from, const Vec2& to, double width, const Color& c);
// Draws and empties the shape list.
void flush_shapes();

// Text in the projection's units (pixels, y down), scaled; glyphs are ~7
// units high at scale 1. Drawn at the next flush_text().
void text(double x, double y, const std::string& s, double scale, const Color& c);
double text_width(const std::string& s, double scale);
void flush_text();

// A new GL context is current: the text atlas (a texture of the previous
// context) is uploaded again at the next flush_text(). Call after making a
// fresh context current when an earlier one may have drawn text.
void forget_gl_objects();

}  // namespace contact2d::game::draw
