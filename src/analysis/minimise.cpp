#include "analysis/minimise.hpp"

#include <nlopt.h>

#include <memory>
#include <stdexcept>
#include <string>

namespace contact2d::analysis {

namespace {

struct Objective {
  const std::function<double(const std::vector<double>&)>* f = nullptr;
  int evaluations = 0;
  std::vector<double> x;  // reused: no allocation per call
};

double call(unsigned dim, const double* xs, double* /*gradient*/, void* data) {
  auto* o = static_cast<Objective*>(data);
  ++o->evaluations;
  o->x.assign(xs, xs + dim);
  return (*o->f)(o->x);
}

}  // namespace

Minimised minimise(const std::function<double(const std::vector<double>&)>& f,
                   std::vector<double> x, const std::vector<double>& lo,
                   const std::vector<double>& hi, const std::vector<double>& step,
                   int max_evaluations) {
  Objective objective{&f, 0, {}};
  const unsigned n = static_cast<unsigned>(x.size());
  const std::unique_ptr<nlopt_opt_s, void (*)(nlopt_opt)> opt(nlopt_create(NLOPT_LN_BOBYQA, n),
                                                              nlopt_destroy);
  if (!opt) throw std::runtime_error("fit: NLopt could not create its BOBYQA optimiser");
  nlopt_set_lower_bounds(opt.get(), lo.data());
  nlopt_set_upper_bounds(opt.get(), hi.data());
  nlopt_set_initial_step(opt.get(), step.data());
  nlopt_set_xtol_rel(opt.get(), 1e-4);
  nlopt_set_ftol_abs(opt.get(), 1e-6);
  nlopt_set_maxeval(opt.get(), max_evaluations);
  nlopt_set_min_objective(opt.get(), call, &objective);
  double value = 0.0;
  const nlopt_result result = nlopt_optimize(opt.get(), x.data(), &value);
  if (result < 0 && result != NLOPT_ROUNDOFF_LIMITED)
    throw std::runtime_error("fit: NLopt's BOBYQA failed (code " + std::to_string(result) + ")");
  return {x, value, objective.evaluations};
}

}  // namespace contact2d::analysis
