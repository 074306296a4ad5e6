// MuJoCo 3.14 (the engine mujoco3) against MuJoCo 2.2.2 on every shipped
// scene and on drops the repository does not ship, under each mapping: the
// same MJCF is the same contact law on both (docs/mujoco3.md), held to
// rounding at the first step that differs and to 1e-9 m or the scene's own
// amplification of rounding (VersionGap, below). Its own executable with
// the label "versions": 50–80 s of stepping, run in the Release stage only.
#include <cmath>
#include <filesystem>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/stepper.hpp"
#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;
using test::other_drops;

// How two builds of MuJoCo differ on a scene. Both step the same MJCF with
// the same algorithm, so they agree bit for bit until a last-bit difference
// of their arithmetic (native x86-64 against WebAssembly: libm's sin, cos,
// pow) first shows; from there the scene itself decides how far the runs
// part. So the tests hold them to:
//  - first_step_gap: the difference at the first step where the two states
//    differ is rounding: ≤ 1e-12 m (a few ulps of a coordinate of ≤ 10 m,
//    times the compensated model's lever of up to ~300 m: ~1e-13 m);
//  - distance ≤ max(1e-9 m, 3·sensitivity), sensitivity being how far
//    MuJoCo 2.2.2 itself moves when the start moves by a rounding-sized
//    1e-14 m (x and y, either sign). Some scenes amplify that to
//    millimetres (a light box rattling, a tumbling box under the seed
//    mapping: measured in docs/mujoco3.md); the factor 3 covers the
//    spread between perturbations of one size (0.1–3.4 mm on one scene).
struct VersionGap {
  double distance = 0.0;        // largest position or angle difference, m or rad
  double first_step_gap = 0.0;  // the difference at the first step that differs
  double sensitivity = 0.0;     // 2.2.2 against itself from a start moved 1e-14 m (0: not needed)
  long long steps = 0;
};

double gap(const State& a, const State& b) {
  const Vec3 e = a.q - b.q;
  return std::max(std::hypot(e.x(), e.y()), std::abs(e.z()));
}

// Steps both until the end or until either reports a failure (then both
// must, at the same step).
double run_apart(Stepper& a, Stepper& b, long long steps, double* first = nullptr) {
  double largest = 0.0;
  for (long long i = 0; i < steps; ++i) {
    const StepStatus sa = a.step(), sb = b.step();
    EXPECT_EQ(sa, sb) << "step " << i;
    if (sa != StepStatus::Ok || sb != StepStatus::Ok) break;
    const double d = gap(a.state(), b.state());
    if (first != nullptr && *first == 0.0 && d > 0.0) *first = d;
    largest = std::max(largest, d);
  }
  return largest;
}

// Both versions on a scene under a mapping; steps = 0 when MuJoCo has no
// such integrator (explicit Euler). Any other refusal is a failure: it
// throws out of the test (a model either version refuses is not skipped).
VersionGap version_gap(const Scene& scene, const std::string& mapping) {
  mujoco::MjcfOptions options;
  options.mapping = *mujoco::parse_mapping(mapping);
  VersionGap g;
  if (scene.sim.integrator == Integrator::ExplicitEuler) return g;
  mujoco::MujocoStepper two(scene, options);
  mujoco3::Mujoco3Stepper three(scene, options);
  g.steps = step_count(scene.sim);
  three.plan(g.steps);
  g.distance = run_apart(two, three, g.steps, &g.first_step_gap);
  if (g.distance <= 1e-9) return g;
  for (const Vec3& nudge :
       {Vec3(1e-14, 0, 0), Vec3(-1e-14, 0, 0), Vec3(0, 1e-14, 0), Vec3(0, -1e-14, 0)}) {
    mujoco::MujocoStepper two(scene, options), moved(scene, options);
    State start = initial_state(scene);
    start.q += nudge;
    moved.reset(start);
    g.sensitivity = std::max(g.sensitivity, run_apart(two, moved, g.steps));
  }
  return g;
}

void expect_versions_agree(const VersionGap& g, const std::string& what) {
  std::printf("  %-52s %.3g (first %.2g, sensitivity %.3g)\n", what.c_str(), g.distance,
              g.first_step_gap, g.sensitivity);
  EXPECT_LE(g.first_step_gap, 1e-12) << what;
  EXPECT_LE(g.distance, std::max(1e-9, 3.0 * g.sensitivity)) << what;
}

std::vector<fs::path> shipped_scenes() {
  std::vector<fs::path> out;
  for (const char* dir :
       {"validation/scenes", "validation/scenes/extreme", "validation/scenes/game"})
    for (const auto& e : fs::directory_iterator(fs::path(CONTACT2D_SOURCE_DIR) / dir))
      if (e.path().extension() == ".toml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Mujoco3, FollowsMujoco222OnEveryShippedSceneWithoutFriction) {
  CONTACT2D_NEEDS_MUJOCO3();
  int compared = 0, expected = 0;
  for (const fs::path& path : shipped_scenes()) {
    const Scene scene =
        load_scene(path.string(),
                   {{"contact.mu", "0"}, {"contact.mu_roll", "0"}, {"contact.mu_torsion", "0"}});
    // Every scene that MuJoCo can step (not explicit Euler), both mappings.
    if (scene.sim.integrator != Integrator::ExplicitEuler) expected += 2;
    for (const char* mapping : {"compensated", "calibrated"}) {
      const VersionGap g = version_gap(scene, mapping);
      if (g.steps == 0) continue;
      ++compared;
      expect_versions_agree(g, path.filename().string() + " " + mapping);
    }
  }
  EXPECT_EQ(compared, expected);
  EXPECT_EQ(expected, 34);  // 17 scenes shipped, none of them explicit Euler today
}

TEST(Mujoco3, FollowsMujoco222WithFrictionAndOnScenesNotShipped) {
  CONTACT2D_NEEDS_MUJOCO3();
  int compared = 0;
  for (double mu : {0.0, 0.6})
    for (const Scene& scene : other_drops(mu))
      for (const char* mapping : {"compensated", "calibrated", "exact", "seed"}) {
        const VersionGap g = version_gap(scene, mapping);
        compared += g.steps > 0;
        expect_versions_agree(g, std::string(shape_name(scene.shape)) + " mu " +
                                     format_number(mu, 2) + " " + mapping);
      }
  EXPECT_EQ(compared, 2 * 4 * 4);  // μ × the four drops × the mappings: each one stepped
}

}  // namespace
}  // namespace contact2d
