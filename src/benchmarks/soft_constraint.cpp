// Closed forms of the soft-constraint law (benchmarks/soft_constraint.hpp).
#include "benchmarks/soft_constraint.hpp"

#include <cmath>

namespace contact2d::benchmarks {

double soft_constraint_force(double inv_mass, double inv_weight, double impedance, double aref,
                             double a0) {
  const double d = impedance;
  return d * (aref - a0) / (d * inv_mass + (1.0 - d) * inv_weight);
}

ConeForce elliptic_cone_force(double stiffness, double depth, double damping, double vn, double vt,
                              double mu, double impratio) {
  ConeForce out;
  const double inside_ft = -impratio * damping * vt;
  const double inside_fn = stiffness * depth - damping * vn;
  out.normal = inside_fn;
  out.tangential = inside_ft;
  if (std::abs(inside_ft) > mu * inside_fn) {  // on the cone
    out.normal =
        (stiffness * depth - damping * vn + mu * damping * std::abs(vt)) / (1 + mu * mu / impratio);
    out.tangential = -mu * out.normal * (vt > 0 ? 1 : -1);
  }
  return out;
}

}  // namespace contact2d::benchmarks
