#include "core/ellipse.hpp"

#include <cmath>

namespace contact2d {

Vec2 ellipse_lowest_point(double a, double b, double theta) {
  const double s = std::sin(theta);
  const double c = std::cos(theta);
  const double h = std::sqrt(a * a * s * s + b * b * c * c);
  return {-(a * a - b * b) * s * c / h, -h};
}

double ellipse_lowest_point_turn_rate(double a, double b, double theta) {
  const double s = std::sin(theta);
  const double c = std::cos(theta);
  const double h = std::sqrt(a * a * s * s + b * b * c * c);
  const double rx = -(a * a - b * b) * s * c / h;
  return -(a * a - b * b) * (c * c - s * s) / h + rx * rx / h;
}

namespace {

// World point of the rim at parameter φ, and f(φ) = sd(e(φ)).
struct Rim {
  const Obstacle& obstacle;
  double a, b, ct, st;
  Vec2 p;
  Vec2 point(double phi) const {
    const double ex = a * std::cos(phi);
    const double ey = b * std::sin(phi);
    return {p.x() + ct * ex - st * ey, p.y() + st * ex + ct * ey};
  }
  double f(double phi) const {
    Vec2 normal;
    return signed_distance(obstacle, point(phi), normal);
  }
};

// Distance from c to the obstacle's bounding shape, a lower bound of the
// distance to the obstacle itself (0 when c is inside it).
double distance_bound(const Obstacle& o, const Vec2& c) {
  Vec2 normal;
  return std::max(0.0, signed_distance(o, c, normal));
}

}  // namespace

bool ellipse_obstacle_contact(const Obstacle& obstacle, double a, double b, const Vec2& p,
                              double ct, double st, ObstacleContact& out) {
  // Every rim point lies within max(a, b) of the centre.
  if (distance_bound(obstacle, p) >= std::max(a, b)) return false;
  const Rim rim{obstacle, a, b, ct, st, p};
  constexpr double kTwoPi = 6.283185307179586;
  constexpr double kStep = kTwoPi / kRimSamples;
  int best = 0;
  double best_f = rim.f(0.0);
  for (int i = 1; i < kRimSamples; ++i) {
    const double value = rim.f(i * kStep);
    if (value < best_f) {
      best_f = value;
      best = i;
    }
  }
  // Golden section on [φ_best − step, φ_best + step].
  constexpr double kInvPhi = 0.6180339887498949;  // (√5 − 1)/2
  double lo = (best - 1) * kStep;
  double hi = (best + 1) * kStep;
  double x1 = hi - kInvPhi * (hi - lo);
  double x2 = lo + kInvPhi * (hi - lo);
  double f1 = rim.f(x1);
  double f2 = rim.f(x2);
  while (hi - lo > 1e-12) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = rim.f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = rim.f(x2);
    }
  }
  double phi = 0.5 * (lo + hi);
  const Vec2 c = rim.point(phi);
  Vec2 normal;
  double depth = -signed_distance(obstacle, c, normal);
  if (-best_f > depth) {  // the search's point no deeper than the best sample: keep the sample
    phi = best * kStep;
    const Vec2 c_best = rim.point(phi);
    depth = -signed_distance(obstacle, c_best, normal);
    out.r = c_best - p;
  } else {
    out.r = c - p;
  }
  if (!(depth > 0.0)) return false;
  out.depth = depth;
  out.normal = normal;
  return true;
}

double ellipse_plate_inertia(double mass, double a, double b) {
  return 0.25 * mass * (a * a + b * b);
}

}  // namespace contact2d
