// The tanh perturbation study, shared by bench/tanh_perturbation.cpp (which
// prints it for docs/speed.md) and tests/core/test_tanh_trajectories.cpp
// (which asserts the vector and the bounded paths stay within it): one scene run on one tanh
// path (core/vector_math.hpp), and the largest distance between two runs.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/run.hpp"
#include "core/vector_math.hpp"

namespace contact2d::study {

// Every step's state of the reference on `scene` with tanh on `path`.
inline std::vector<State> run_on_path(const Scene& scene, TanhPath path) {
  const TanhPath before = set_tanh_path(path);
  ReferenceStepper stepper(scene);
  std::vector<State> states;
  const long long steps = step_count(scene.sim);
  states.reserve(static_cast<size_t>(steps));
  for (long long i = 0; i < steps; ++i) {
    if (stepper.step() != StepStatus::Ok) break;
    states.push_back(stepper.state());
  }
  set_tanh_path(before);
  return states;
}

struct Distance {
  double position = 0.0;  // max over steps of |Δ(x, y)|, m
  double angle = 0.0;     // max over steps of |Δθ|, rad
  bool same_length = true;
};

inline Distance distance(const std::vector<State>& a, const std::vector<State>& b) {
  Distance d;
  d.same_length = a.size() == b.size();
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i) {
    d.position = std::max(d.position, std::hypot(a[i].q.x() - b[i].q.x(), a[i].q.y() - b[i].q.y()));
    d.angle = std::max(d.angle, std::abs(a[i].q.z() - b[i].q.z()));
  }
  return d;
}

// How far one ulp of tanh moves the scene: the largest distance from the
// unperturbed scalar run of the runs with every tanh one ulp up, one ulp
// down, and up or down at random value by value (kRandomSeeds seeds); and
// the vector and the bounded paths' distances from the same scalar run.
constexpr int kRandomSeeds = 8;

struct Perturbation {
  Distance ulp;      // max over the perturbed runs vs scalar
  Distance vector;   // vector vs scalar
  Distance bounded;  // bounded (contact2d's own tanh) vs scalar
};

inline void widen(Distance& to, const Distance& d) {
  to.position = std::max(to.position, d.position);
  to.angle = std::max(to.angle, d.angle);
  to.same_length = to.same_length && d.same_length;
}

inline Perturbation perturbation(const Scene& scene) {
  const std::vector<State> scalar = run_on_path(scene, TanhPath::Scalar);
  Perturbation p;
  widen(p.ulp, distance(scalar, run_on_path(scene, TanhPath::ScalarUlpUp)));
  widen(p.ulp, distance(scalar, run_on_path(scene, TanhPath::ScalarUlpDown)));
  for (int seed = 1; seed <= kRandomSeeds; ++seed) {
    set_tanh_perturbation_seed(static_cast<unsigned long long>(seed));
    widen(p.ulp, distance(scalar, run_on_path(scene, TanhPath::ScalarUlpRandom)));
  }
  p.vector = distance(scalar, run_on_path(scene, TanhPath::Vector));
  p.bounded = distance(scalar, run_on_path(scene, TanhPath::Bounded));
  return p;
}

}  // namespace contact2d::study
