// A comparison of N engines (analysis/compare_run.hpp): each run measured
// against the first and the converged solution exactly as it would be in a
// comparison of that pair alone, named apart when two share an engine, and
// the engines chosen from the registry's data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "analysis/compare_run.hpp"
#include "core/input_error.hpp"
#include "mj_test_util.hpp"

namespace contact2d {
namespace {

// A box landing on a corner with friction (the engines differ by
// centimetres), short enough for four comparisons.
const char* kCornerBox = R"(scene = "box"
[body]
mass = 1.0
width = 0.4
height = 0.2
[contact]
k = 1e4
c = 20
mu = 0.5
[initial]
y = 0.5
theta = 0.3
vx = 0.5
[sim]
dt = 1e-4
duration = 0.4
integrator = "semi_implicit_euler"
)";

std::string flag_of(std::string_view name) { return "--" + std::string(name); }

analysis::Comparison compared_on(const std::vector<std::string>& names) {
  const Scene scene = test::scene_from(kCornerBox);
  analysis::Comparison c = analysis::prepare_comparison(
      scene, analysis::comparison_engines(names, {}, 0.0, "box.toml", flag_of));
  analysis::run_engines(c);
  analysis::measure(c, 1e-10, false);
  return c;
}

void expect_same_distances(const analysis::TrajectoryError& a, const analysis::TrajectoryError& b,
                           const std::string& what) {
  EXPECT_EQ(a.samples, b.samples) << what;
  EXPECT_EQ(a.max_pos, b.max_pos) << what;
  EXPECT_EQ(a.rms_pos, b.rms_pos) << what;
  EXPECT_EQ(a.end_pos, b.end_pos) << what;
  EXPECT_EQ(a.max_angle, b.max_angle) << what;
  EXPECT_EQ(a.max_vel, b.max_vel) << what;
  EXPECT_EQ(a.time_of_max_pos, b.time_of_max_pos) << what;
}

// Every engine is deterministic and each run is measured on its own, so
// the distances of a run in a three-engine comparison are, bit for bit,
// those of its two-engine comparison; a mixed-up index or a run measured
// against the wrong one would differ by centimetres.
TEST(CompareEngines, EachRunIsMeasuredAsInItsOwnPair) {
  const analysis::Comparison three = compared_on({"mujoco:exact", "mujoco:calibrated:boxes"});
  ASSERT_EQ(three.runs.size(), 3u);
  ASSERT_TRUE(three.converged.available);
  const analysis::Comparison exact = compared_on({"mujoco:exact"});
  const analysis::Comparison boxes = compared_on({"mujoco:calibrated:boxes"});
  expect_same_distances(three.runs[1].vs_first, exact.runs[1].vs_first, "exact vs ref");
  expect_same_distances(three.runs[2].vs_first, boxes.runs[1].vs_first, "boxes vs ref");
  expect_same_distances(three.runs[0].vs_converged, exact.runs[0].vs_converged, "ref vs converged");
  expect_same_distances(three.runs[1].vs_converged, exact.runs[1].vs_converged,
                        "exact vs converged");
  expect_same_distances(three.runs[2].vs_converged, boxes.runs[1].vs_converged,
                        "boxes vs converged");
  // The two MuJoCo models differ from each other, so the test would see a swap.
  EXPECT_GT(std::abs(three.runs[1].vs_first.max_pos - three.runs[2].vs_first.max_pos), 1e-4);
  EXPECT_EQ(three.runs[0].vs_first.samples, 0u);  // the first is not measured against itself
}

TEST(CompareEngines, RunsOfOneEngineAreNamedApart) {
  const Scene scene = test::scene_from(kCornerBox);
  const analysis::Comparison two = analysis::prepare_comparison(
      scene, analysis::comparison_engines({}, {}, 0.0, "box.toml", flag_of));
  ASSERT_EQ(two.runs.size(), 2u);
  EXPECT_EQ(two.runs[0].label, "ref");
  EXPECT_EQ(two.runs[0].key, "ref");
  EXPECT_EQ(two.runs[1].label, "MuJoCo");
  EXPECT_EQ(two.runs[1].key, "mujoco");
  const analysis::Comparison three = analysis::prepare_comparison(
      scene, analysis::comparison_engines({"mujoco:exact", "mujoco::boxes"}, {}, 0.0, "box.toml",
                                          flag_of));
  EXPECT_EQ(three.runs[1].label, "mujoco:exact");
  EXPECT_EQ(three.runs[1].key, "mujoco_exact");
  EXPECT_EQ(three.runs[2].label, "mujoco::boxes");
  EXPECT_EQ(three.runs[2].key, "mujoco__boxes");
}

// The JSON of two engines keeps its keys; a third adds the same keys under
// its own key.
TEST(CompareEngines, JsonKeysOfAFurtherEngineCarryItsKey) {
  const analysis::Comparison three = compared_on({"mujoco:exact", "mujoco:calibrated:boxes"});
  const std::string json = analysis::comparison_json(three, "box.toml");
  for (const char* key :
       {"\"mapping\": \"exact\"", "\"geometry\": \"corners\"",
        "\"mujoco_calibrated_boxes_mapping\": \"calibrated\"",
        "\"mujoco_calibrated_boxes_geometry\": \"boxes\"",
        "\"integrators\": {\"ref\": \"semi_implicit_euler\", \"mujoco_exact\": \"Euler\", "
        "\"mujoco_calibrated_boxes\": \"Euler\"}",
        "\"ref_vs_mujoco_exact_max_pos_err\": ", "\"ref_vs_mujoco_calibrated_boxes_max_pos_err\": ",
        "\"mujoco_calibrated_boxes_vs_converged_max_pos_err\": ",
        "\"mujoco_calibrated_boxes_solref\": [", "\"mujoco_calibrated_boxes_warnings\": ["})
    EXPECT_NE(json.find(key), std::string::npos) << key << " in " << json;
  const std::string pair = analysis::comparison_json(compared_on({"mujoco"}), "box.toml");
  EXPECT_EQ(pair.find("mujoco_calibrated"), std::string::npos) << pair;
  EXPECT_NE(pair.find("\"ref_vs_mujoco_max_pos_err\": "), std::string::npos) << pair;
}

TEST(CompareEngines, DefaultIsEveryEngineBuiltInWithTheOptionsItTakes) {
  const std::vector<engines::EngineSpec> specs =
      analysis::comparison_engines({}, {{"mapping", "exact"}}, 0.002, "box.toml", flag_of);
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].name(), "ref");
  EXPECT_EQ(specs[1].name(), "mujoco:exact");
  EXPECT_EQ(specs[1].model_dt, 0.002);
  EXPECT_EQ(specs[1].source, "box.toml");
}

