// contact2d_compare_sections: where the wall time of `contact2d compare`
// goes, section by section, on each shipped scene (docs/speed.md):
//   engines     the reference and MuJoCo at the scene's Δt (run_engines)
//   converged   the converged solution, its run at 10× the tolerance and
//               the perturbed run of the amplification (measure, no
//               diagnosis)
//   diagnosis   what the diagnosis adds, as compare runs it: its early
//               MuJoCo runs beside the base runs, then the first tier, and
//               the fine-step re-runs only when it leaves the difference
//               unexplained (analysis/comparison.hpp)
//   full        the diagnosis with every re-run (--full-diagnosis)
// Each section is the median of `repeats` runs (default 5) on the
// machine's cores, as compare runs it; the scenes are the four built-in
// ones unless given (paths). The ratio is the cost of compare
// with its diagnosis over --no-diagnosis: (engines + converged +
// diagnosis) / (engines + converged); the process's start (the same for
// both) is in neither.
//
//   build-dir/bench/contact2d_compare_sections [repeats [SCENE.toml ...]]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "analysis/compare_run.hpp"
#include "analysis/comparison.hpp"
#include "io/scene_file.hpp"

namespace {

using namespace contact2d;

double seconds(const std::function<void()>& section) {
  const auto start = std::chrono::steady_clock::now();
  section();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::printf(
      "| scene | engines (s) | converged (s) | diagnosis (s) | full diagnosis (s) | "
      "with diagnosis / without | full / without | not re-run |\n"
      "|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> paths;
  for (int i = 2; i < argc; ++i) paths.emplace_back(argv[i]);
  if (paths.empty())
    for (const char* name : {"point_mass", "box", "tshape", "circle"})
      paths.push_back(std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes/" + name + ".toml");
  for (const std::string& path : paths) {
    const Scene scene = load_scene(path);
    const std::string name = path.substr(path.find_last_of('/') + 1);
    engines::EngineSpec ref, mujoco;
    ref.kind = "ref";
    mujoco.kind = "mujoco";
    std::vector<double> engines_s, converged_s, diagnosis_s, full_s;
    std::string skipped;
    for (int i = 0; i < repeats; ++i) {
      // Without the diagnosis, as compare --no-diagnosis runs.
      analysis::Comparison c = analysis::prepare_comparison(scene, {ref, mujoco});
      engines_s.push_back(seconds([&] { analysis::run_engines(c); }));
      converged_s.push_back(seconds([&] { analysis::measure(c, 1e-12, false); }));
      const analysis::ThreeWay three = analysis::pair(c, 1);
      // With it, as compare runs: the early MuJoCo runs beside the base
      // runs, then the rest; its cost is what it adds to the sections above.
      analysis::Comparison with = analysis::prepare_comparison(scene, {ref, mujoco});
      diagnosis_s.push_back(seconds([&] {
                              analysis::run_engines(with, true);
                              analysis::measure(with, 1e-12, true);
                            }) -
                            engines_s.back() - converged_s.back());
      const analysis::Diagnosis& d = with.diagnosis;
      analysis::DiagnosisOptions full;
      full.full = true;
      full_s.push_back(seconds([&] {
        analysis::diagnose(scene, mujoco, c.runs[0].run, c.runs[1].run, three,
                           analysis::registry_runner(), full);
      }));
      skipped.clear();
      for (const std::string& cause : d.not_rerun) skipped += (skipped.empty() ? "" : ", ") + cause;
    }
    const double e = median(engines_s), cv = median(converged_s), dg = median(diagnosis_s),
                 fl = median(full_s);
    std::printf("| %s | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %s |\n", name.c_str(), e, cv, dg,
                fl, (e + cv + dg) / (e + cv), (e + cv + fl) / (e + cv),
                skipped.empty() ? "–" : skipped.c_str());
  }
  return 0;
}
