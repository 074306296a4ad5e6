// contact2d_friction: the friction table: scene ×
// mapping, the max position difference (m) between the reference and MuJoCo
// at Δt = 1e-4 s (Kelvin–Voigt, k = 1e4 N/m, semi-implicit Euler in both,
// samples every 1 ms), and what MuJoCo does that the reference does not: its
// largest height above the reference's (the hop) and the disc's largest slip.
//
//   build-dir/bench/contact2d_friction [--mappings calibrated,compensated] [--variants]
//
// --variants adds, per mapping, impratio × 0.01, 0.1 and 10 (the rule's
// value at Δt = 1e-6, 1e-5 and 1e-3 held at Δt = 1e-4: Δt-independent
// choices), for the rolling disc calibrated's model with the cone
// coefficient μ_roll' of compensated, and for compensated the friction
// split (analysis::friction_split_xml) that removes the damper's push from the cone:
// the measurement that attributes the remaining differences.
//
// Scenes (analysis/friction_table.hpp, where the report's table comes from;
// all 1 kg):
//   box_slide      box 0.4 × 0.2 m lying flat, vx = 2 m/s, μ = 0.5, c = 50, 1.5 s
//   box_slide_c200 the same with c = 200 N·s/m
//   tshape         the T of tests/mujoco/mj_test_util.hpp's drop (θ = 0.2,
//                  vx = 0.3), μ = 0.5, c = 200, 2 s
//   roll           disc R = 0.1 m rolling (ω = −v/R) at 2 m/s, μ = 0.5,
//                  μ_roll = 0.01 m, c = 200, 3 s (stops after 3.06 m)
//   slide_roll     disc at 2 m/s without spin, μ = 0.2, c = 200, 2 s: slides,
//                  then rolls at 2/3 of v0 (Drake's bowling ball in 2D)
//   backspin       disc dropped from 0.3 m with vx = 1 m/s, ω = +30 rad/s
//                  (backspin), μ = 0.5, c = 200, 2 s
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "analysis/friction_table.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/body.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"

