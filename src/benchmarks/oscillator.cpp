// Closed forms of the spring–damper under gravity (benchmarks/oscillator.hpp).
#include "benchmarks/oscillator.hpp"

#include <cmath>
#include <limits>

namespace contact2d::benchmarks {

OscillatorState damped_oscillator(double gravity, double stiffness, double damping, double z0,
                                  double w0, double s) {
  OscillatorState out;
  if (stiffness == 0.0 && damping == 0.0) {  // flight
    out.z = z0 + w0 * s - 0.5 * gravity * s * s;
    out.w = w0 - gravity * s;
    return out;
  }
  const double beta = 0.5 * damping;
  if (!(beta * beta < stiffness)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
  }
  const double z_eq = -gravity / stiffness;
  const double wd = std::sqrt(stiffness - beta * beta);  // ω_d
  const double u0 = z0 - z_eq;
  const double e = std::exp(-beta * s);
  const double cs = std::cos(wd * s), sn = std::sin(wd * s);
  out.z = z_eq + e * (u0 * cs + (w0 + beta * u0) / wd * sn);
  out.w = e * (w0 * cs - (stiffness * u0 + beta * w0) / wd * sn);
  return out;
}

double fall_time(double gravity, double z, double w) {
  return (w + std::sqrt(w * w + 2.0 * gravity * z)) / gravity;
}

double drop_depth(double mass, double gravity, double stiffness, double height) {
  const double mg = mass * gravity;
  return (mg + std::sqrt(mg * mg + 2.0 * stiffness * mg * height)) / stiffness;
}

double bouncing_height(double gravity, double stiffness, double z0, double t) {
  const double t1 = std::sqrt(2.0 * z0 / gravity);
  const double v1 = -gravity * t1;
  const double omega = std::sqrt(stiffness);
  const double a = gravity / stiffness, b = v1 / omega;
  const double phi = std::atan2(b, a);
  const double tc = (2.0 * M_PI + 2.0 * phi) / omega;
  double s = std::fmod(t, 2.0 * t1 + tc);  // time since the last apex
  if (s <= t1) return z0 - 0.5 * gravity * s * s;
  s -= t1;
  if (s <= tc) return -a + a * std::cos(omega * s) + b * std::sin(omega * s);
  s -= tc;  // rising flight from the ground at +|v1|
  return -v1 * s - 0.5 * gravity * s * s;
}

}  // namespace contact2d::benchmarks
