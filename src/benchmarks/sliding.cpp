// Closed forms of sliding to rest (benchmarks/sliding.hpp).
#include "benchmarks/sliding.hpp"

#include <cmath>

namespace contact2d::benchmarks {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double coulomb_sliding_distance(double v0, double mu, double gravity) {
  return v0 * v0 / (2.0 * mu * gravity);  // v0²/(2μg)
}

double coulomb_sliding_time(double v0, double mu, double gravity) {
  return v0 / (mu * gravity);  // v0/(μg)
}

double tanh_sliding_distance_excess(double mu, double gravity, double alpha) {
  return kPi * kPi / (12.0 * alpha * alpha * mu * gravity);  // π²/(12α²μg)
}

double tanh_sliding_distance(double v0, double mu, double gravity, double alpha) {
  return coulomb_sliding_distance(v0, mu, gravity) +
         tanh_sliding_distance_excess(mu, gravity, alpha);
}

double tanh_sliding_speed(double v0, double deceleration, double alpha, double t) {
  const double a = alpha * v0;
  // ln sinh(a) = a + ln(1 − e^(−2a)) − ln 2, finite for every a > 0.
  const double log_sinh = a + std::log1p(-std::exp(-2.0 * a)) - std::log(2.0);
  const double log_rhs = log_sinh - deceleration * alpha * t;  // ln(sinh(αv0)·e^(−aαt))
  return std::asinh(std::exp(log_rhs)) / alpha;
}

double tanh_sliding_time(double v0, double v, double deceleration, double alpha) {
  return std::log(std::sinh(alpha * v0) / std::sinh(alpha * v)) / (deceleration * alpha);
}

double box_pitch_distance(double mass, double mu, double gravity, double width, double height,
                          double stiffness) {
  // −(h·β/2)·(π²/8 − ½) with β = μ·m·g·h/(k·w²)
  return -mass * mu * gravity * height * height * (kPi * kPi / 8.0 - 0.5) /
         (2.0 * stiffness * width * width);
}

BoxSlide box_sliding_distance(double v0, double mu, double gravity, double alpha, double mass,
                              double width, double height, double stiffness) {
  BoxSlide out;
  out.coulomb = coulomb_sliding_distance(v0, mu, gravity);
  out.tanh = tanh_sliding_distance_excess(mu, gravity, alpha);
  out.pitch = box_pitch_distance(mass, mu, gravity, width, height, stiffness);
  return out;
}

}  // namespace contact2d::benchmarks
