// Small helpers for the analytic tests: build scenes in code and step them.
#pragma once

#include <cmath>

#include "core/integrators.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"

namespace contact2d::test {

// Steps a model n times from s with the core's step() (no divergence rule,
// so a test can watch an unstable method grow).
inline State advance(const Model& model, Integrator integrator, double dt, State s, long long n) {
  StepWorkspace ws(model);
  find_contacts(model, s.q, ws.contacts);
  for (long long i = 0; i < n; ++i) step(model, integrator, dt, s, ws);
  return s;
}

// Least-squares slope of log(err) against log(h).
template <typename Hs, typename Errs>
double log_log_slope(const Hs& hs, const Errs& errs) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(std::size(hs));
  for (size_t i = 0; i < std::size(hs); ++i) {
    const double x = std::log(hs[i]);
    const double y = std::log(errs[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace contact2d::test
