// Both engines and the converged solution against closed forms: the table of
// validation/report/closed_forms.md and the runs that tests/mujoco/test_closed_forms.cpp checks.
// docs/closed-forms.md derives every closed form and every tolerance; the closed forms are
// computed by src/benchmarks/, and this file only builds the scenes, runs and measures.
//
// A case is one scene; each of its quantities is read off the sampled
// trajectory of three runs with the same extractor:
//   reference   the reference solver with the scene's integrator (the
//               default, semi-implicit Euler) at Δt = 1e-4 s;
//   MuJoCo      the engine "mujoco": the default mapping and geometry, its
//               Euler integrator at the same Δt;
//   converged   the dense Dormand–Prince reference (reference/
//               dense_reference.hpp) at rtol = atol = kConvergedTol, sampled
//               at the same times; for the slope, in the slope's own frame
//               (SlopeFrame).
// The cases (Kelvin–Voigt law unless the case says otherwise):
//   static      point mass and flat box at rest: depth = m·g/(N·k); and
//               MuJoCo's own direct-form answer m·g·Â·(1 − d)/(N·s) from the
//               compiled model (s = −solref[0], d = solimp[0], Â =
//               body_invweight0), which the mapping must make equal to m·g/k
//   rebound     point mass without gravity, one impact at ζ = 0.1 and 0.3,
//               both damping laws: e = v_out/v_in
//   slide       flat box launched at v0 with friction: distance to rest
//   roll        disc rolling with rolling resistance: deceleration, distance
//   bowling     disc launched sliding without spin: final speed, time to roll
//   backspin    disc thrown at the ground with backspin, no gravity, one
//               impact: v_x′ and R·ω′ from the impulse balance under Coulomb
//               friction, sliding through the impact or rolling out of it
//   slope       box on an inclined capsule obstacle: acceleration when
//               tanθ > μ, creep speed when tanθ < μ (the converged solution
//               in the slope's own frame, SlopeFrame)
// Nothing here decides pass or fail: the test does, with the tolerances
// derived in docs/closed-forms.md. The rows carry the same tolerances for the
// report.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/run.hpp"
#include "core/scene.hpp"

namespace contact2d::analysis {

// Tolerance of the converged solution (rtol = atol).
constexpr double kConvergedTol = 1e-10;

// What a quantity is read from: the sampled trajectory of one run and the
// case's scene.
using Extractor = std::function<double(const Scene& scene, const Trajectory& trajectory)>;

struct ClosedFormQuantity {
  std::string name;     // "depth at rest (m)"
  std::string formula;  // "m·g/k"
  double closed_form = 0.0;
  Extractor extract;
  // |reference − closed form| ≤ tolerance, |converged − closed form| ≤
  // converged_tolerance: derived (docs/closed-forms.md).
  double tolerance = 0.0;
  double converged_tolerance = 0.0;
  std::string why;  // the tolerance in a few words, for the report
  // What MuJoCo is expected to do here: a derived tolerance when its law
  // agrees, otherwise the measured-and-explained bound of the test (a
  // finding, stated as such in the report).
  double mujoco_bound = 0.0;
  bool mujoco_bound_derived = false;
  std::string mujoco_why;
  bool reference_applies = true;  // false: a MuJoCo-only closed form
};

// A slope case's own frame: the capsule's surface line through `origin`
// along u = (cos θ, sin θ), normal n = (−sin θ, cos θ). The dense reference
// (ground contact only) solves the slope there: the same body on flat ground
// with gravity g·cos θ and the applied force −m·g·sin θ along the slope;
// its trajectory is mapped back (p = origin + x'·u + y'·n, θ + θ').
struct SlopeFrame {
  double theta = 0.0;
  Vec2 origin = Vec2::Zero();
};

struct ClosedFormCase {
  std::string id;    // "static.point_mass"
  std::string name;  // "static penetration, point mass"
  Scene scene;
  bool converged_available = true;        // false: not solvable by the dense reference
  std::optional<SlopeFrame> slope_frame;  // the converged solution in the slope's frame
  std::vector<ClosedFormQuantity> quantities;
};

// The cases with their scenes, closed forms and tolerances (cheap: MuJoCo is
// compiled once for the static case's model constants).
std::vector<ClosedFormCase> closed_form_cases();

struct ClosedFormRow {
  std::string case_id, case_name;
  ClosedFormQuantity quantity;  // extract left as is
  double reference = std::numeric_limits<double>::quiet_NaN();
  double mujoco = std::numeric_limits<double>::quiet_NaN();
  double converged = std::numeric_limits<double>::quiet_NaN();  // NaN: not available
  std::string converged_note;                                   // why not available
};

struct ClosedFormTable {
  std::vector<ClosedFormRow> rows;
  double seconds = 0.0;       // wall clock of all runs
  std::string mujoco_engine;  // "mujoco calibrated Euler" (Stepper::describe)
  std::string reference_engine;
};

// Runs every case on the three engines (in parallel, `threads` = 0: one per
// core) and reads every quantity. Throws std::runtime_error when a run
// diverges or the converged solution fails where it should run.
// `mujoco_engine`: the registry's name of the MuJoCo whose column it is
// ("mujoco", "mujoco3": the same model, the same bounds).
ClosedFormTable closed_form_table(unsigned threads = 0,
                                  const std::string& mujoco_engine = "mujoco");

}  // namespace contact2d::analysis