TEST(CompareEngines, BadChoicesAreOneLineErrors) {
  auto error = [](const std::vector<std::string>& names, const engines::OptionValues& given) {
    try {
      analysis::comparison_engines(names, given, 0.0, "box.toml", flag_of);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // Several engines: each carries its options in its name. One engine
  // takes them as options, as simulate's --engine does.
  EXPECT_EQ(error({"mujoco", "mujoco3"}, {{"mapping", "exact"}}),
            "--mapping exact: with --engines an engine's options are part of its name "
            "(KIND:VALUE:VALUE)");
  EXPECT_EQ(error({"mujoco"}, {{"mapping", "exact"}}), "");
  EXPECT_EQ(error({"mujoco:seed"}, {{"mapping", "exact"}}),
            "--mapping exact: the engine's name mujoco:seed gives mapping seed already");
  EXPECT_EQ(error({"bullet"}, {}), "--engines bullet: unknown engine (use ref, mujoco or mujoco3)");
  EXPECT_EQ(error({"ref"}, {}),
            "--engines ref: the reference is always compared, as the first run");
  EXPECT_EQ(error({"mujoco", "mujoco:calibrated:corners"}, {}),
            "--engines mujoco:calibrated:corners: the same engine as mujoco, named twice");
  EXPECT_EQ(error({}, {{"mapping", "stiff"}}),
            "--mapping stiff: unknown mapping (seed, exact, calibrated, compensated)");
  EXPECT_THROW(
      analysis::prepare_comparison(test::scene_from(kCornerBox), {engines::parse_engine("ref")}),
      InputError);
}

// The diagnosis's causes are those of soft constraints (MuJoCo's): it is of
// the first engine that has them, and without one it says why it did not
// run instead of explaining a difference in MuJoCo's terms.
TEST(CompareEngines, DiagnosisIsOfTheFirstEngineWithSoftConstraints) {
  const Scene scene = test::scene_from(kCornerBox);
  const engines::EngineSpec ref = engines::parse_engine("ref");
  analysis::Comparison c =
      analysis::prepare_comparison(scene, {ref, ref, engines::parse_engine("mujoco:exact")});
  analysis::run_engines(c);
  analysis::measure(c, 1e-10, true);
  EXPECT_EQ(c.diagnosed, 2u);
  EXPECT_TRUE(c.diagnosis.ran);
  // ref ↔ mujoco:exact differ by centimetres here: the diagnosis re-ran and found causes.
  EXPECT_FALSE(c.diagnosis.findings.empty());
  analysis::Comparison none = analysis::prepare_comparison(scene, {ref, ref});
  analysis::run_engines(none);
  analysis::measure(none, 1e-10, true);
  EXPECT_EQ(none.diagnosed, 0u);
  EXPECT_FALSE(none.diagnosis.ran);
  EXPECT_TRUE(none.diagnosis.findings.empty());
  EXPECT_EQ(none.diagnosis.summary.rfind("Not run: ", 0), 0u) << none.diagnosis.summary;
  EXPECT_NE(none.diagnosis.summary.find("ref has none."), std::string::npos)
      << none.diagnosis.summary;
}

// The diagnosis's MuJoCo runs made early, beside the base runs, are the
// runs it would make itself: on every built-in shape with friction (the
// early runs: friction, rolling resistance, mapping) the findings are the
// same bit for bit, and the early runs were used.
TEST(CompareEngines, EarlyDiagnosisRunsChangeNoFinding) {
  for (const Shape shape : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
    Scene scene = test::drop_scene(shape, 200.0, 0.5);
    scene.sim.duration = 0.5;
    scene.contact.damping = DampingLaw::Compression;
    if (shape == Shape::Circle) scene.contact.mu_roll = 0.01;
    const std::vector<engines::EngineSpec> specs = {engines::parse_engine("ref"),
                                                    engines::parse_engine("mujoco")};
    analysis::Comparison late = analysis::prepare_comparison(scene, specs);
    analysis::run_engines(late, false);
    analysis::measure(late, 1e-10, true);
    analysis::Comparison early = analysis::prepare_comparison(scene, specs);
    analysis::run_engines(early, true);
    EXPECT_EQ(early.early.size(), shape == Shape::Circle ? 3u : 2u) << shape_name(shape);
    analysis::measure(early, 1e-10, true);
    ASSERT_EQ(late.diagnosis.findings.size(), early.diagnosis.findings.size());
    for (size_t i = 0; i < late.diagnosis.findings.size(); ++i) {
      const analysis::Finding &a = late.diagnosis.findings[i], &b = early.diagnosis.findings[i];
      EXPECT_EQ(a.cause, b.cause);
      if (std::isfinite(a.after) || std::isfinite(b.after)) {
        EXPECT_EQ(a.after, b.after) << shape_name(shape) << " " << a.cause;
      }
      EXPECT_EQ(a.explanation, b.explanation);
    }
    EXPECT_EQ(late.diagnosis.summary, early.diagnosis.summary);
  }
}

// An engine that cannot run the scene says so before anything runs.
TEST(CompareEngines, AnIntegratorAnEngineLacksFailsBeforeAnyRun) {
  Scene scene = test::scene_from(kCornerBox);
  scene.sim.integrator = Integrator::ExplicitEuler;
  try {
    analysis::prepare_comparison(scene,
                                 analysis::comparison_engines({}, {}, 0.0, "box.toml", flag_of));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("explicit_euler has no MuJoCo 2.2 counterpart"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace contact2d

namespace contact2d {
namespace {

// A box dropped flat onto a narrow post (issue 49): the post's corners
// press into the box's bottom face, between its corners. The corners
// geometry has MuJoCo's geoms at the box's corners only: MuJoCo makes no
// contact, the box passes into the post, and MuJoCo's run later "diverges"
// (the energy rises). compare names the missing contact first, with the
// geometry that sees it; the boxes geometry runs without the note; a box
// landing on a wide platform (its corners on the platform's face) gets no
// note.
const char* kBoxOnPost = R"(scene = "box"
[body]
mass = 1
width = 0.4
height = 0.1
[contact]
k = 1e4
c = 50
mu = 0.5
damping = "kelvin_voigt"
[initial]
y = 0.5
[sim]
dt = 1e-4
duration = 0.4
[[obstacle]]
type = "box"
x = 0.05
y = 0.15
width = WIDTH
height = 0.3
)";

analysis::Comparison on_obstacle(const std::string& width, const std::string& engine) {
  std::string text = kBoxOnPost;
  text.replace(text.find("WIDTH"), 5, width);
  analysis::Comparison c = analysis::prepare_comparison(
      test::scene_from(text),
      analysis::comparison_engines({engine}, {}, 0.0, "post.toml", flag_of));
  analysis::run_engines(c, false);
  return c;
}

TEST(CompareEngines, AContactTheCornersGeometryCannotMakeIsNamed) {
  const analysis::Comparison post = on_obstacle("0.05", "mujoco");
  const engines::EngineRun& run = post.runs[1].run;
  std::string said = run.divergence_message;
  for (const std::string& w : run.warnings) said += w;
  EXPECT_EQ(said.rfind("MuJoCo has no contact where the reference has one: at t = ", 0), 0u)
      << said;
  EXPECT_NE(said.find("a corner of obstacle 0 is"), std::string::npos) << said;
  EXPECT_NE(said.find("mujoco:calibrated:boxes (--geometry boxes)"), std::string::npos) << said;
  const analysis::Comparison boxes = on_obstacle("0.05", "mujoco:calibrated:boxes");
  EXPECT_FALSE(boxes.runs[1].run.trajectory.divergence.has_value());
  for (const std::string& w : boxes.runs[1].run.warnings)
    EXPECT_EQ(w.find("has no contact"), std::string::npos) << w;
  // There 2.2.2's box-box collider makes a contact 0.95 m off the body's box
  // (at t = 0.2733 s), where the post's corner meets the box's face: named
  // in its warnings (compare's "Versions" called the difference rounding).
  const std::vector<std::string>& stray = boxes.runs[1].run.warnings;
  EXPECT_TRUE(std::any_of(stray.begin(), stray.end(), [](const std::string& w) {
    return w.rfind("MuJoCo 2.2.2 made a contact off the body: at t = ", 0) == 0 &&
           w.find("outside part0_box, between obstacle0 and part0_box") != std::string::npos;
  }));
}

// A box landing flat on a wide platform: its corners are on the platform's
// face, and 2.2.2's sphere-box collider gives a corner sphere whose centre
// is inside the box the depth −radius (1e-9 m) however deep it is, so the
// box sinks into the platform (measured 2.8 cm deep at 0.3 s, still sinking
// at 0.098 m/s, where the reference rests 1 mm deep). compare names it; the
// boxes geometry rests (0.349 m, as the reference) without the note.
TEST(CompareEngines, MujocoTwoSinkingIntoABoxObstacleIsNamed) {
  const analysis::Comparison platform = on_obstacle("1.0", "mujoco");
  const engines::EngineRun& run = platform.runs[1].run;
  std::string said = run.divergence_message;
  for (const std::string& w : run.warnings) said += w;
  EXPECT_EQ(said.rfind("MuJoCo 2.2.2 has no spring where the reference has one: at t = ", 0), 0u)
      << said;
  EXPECT_NE(said.find("mujoco:calibrated:boxes (--geometry boxes)"), std::string::npos) << said;
  const analysis::Comparison boxes = on_obstacle("1.0", "mujoco:calibrated:boxes");
  EXPECT_FALSE(boxes.runs[1].run.trajectory.divergence.has_value());
  for (const std::string& w : boxes.runs[1].run.warnings) {
    EXPECT_EQ(w.find("has no"), std::string::npos) << w;
    EXPECT_EQ(w.find("off the body"), std::string::npos) << w;  // a box on a box: no stray contact
  }
  EXPECT_NEAR(boxes.runs[1].run.trajectory.samples.back().state.q.y(), 0.349, 1e-3);
}

}  // namespace
}  // namespace contact2d
