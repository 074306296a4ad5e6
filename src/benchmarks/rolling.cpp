// Closed forms of rolling (benchmarks/rolling.hpp).
#include "benchmarks/rolling.hpp"

#include <cmath>

namespace contact2d::benchmarks {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double rolling_resistance_deceleration(double mu_roll, double gravity, double radius,
                                       double kappa) {
  return mu_roll * gravity / (radius * (1.0 + kappa));  // μ_roll·g/(R·(1 + κ))
}

RollingStop rolling_distance_terms(double v0, double deceleration, double mu, double gravity,
                                   double alpha, double kappa) {
  const double a = deceleration;
  const double slip = std::atanh(a / (mu * gravity)) / alpha;  // v_s: μg·tanh(α·v_s) = a
  RollingStop out;
  out.roll = rolling_resistance_distance(v0, a);
  out.slip = slip * v0 * kappa / ((1.0 + kappa) * a);
  out.tanh = kPi * kPi / (12.0 * alpha * alpha * a);
  return out;
}

double rolling_distance(double v0, double deceleration, double mu, double gravity, double alpha,
                        double kappa) {
  return rolling_distance_terms(v0, deceleration, mu, gravity, alpha, kappa).distance();
}

double rolling_resistance_distance(double v0, double deceleration) {
  return v0 * v0 / (2.0 * deceleration);  // v0²/(2a)
}

double slide_to_roll_final_speed(double v0, double rim0, double kappa) {
  return (v0 - kappa * rim0) / (1.0 + kappa);  // L = κ·R·ω − v conserved, ω·R = −v at the end
}

double slide_to_roll_speed(double v0, double u0, double u, double kappa) {
  return v0 - (u0 - u) * kappa / (1.0 + kappa);
}

double slide_to_roll_spin(double omega0, double u0, double u, double radius, double kappa) {
  return omega0 - (u0 - u) / ((1.0 + kappa) * radius);
}

double slide_to_roll_slip_deceleration(double mu, double gravity, double kappa) {
  return (1.0 + 1.0 / kappa) * mu * gravity;
}

double slide_to_roll_distance_offset(double u0, double mu, double gravity, double alpha,
                                     double kappa) {
  // κ/(1 + κ)·(1/a_u) = 1/(((1 + κ)/κ)·(1 + 1/κ)·μ·g): 9μg for the disc.
  const double factor = (1.0 + kappa) / kappa * (1.0 + 1.0 / kappa);
  return (0.5 * u0 * u0 + kPi * kPi / (12.0 * alpha * alpha)) / (factor * mu * gravity);
}

SpinImpact spin_impact(double vx, double rim, double normal_impulse, double mass, double mu,
                       double kappa) {
  const double u = vx + rim;
  SpinImpact out;
  out.rolls = u <= (1.0 + 1.0 / kappa) * mu * normal_impulse / mass;  // μ·P stops the slip
  if (out.rolls) {
    out.vx = vx - u * kappa / (1.0 + kappa);
    out.rim = rim - u / (1.0 + kappa);
  } else {
    out.vx = vx - mu * normal_impulse / mass;
    out.rim = rim - mu * normal_impulse / (kappa * mass);
  }
  return out;
}

}  // namespace contact2d::benchmarks