namespace {

using namespace contact2d;

struct Row {
  analysis::TrajectoryError e;
  double hop = 0.0;   // largest height of MuJoCo's COM above the reference's, m
  double slip = 0.0;  // disc: largest |v − (−ω R)| difference, m/s
};

Row measure(const Scene& scene, const Trajectory& reference, const std::string& xml) {
  mujoco::MujocoStepper stepper(scene, xml, "friction scene");
  const Trajectory mj = simulate(stepper, scene.sim);
  Row row;
  row.e = analysis::error_between(reference, mj);
  const size_t n = std::min(reference.samples.size(), mj.samples.size());
  for (size_t i = 0; i < n; ++i) {
    const State& a = reference.samples[i].state;
    const State& b = mj.samples[i].state;
    row.hop = std::max(row.hop, b.q.y() - a.q.y());
    if (scene.shape == Shape::Circle) {
      const double slip_a = a.v.x() + a.v.z() * scene.radius;
      const double slip_b = b.v.x() + b.v.z() * scene.radius;
      row.slip = std::max(row.slip, std::abs(slip_b - slip_a));
    }
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mapping_list = "calibrated,compensated";
  bool variants = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--mappings") && i + 1 < argc) mapping_list = argv[++i];
    if (!std::strcmp(argv[i], "--variants")) variants = true;
  }
  try {
    std::vector<mujoco::Mapping> mappings;
    for (size_t start = 0; start <= mapping_list.size();) {
      const size_t end = std::min(mapping_list.find(',', start), mapping_list.size());
      const auto m = mujoco::parse_mapping(mapping_list.substr(start, end - start));
      if (!m) throw std::runtime_error("unknown mapping in " + mapping_list);
      mappings.push_back(*m);
      start = end + 1;
    }
    // The report's table (analysis::friction_table): the attribution and
    // every knob, one line per scene.
    std::printf("%-16s %10s %10s %10s %10s %10s %10s\n", "scene", "calibrated", "compensated",
                "hop", "shape", "push", "rest");
    const std::vector<analysis::FrictionRow> rows = analysis::friction_table();
    for (const analysis::FrictionRow& r : rows)
      std::printf("%-16s %10.3g %10.3g %10.3g %10.3g %10.3g %10.3g\n", r.name.c_str(),
                  r.calibrated.max_pos, r.compensated.max_pos, r.compensated.hop, r.shape, r.push,
                  r.conformance);
    std::printf("\n%-16s", "knob (m)");
    for (analysis::FrictionKnob k : analysis::kFrictionKnobs)
      std::printf(" %22s", analysis::knob_name(k).c_str());
    std::printf(" %22s\n", "split");
    for (const analysis::FrictionRow& r : rows) {
      std::printf("%-16s", r.name.c_str());
      for (double d : r.knobs) std::printf(" %22.3g", d);
      std::printf(" %22.3g\n", r.split.max_pos);
    }
    std::printf("\n");
    if (!variants) return 0;
    std::printf("%-15s %-12s %10s %10s %10s %10s %10s\n", "scene", "mapping", "max pos m",
                "max ang rad", "hop m", "slip m/s", "impratio");
    for (const analysis::FrictionScene& fs : analysis::friction_scenes()) {
      const Scene& scene = fs.scene;
      const Trajectory reference = simulate(scene);
      for (mujoco::Mapping m : mappings) {
        mujoco::MjcfOptions options;
        options.mapping = m;
        const mujoco::GeneratedModel g = mujoco::generate_mjcf(scene, options);
        const Row row = measure(scene, reference, g.xml);
        std::printf("%-15s %-12s %10.3g %10.3g %10.3g %10.3g %10.4g\n", fs.name.c_str(),
                    std::string(mujoco::mapping_name(m)).c_str(), row.e.max_pos, row.e.max_angle,
                    row.hop, row.slip, g.settings.impratio);
        std::fflush(stdout);
        if (!variants) continue;
        for (double factor : {0.01, 0.1, 10.0}) {
          mujoco::SolverSettings s = g.settings;
          s.impratio *= factor;
          const Row v = measure(scene, reference, mujoco::write_mjcf(scene, options, s));
          std::printf("%-15s %-12s %10.3g %10.3g %10.3g %10.3g %10.4g (impratio x%g)\n",
                      fs.name.c_str(), std::string(mujoco::mapping_name(m)).c_str(), v.e.max_pos,
                      v.e.max_angle, v.hop, v.slip, s.impratio, factor);
        }
        if (m == mujoco::Mapping::Compensated) {
          for (double w : {0.3}) {
            for (double rho_share : {1e-3, 1e-4}) {
              const double rho = rho_share * scene.contact.c;
              const Row v = measure(scene, reference, analysis::friction_split_xml(scene, w, rho));
              std::printf("%-15s %-12s %10.3g %10.3g %10.3g %10.3g (split w %g, rho %g c)\n",
                          fs.name.c_str(), "split", v.e.max_pos, v.e.max_angle, v.hop, v.slip, w,
                          rho_share);
              std::fflush(stdout);
            }
          }
        }
        if (m == mujoco::Mapping::Compensated && scene.shape == Shape::Circle &&
            scene.contact.mu_roll > 0.0) {
          // the slip the cone needs, v_t = κ·(μ_roll/μ)²·ω/R, 100× smaller
          // with μ × 10 in MuJoCo (the disc never slides here)
          Scene wide = scene;
          wide.contact.mu *= 10;
          for (double factor : {1.0, 100.0}) {
            // × 100 keeps the divisor 1 + μ²/impratio and the rolling slope
            mujoco::SolverSettings s = g.settings;
            s.impratio *= factor;
            const Row v = measure(scene, reference, mujoco::write_mjcf(wide, options, s));
            std::printf("%-15s %-12s %10.3g %10.3g %10.3g %10.3g %10.4g (mu x10 in MuJoCo)\n",
                        fs.name.c_str(), std::string(mujoco::mapping_name(m)).c_str(), v.e.max_pos,
                        v.e.max_angle, v.hop, v.slip, s.impratio);
          }
        }
        if (m == mujoco::Mapping::Calibrated && scene.shape == Shape::Circle &&
            scene.contact.mu_roll > 0.0) {
          // the elliptic cone's shared budget: mu_roll' = mu_roll/sqrt(1 - (kappa mu_roll/(mu
          // R))^2)
          Scene budget = scene;
          const double kappa = 2.0 / 3.0;
          const double q = kappa * scene.contact.mu_roll / (scene.contact.mu * scene.radius);
          budget.contact.mu_roll = scene.contact.mu_roll / std::sqrt(1 - q * q);
          const Row v = measure(scene, reference, mujoco::write_mjcf(budget, options, g.settings));
          std::printf("%-15s %-12s %10.3g %10.3g %10.3g %10.3g %10.4g (mu_roll %.6g)\n",
                      fs.name.c_str(), std::string(mujoco::mapping_name(m)).c_str(), v.e.max_pos,
                      v.e.max_angle, v.hop, v.slip, g.settings.impratio, budget.contact.mu_roll);
        }
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contact2d_friction: %s\n", e.what());
    return 1;
  }
  return 0;
}
