// Every fix compare's diagnosis prints, pasted into compare as printed,
// gives the remainder the diagnosis reported (Finding::after): the fix is
// read token by token as the program reads its options (--set KEY=VALUE,
// --dt, --model-dt, --mapping), applied to the scene file's text and to the
// MuJoCo engine, and both engines are run again. A fix that changes MuJoCo's
// model as well as the reference (a friction law's μ_roll corrected a second
// time, a rounded impratio) or that leaves out part of what the re-run
// changed (the Δt of the held-model re-run) fails.
//
// Tolerance. The pasted run is the diagnosis's re-run through the same
// code on the same numbers, so the distances agree to rounding: 1e-12 m
// plus 1e-9 of the distance (a number printed to its shortest round-trip
// form is read back to the same double; measured: every case equal).
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/friction_table.hpp"
#include "analysis/trajectory_error.hpp"
#include "diagnosis_util.hpp"
#include "io/scene_file.hpp"
#include "io/scene_writer.hpp"
#include "report/random_scenes.hpp"

namespace contact2d {
namespace {

struct Pasted {
  Scene scene;
  engines::EngineSpec spec;
};

// The fix's options applied as compare applies them.
Pasted paste(const Scene& scene, engines::EngineSpec spec, const std::string& fix) {
  std::istringstream in(fix);
  std::vector<Override> overrides;
  for (std::string option, value; in >> option >> value;) {
    if (option == "--set") {
      overrides.push_back(parse_override(value));
    } else if (option == "--dt") {
      overrides.push_back({"sim.dt", value, "--dt"});
    } else if (option == "--model-dt") {
      spec.model_dt = std::stod(value);
    } else if (option == "--mapping") {
      spec.set("mapping", value);
    } else {
      ADD_FAILURE() << "an option the test cannot paste: " << option << " in " << fix;
    }
  }
  return {parse_scene(scene_to_toml(scene), "pasted fix", overrides), spec};
}

// The fixes the diagnosis prints on the four shipped scenes under both
// mappings (counted: 54 with the full diagnosis), the rest of docs/compare.md's 96
// on the friction scenes.
constexpr int kShippedFixes = 54;

// Each finding with a fix: its remainder, and the pasted run's distance.
// Returns how many fixes were pasted (a run that pastes none checks
// nothing: the tests count them).
int check_fixes(const std::string& name, const Scene& scene, const std::string& mapping) {
  int pasted_fixes = 0;
  engines::EngineSpec spec;
  spec.kind = "mujoco";
  spec.set("mapping", mapping);
  // Full: the fixes of the fine-step causes too.
  const analysis::Diagnosis d = test::diagnosed(scene, spec, 1e-10, true).diagnosis;
  for (const analysis::Finding& f : d.findings) {
    if (f.fix.empty() || !std::isfinite(f.after)) continue;
    const Pasted p = paste(scene, spec, f.fix);
    const engines::EngineRun ref = engines::run_engine("ref", p.scene);
    const engines::EngineRun mj = engines::run_engine(p.spec, p.scene);
    EXPECT_FALSE(ref.trajectory.divergence || mj.trajectory.divergence) << name << " " << f.fix;
    if (ref.trajectory.divergence || mj.trajectory.divergence) continue;
    const double pasted = analysis::error_between(ref.trajectory, mj.trajectory).max_pos;
    std::printf("%s (%s) %s: reported %.6g m, pasted %.6g m  [%s]\n", name.c_str(), mapping.c_str(),
                f.cause.c_str(), f.after, pasted, f.fix.c_str());
    EXPECT_NEAR(pasted, f.after, 1e-12 + 1e-9 * f.after)
        << name << " (" << mapping << "): " << f.cause << ": " << f.fix;
    ++pasted_fixes;
  }
  return pasted_fixes;
}

TEST(PrintedFixes, DoWhatTheDiagnosisReportsOnTheShippedScenes) {
  int fixes = 0;
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    const Scene scene =
        load_scene(std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes/" + name + ".toml");
    for (const char* mapping : {"calibrated", "compensated"})
      fixes += check_fixes(name, scene, mapping);
  }
  std::printf("shipped scenes: %d fixes pasted\n", fixes);
  EXPECT_EQ(fixes, kShippedFixes);  // docs/compare.md: with the friction scenes', 96
}

// The closed-form friction scenes (analysis/friction_table.hpp): backspin,
// sliding to rest, rolling with resistance, on the compensated mapping,
// whose friction findings are the friction law's.
TEST(PrintedFixes, DoWhatTheDiagnosisReportsOnTheFrictionScenes) {
  int fixes = 0;
  for (const analysis::FrictionScene& fs : analysis::friction_scenes())
    fixes += check_fixes(fs.name, fs.scene, "compensated");
  std::printf("friction scenes: %d fixes pasted\n", fixes);
  EXPECT_EQ(fixes, 96 - kShippedFixes);  // docs/compare.md's 96 in all
}

// The diagnosis compare prints (the fine-step re-runs only when the others
// leave the difference unexplained) against the full one: every cause the
// screened diagnosis measures has the full one's numbers bit for bit (the
// same runs), its summary is the full one's whenever nothing was skipped,
// and a skipped cause is one the first tier's explanation made
// unnecessary. How often a skipped cause would have been named beside the
// one that explains ≥ kExplainedShare is counted and printed (measured: on
// stiff_k1e9, time_step at 20 % beside damping_law at 100 %).
void check_screened(const std::string& name, const Scene& scene, int& skipped_named) {
  const test::Diagnosed full = test::diagnosed(scene, {}, 1e-10, true);
  const test::Diagnosed screened = test::diagnosed(scene, {}, 1e-10, false);
  EXPECT_TRUE(full.diagnosis.not_rerun.empty()) << name;
  for (const analysis::Finding& f : screened.diagnosis.findings) {
    const analysis::Finding* same = test::finding(full.diagnosis, f.cause);
    ASSERT_NE(same, nullptr) << name << ": " << f.cause;
    EXPECT_EQ(f.named, same->named) << name << ": " << f.cause;
    if (std::isfinite(f.after) || std::isfinite(same->after)) {
      EXPECT_EQ(f.after, same->after) << name << ": " << f.cause;
    }
    EXPECT_EQ(f.fix, same->fix) << name << ": " << f.cause;
    EXPECT_EQ(f.explanation, same->explanation) << name << ": " << f.cause;
  }
  const std::vector<std::string>& skipped = screened.diagnosis.not_rerun;
  EXPECT_EQ(screened.diagnosis.findings.size() + skipped.size(), full.diagnosis.findings.size())
      << name;
  if (skipped.empty()) {
    EXPECT_EQ(screened.diagnosis.summary, full.diagnosis.summary) << name;
    return;
  }
  // Skipped only when a first-tier cause takes away ≥ kExplainedShare.
  bool explained = false;
  for (const analysis::Finding& f : screened.diagnosis.findings)
    explained |= f.named && f.share >= analysis::kExplainedShare;
  EXPECT_TRUE(explained) << name << ": " << screened.diagnosis.summary;
  for (const std::string& cause : skipped) {
    EXPECT_EQ(test::finding(screened.diagnosis, cause), nullptr) << name << ": " << cause;
    const analysis::Finding* f = test::finding(full.diagnosis, cause);
    ASSERT_NE(f, nullptr) << name << ": " << cause;
    std::printf("%s: %s not re-run (full: %.3g %s)\n", name.c_str(), cause.c_str(), f->share,
                f->named ? "named" : "ruled out");
    skipped_named += f->named ? 1 : 0;
  }
}

TEST(ScreenedDiagnosis, MeasuresWhatTheFullOneMeasuresOnShippedAndRandomScenes) {
  int skipped_named = 0, scenes = 0;
  const std::string dir = std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes/";
  for (const char* name :
       {"point_mass", "box", "tshape", "circle", "extreme/impact_50ms", "extreme/large_mass",
        "extreme/rolling_to_rest", "extreme/stiff_k1e9", "extreme/impact_50ms_coarse_step"}) {
    check_screened(name, load_scene(dir + name + ".toml"), skipped_named);
    ++scenes;
  }
  for (const analysis::FrictionScene& fs : analysis::friction_scenes()) {
    check_screened(fs.name, fs.scene, skipped_named);
    ++scenes;
  }
  for (const report::RandomScene& rs : report::draw_random_scenes(2026, 8)) {
    check_screened(rs.name, rs.scene, skipped_named);
    ++scenes;
  }
  std::printf("%d scenes; skipped causes the full diagnosis names: %d\n", scenes, skipped_named);
}

}  // namespace
}  // namespace contact2d
