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

// Each finding with a fix: its remainder, and the pasted run's distance.
void check_fixes(const std::string& name, const Scene& scene, const std::string& mapping) {
  engines::EngineSpec spec;
  spec.kind = "mujoco";
  spec.set("mapping", mapping);
  const analysis::Diagnosis d = test::diagnosed(scene, spec, 1e-10).diagnosis;
  for (const analysis::Finding& f : d.findings) {
    if (f.fix.empty() || !std::isfinite(f.after)) continue;
    const Pasted p = paste(scene, spec, f.fix);
    const engines::EngineRun ref = engines::run_engine("ref", p.scene);
    const engines::EngineRun mj = engines::run_engine(p.spec, p.scene);
    ASSERT_FALSE(ref.trajectory.divergence || mj.trajectory.divergence) << name << " " << f.fix;
    const double pasted = analysis::error_between(ref.trajectory, mj.trajectory).max_pos;
    std::printf("%s (%s) %s: reported %.6g m, pasted %.6g m  [%s]\n", name.c_str(), mapping.c_str(),
                f.cause.c_str(), f.after, pasted, f.fix.c_str());
    EXPECT_NEAR(pasted, f.after, 1e-12 + 1e-9 * f.after)
        << name << " (" << mapping << "): " << f.cause << ": " << f.fix;
  }
}

TEST(PrintedFixes, DoWhatTheDiagnosisReportsOnTheShippedScenes) {
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    const Scene scene =
        load_scene(std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes/" + name + ".toml");
    for (const char* mapping : {"calibrated", "compensated"}) check_fixes(name, scene, mapping);
  }
}

// The closed-form friction scenes (analysis/friction_table.hpp): backspin,
// sliding to rest, rolling with resistance, on the compensated mapping,
// whose friction findings are the friction law's.
TEST(PrintedFixes, DoWhatTheDiagnosisReportsOnTheFrictionScenes) {
  for (const analysis::FrictionScene& fs : analysis::friction_scenes())
    check_fixes(fs.name, fs.scene, "compensated");
}

}  // namespace
}  // namespace contact2d
