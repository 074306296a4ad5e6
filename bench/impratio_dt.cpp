// contact2d_impratio: calibrated's impratio = 1/(c·Δt·A_t) depends on Δt.
// Does a Δt-independent choice measure as well? On each built-in scene with
// the Kelvin–Voigt law (the compression law's gap to MuJoCo's damper would
// swamp friction: see README) at Δt = 1e-3, 1e-4, 1e-5, the max and RMS
// position error against the reference (same Δt and integrator, samples
// every 1 ms) of the generated model with
//   rule    impratio = 1/(c·Δt·A_t) (as generated)
//   fixed   1/(c·1e-3·A_t): the rule at the largest Δt, chatter-free below it
//   old     μ·m·g·α/c: what the header used to state
// Everything else in the model is as generated.
//
//   build-dir/bench/contact2d_impratio
#include <cstdio>
#include <exception>
#include <string>

#include "analysis/trajectory_error.hpp"
#include "core/body.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"

int main() {
  using namespace contact2d;
  std::printf("%-11s %-7s  %-33s %-33s %-33s\n", "scene", "dt", "rule: impratio max rms",
              "fixed: impratio max rms", "old: impratio max rms");
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    const std::string source = std::string("validation/scenes/") + name + ".toml";
    const Scene base = load_scene(std::string(CONTACT2D_SOURCE_DIR) + "/" + source);
    for (double dt : {1e-3, 1e-4, 1e-5}) {
      Scene s = base;
      s.sim.dt = dt;
      s.sim.output_dt = 1e-3;
      s.contact.damping = DampingLaw::KelvinVoigt;
      mujoco::MjcfOptions options;
      options.source = source;
      mujoco::GeneratedModel generated;
      try {
        generated = mujoco::generate_mjcf(s, options);
      } catch (const std::exception& e) {
        std::printf("%-11s %-7g  %s\n", name, dt, e.what());
        continue;
      }
      const Trajectory reference = simulate(s);
      const RigidBody body = make_body(s);
      const double r = body_extent(body);
      const double a_t = body.rotates ? 1.0 / body.mass + r * r / body.inertia : 1.0 / body.mass;
      const double fixed = 1.0 / (s.contact.c * 1e-3 * a_t);
      const double old = s.contact.mu * body.mass * s.sim.gravity * s.contact.alpha / s.contact.c;
      std::printf("%-11s %-7g", name, dt);
      for (double impratio : {generated.settings.impratio, fixed, old}) {
        mujoco::SolverSettings settings = generated.settings;
        settings.impratio = impratio;
        mujoco::MujocoStepper stepper(s, mujoco::write_mjcf(s, options, settings), source);
        const analysis::TrajectoryError e =
            analysis::error_between(reference, simulate(stepper, s.sim));
        std::printf("  %9.4g %10.4g %10.4g", impratio, e.max_pos, e.rms_pos);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  return 0;
}
