// Closed forms at rest (benchmarks/rest.hpp).
#include "benchmarks/rest.hpp"

namespace contact2d::benchmarks {

double rest_depth(double mass, double gravity, double stiffness, int contacts) {
  return mass * gravity / (contacts * stiffness);  // N·k·d = m·g
}

double soft_constraint_rest_depth(double mass, double gravity, double inv_weight, double impedance,
                                  int contacts, double stiffness) {
  return mass * gravity * inv_weight * (1.0 - impedance) / (contacts * stiffness);  // f·Â·(1−d)/s
}

}  // namespace contact2d::benchmarks
