// Closed forms of a block on a slope (benchmarks/slope.hpp).
#include "benchmarks/slope.hpp"

#include <cmath>

namespace contact2d::benchmarks {

double slope_rest_depth(double mass, double gravity, double theta, double stiffness, int contacts) {
  return mass * gravity * std::cos(theta) / (contacts * stiffness);  // N·k·d = m·g·cosθ
}

double slope_sliding_acceleration(double gravity, double theta, double mu) {
  return gravity * (std::sin(theta) - mu * std::cos(theta));
}

double tanh_creep_speed(double theta, double mu, double alpha) {
  return std::atanh(std::tan(theta) / mu) / alpha;  // μ·cosθ·tanh(αv) = sinθ
}

double soft_constraint_creep_speed(double mass, double gravity, double theta, int contacts,
                                   double impratio, double damping, double impedance) {
  // N rows of impratio·c·v/(1 − d) against m·g·sinθ
  return (1.0 - impedance) * mass * gravity * std::sin(theta) / (contacts * impratio * damping);
}

}  // namespace contact2d::benchmarks
