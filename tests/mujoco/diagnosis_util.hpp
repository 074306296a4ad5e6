// compare's three-way numbers and diagnosis on the real engines, for the
// MuJoCo tests that check what the diagnosis names.
#pragma once

#include <string>

#include "analysis/comparison.hpp"
#include "engines/engines.hpp"

namespace contact2d::test {

struct Diagnosed {
  analysis::ThreeWay three;
  analysis::Diagnosis diagnosis;
};

// Both engines on the scene (MuJoCo as `spec`: the default mapping unless
// given), the three-way distances at converged tolerance `tol`, and the
// diagnosis, as `compare` runs them (`full`: as compare --full-diagnosis).
inline Diagnosed diagnosed(const Scene& scene, engines::EngineSpec spec = {}, double tol = 1e-12,
                           bool full = false) {
  spec.kind = "mujoco";
  const engines::EngineRun ref = engines::run_engine("ref", scene);
  const engines::EngineRun mj = engines::run_engine(spec, scene);
  Diagnosed d;
  d.three = analysis::three_way(scene, ref.trajectory, mj.trajectory, tol);
  analysis::DiagnosisOptions how;
  how.full = full;
  d.diagnosis = analysis::diagnose(scene, spec, ref, mj, d.three, analysis::registry_runner(), how);
  return d;
}

// The finding of that cause, named or not; nullptr when it was not re-run.
inline const analysis::Finding* finding(const analysis::Diagnosis& d, const std::string& cause) {
  for (const analysis::Finding& f : d.findings)
    if (f.cause == cause) return &f;
  return nullptr;
}

}  // namespace contact2d::test
