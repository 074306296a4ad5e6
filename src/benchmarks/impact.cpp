// Closed forms of one impact (benchmarks/impact.hpp).
#include "benchmarks/impact.hpp"

#include <cmath>
#include <limits>

namespace contact2d::benchmarks {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The Kelvin–Voigt oscillator in units of 1/ω: the time its force first
// returns to zero and the speed x'(τ) then (negative: leaving).
struct KelvinVoigtExit {
  double time = 0.0;
  double speed = 0.0;
};
KelvinVoigtExit kelvin_voigt_exit(double zeta) {
  if (zeta == 1.0) return {2.0, -std::exp(-2.0)};  // x = t·e^(−t), force (2 − t)·e^(−t)
  if (zeta < 1.0) {
    const double wd = std::sqrt(1.0 - zeta * zeta);
    const double theta = std::atan2(2.0 * zeta * wd, 1.0 - 2.0 * zeta * zeta);
    const double tc = (kPi - theta) / wd;  // first zero of the force after t = 0
    return {tc, std::exp(-zeta * tc) * (std::cos(wd * tc) - zeta / wd * std::sin(wd * tc))};
  }
  const double s = std::sqrt(zeta * zeta - 1.0);
  const double l1 = -zeta + s, l2 = -zeta - s;
  const double a1 = 1.0 + 2.0 * zeta * l1, a2 = 1.0 + 2.0 * zeta * l2;  // the force's weights
  const double tc = std::log(a2 / a1) / (l1 - l2);
  return {tc, (l1 * std::exp(l1 * tc) - l2 * std::exp(l2 * tc)) / (l1 - l2)};
}

}  // namespace

double compression_restitution(double zeta) {
  if (!(zeta >= 0.0 && zeta < 1.0)) return kNaN;
  const double s = std::sqrt(1.0 - zeta * zeta);  // ω_d
  return std::exp(-zeta * std::atan(s / zeta) / s);
}

double compression_contact_time(double zeta) {
  if (!(zeta >= 0.0 && zeta < 1.0)) return kNaN;
  const double s = std::sqrt(1.0 - zeta * zeta);
  return std::atan(s / zeta) / s + 0.5 * kPi;  // in, φ/ω_d; out, a quarter period
}

double kelvin_voigt_restitution(double zeta) {
  if (!(zeta >= 0.0)) return kNaN;
  return -kelvin_voigt_exit(zeta).speed;
}

double kelvin_voigt_contact_time(double zeta) {
  if (!(zeta >= 0.0)) return kNaN;
  return kelvin_voigt_exit(zeta).time;
}

double dashpot_restitution(double zeta) {
  if (!(zeta >= 0.0 && zeta < 1.0)) return kNaN;
  return std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta));
}

double impact_normal_impulse(double mass, double restitution, double v_in) {
  return mass * (1.0 + restitution) * v_in;
}

}  // namespace contact2d::benchmarks
