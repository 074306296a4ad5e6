// Derivative-free minimisation for the fits against real data
// (analysis/real_impacts.hpp): NLopt's BOBYQA (Powell's bound-constrained
// quadratic-model trust region), which needs no gradient — the objectives
// are medians of replayed impacts, piecewise smooth at best.
#pragma once

#include <functional>
#include <vector>

namespace contact2d::analysis {

struct Minimised {
  std::vector<double> x;
  double f = 0.0;
  int evaluations = 0;
};

// f minimised over the box [lo, hi] from x, first trust-region steps `step`,
// at most `max_evaluations` calls (stops earlier at a relative change of x
// below 1e-4 or of f below 1e-6). Throws std::runtime_error when NLopt fails.
Minimised minimise(const std::function<double(const std::vector<double>&)>& f,
                   std::vector<double> x, const std::vector<double>& lo,
                   const std::vector<double>& hi, const std::vector<double>& step,
                   int max_evaluations);

}  // namespace contact2d::analysis
