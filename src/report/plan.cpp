// The plan of `contact2d report` (report/plan.hpp): the scenes, the
// overrides of each case and the order of the runs, section by section of
// the pages, and then the pages. Every run is a call of the seam
// (report/runs.hpp); this file reads scene files and writes pages only.
#include "report/plan.hpp"

#include <glob.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

#include "analysis/engine.hpp"
#include "io/atomic_file.hpp"
#include "io/scene_file.hpp"
#include "io/scene_writer.hpp"
#include "report/numbers.hpp"
#include "report/pages.hpp"
#include "report/random_scenes.hpp"
#include "report/runs.hpp"

namespace contact2d::report {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kScenes{"point_mass", "box", "tshape", "circle"};
const std::vector<std::string> kMappings{"seed", "exact", "calibrated", "compensated"};

std::string scene_path(const std::string& name) { return "validation/scenes/" + name + ".toml"; }

Scene load(const std::string& path, const std::vector<Override>& overrides = {}) {
  return load_scene(path, overrides);
}

// --set contact.damping=kelvin_voigt
const std::vector<Override> kKelvinVoigt{
    {"contact.damping", std::string(damping_law_name(DampingLaw::KelvinVoigt))}};
// The agreement goal's runs: --dt 1e-4 --set contact.damping=kelvin_voigt --set contact.c=C
std::vector<Override> goal(const std::string& c) {
  return {{"contact.damping", std::string(damping_law_name(DampingLaw::KelvinVoigt))},
          {"contact.c", c},
          {"sim.dt", "1e-4"}};
}
std::vector<Override> with(std::vector<Override> a, const std::vector<Override>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
const std::vector<Override> kFrictionless{{"contact.mu", "0"}, {"contact.mu_roll", "0"}};

// One case of README.md: the scene on both engines.
ComparisonRow compare(const std::string& s, const std::vector<Override>& overrides,
                      const std::string& mapping = "calibrated",
                      const std::string& geometry = "corners", const std::string& plot = "") {
  return compare_engines(load(scene_path(s), overrides), scene_path(s), mapping, geometry, plot);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void write_page(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  std::fputs(text.c_str(), file.get());
  file.commit();
}

// One line on stderr; whole lines from every thread of the pool.
void progress(const std::string& what) {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  std::cerr << "report: " << what << "\n";
}

// The report's sections timed (plan.hpp, ReportTimings): each call of
// time() adds one task's wall-clock seconds to its section.
class SectionClock {
 public:
  template <class Task>
  void time(const std::string& section, Task&& task) {
    const double start = seconds_since(origin_);
    task();
    const double end = seconds_since(origin_);
    const std::lock_guard<std::mutex> lock(mutex_);
    for (SectionTime& s : timings_.sections) {
      if (s.name != section) continue;
      s.seconds += end - start;
      s.start = std::min(s.start, start);
      s.end = std::max(s.end, end);
      return;
    }
    timings_.sections.push_back({section, end - start, start, end});
  }
  ReportTimings done() {
    const std::lock_guard<std::mutex> lock(mutex_);
    timings_.total = seconds_since(origin_);
    std::sort(timings_.sections.begin(), timings_.sections.end(),
              [](const SectionTime& a, const SectionTime& b) { return a.start < b.start; });
    return timings_;
  }

 private:
  std::chrono::steady_clock::time_point origin_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  ReportTimings timings_;
};

// One piece of the report's work, run by run_tasks on the report's pool:
// its section (for the timings), and what it runs. A task fills only its
// own, already allocated, place in the results, so the pages come out the
// same whichever thread ran it and in whichever order.
struct Task {
  std::string section;
  std::function<void()> run;
};
using Tasks = std::vector<Task>;

// Runs the tasks on `jobs` threads (analysis::parallel_for: 0 is one per
// core), handed out in their order, task 0 on this thread; after a task
// fails no other one starts, and the first failure is rethrown once the
// running ones end.
void run_tasks(const Tasks& tasks, unsigned jobs, SectionClock& clock) {
  std::atomic<bool> failed{false};
  analysis::parallel_for(tasks.size(), jobs, [&](size_t i) {
    if (failed.load()) return;
    try {
      clock.time(tasks[i].section, tasks[i].run);
    } catch (...) {
      failed.store(true);
      throw;
    }
  });
}

// ------------------------------------------------------------ README.md

// The models, and every scene under every mapping as shipped and with the
// Kelvin–Voigt law (sections 1 and 8).
void mapping_tasks(const ReportRequest& o, bool v3, ReadmeData& d, Tasks& tasks) {
  tasks.push_back({"models", [&o] {
                     progress("models");
                     for (const std::string& s : kScenes) {
                       for (const std::string& m : kMappings) {
                         write_model(load(scene_path(s)), scene_path(s), m,
                                     o.models + "/" + s + "." + m + ".xml");
                       }
                     }
                   }});
  for (const std::string& s : kScenes) {
    for (const std::string& m : kMappings) {
      d.shipped.push_back({s, m, {}});
      d.kelvin_voigt.push_back({s, m, {}});
    }
  }
  if (v3) d.kelvin_voigt_v3 = d.kelvin_voigt;
  for (size_t i = 0; i < d.shipped.size(); ++i) {
    // The plots of section 8: the default mapping.
    const bool plotted = d.shipped[i].mapping == "calibrated";
    const std::string s = d.shipped[i].scene;
    for (const bool kv : {false, true}) {
      MappingCase& c = (kv ? d.kelvin_voigt : d.shipped)[i];
      const std::string plot =
          plotted ? o.out + "/" + s + (kv ? ".kelvin_voigt.png" : ".shipped.png") : "";
      // With the Kelvin–Voigt law, MuJoCo 3.14 too (section 2, In short).
      MappingCase* c3 = kv && v3 ? &d.kelvin_voigt_v3[i] : nullptr;
      tasks.push_back({"mappings", [&c, c3, plot, kv] {
                         progress("README.md: " + c.scene + ", " + c.mapping + " mapping" +
                                  (kv ? ", Kelvin–Voigt" : ""));
                         if (!c3) {
                           c.result = compare(c.scene, kv ? kKelvinVoigt : std::vector<Override>{},
                                              c.mapping, "corners", plot);
                           return;
                         }
                         const VersionsComparison both =
                             compare_versions(load(scene_path(c.scene), kKelvinVoigt),
                                              scene_path(c.scene), c.mapping, "corners", plot);
                         c.result = both.v2;
                         c3->result = both.v3;
                         c3->v2_vs_v3 = both.apart;
                       }});
    }
  }
}

// A scene whose two laws agree to the bit keeps one plot.
void drop_law_independent_plots(const ReportRequest& o, ReadmeData& d) {
  for (const std::string& s : kScenes) {
    const ComparisonRow* shipped = nullptr;
    const ComparisonRow* kv = nullptr;
    for (const MappingCase& c : d.shipped)
      if (c.scene == s && c.mapping == "calibrated") shipped = &c.result;
    for (const MappingCase& c : d.kelvin_voigt)
      if (c.scene == s && c.mapping == "calibrated") kv = &c.result;
    if (shipped && kv && shipped->max_pos == kv->max_pos && shipped->rms_pos == kv->rms_pos &&
        shipped->max_angle == kv->max_angle && shipped->max_vel == kv->max_vel &&
        shipped->end_pos == kv->end_pos) {
      d.law_independent.push_back(s);
      fs::remove(o.out + "/" + s + ".kelvin_voigt.png");
    }
  }
}

// The three-way comparisons with their diagnoses, as shipped (their runs
// kept in `runs` for the animations) and with the Kelvin–Voigt law.
void three_way_tasks(bool v3, ReadmeData& d, std::vector<ThreeWayRuns>& runs, Tasks& tasks) {
  d.named_share = named_share();
  d.three_way.resize(2 * kScenes.size());
  runs.resize(kScenes.size());
  for (size_t i = 0; i < 2 * kScenes.size(); ++i) {
    tasks.push_back({"three-way", [&d, &runs, i, v3] {
                       const std::string& s = kScenes[i / 2];
                       const bool kv = i % 2 == 1;
                       progress("three-way comparison: " + s + (kv ? ", Kelvin–Voigt" : ""));
                       d.three_way[i] = compare_three_way(
                           load(scene_path(s), kv ? kKelvinVoigt : std::vector<Override>{}),
                           scene_path(s), kv ? "Kelvin–Voigt" : "as shipped", d.converged_tol,
                           kv ? nullptr : &runs[i / 2], v3);
                     }});
  }
}

// Each scene's animation as shipped until one cannot be drawn, then the
// reason there is none.
// MuJoCo 3.14's beside it where it differs from 2.2.2's by more than
// rounding (report/numbers.hpp: kVersionsRounding).
void animations(const ReportRequest& o, const std::vector<ThreeWayRuns>& runs, ReadmeData& d) {
  for (size_t i = 0; i < kScenes.size() && d.animation_note.empty(); ++i) {
    progress("animation " + kScenes[i]);
    ThreeWayCase& c = d.three_way[2 * i];
    d.animation_note = animate_three_way(runs[i], o.out + "/" + kScenes[i] + ".gif", c);
    if (d.animation_note.empty() && versions_differ(c.v2_vs_v3))
      d.animation_note =
          animate_three_way(runs[i], o.out + "/" + kScenes[i] + ".mujoco3.gif", c, true);
  }
}

// The agreement goal at c = 200 and 1000, without and with friction.
// A goal case on both versions (with `v3`) or on 2.2.2.
void goal_run(GoalCase& g, const std::string& s, const std::vector<Override>& overrides, bool v3) {
  if (!v3) {
    g.result = compare(s, overrides);
    return;
  }
  const VersionsComparison both =
      compare_versions(load(scene_path(s), overrides), scene_path(s), "calibrated", "corners");
  g.result = both.v2;
  g.v3_max_pos = both.v3.max_pos;
  g.v3_max_angle = both.v3.max_angle;
  g.v2_vs_v3 = both.apart;
}

void goal_tasks(bool v3, ReadmeData& d, Tasks& tasks) {
  for (const std::string c : {"200", "1000"}) {
    for (const std::string& s : kScenes)
      d.goals.push_back({s + ", c = " + c + ", frictionless", 1e-5, 1e-4, {}});
    for (const std::string& s : kScenes) {
      const double pos_goal = s == "point_mass" || s == "circle" ? 1e-3 : 3e-3;
      d.goals.push_back({s + ", c = " + c + ", friction", pos_goal, std::nullopt, {}});
    }
    const std::string no_roll = "circle, c = " + c + ", friction, no rolling resistance";
    d.goals.push_back({no_roll, 1e-3, std::nullopt, {}});
  }
  size_t next = 0;
  for (const std::string c : {"200", "1000"}) {
    for (const std::string& s : kScenes) {
      tasks.push_back({"goals", [&g = d.goals[next++], s, c, v3] {
                         progress("goal: " + g.label);
                         goal_run(g, s, with(goal(c), kFrictionless), v3);
                       }});
    }
    for (const std::string& s : kScenes) {
      tasks.push_back({"goals", [&g = d.goals[next++], s, c, v3] {
                         progress("goal: " + g.label);
                         goal_run(g, s, goal(c), v3);
                         add_friction_parts(load(scene_path(s), goal(c)), "calibrated", g, v3);
                       }});
    }
    tasks.push_back({"goals", [&g = d.goals[next++], c, v3] {
                       progress("goal: " + g.label);
                       goal_run(g, "circle", with(goal(c), {{"contact.mu_roll", "0"}}), v3);
                     }});
  }
}

// The geometries of the box and the T; the integrators.
void geometry_and_integrator_tasks(ReadmeData& d, Tasks& tasks) {
  for (const std::string s : {"box", "tshape"}) {
    for (const bool friction : {false, true}) {
      for (const std::string geometry : {"corners", "boxes"})
        d.geometry.push_back({s, friction, geometry, {}});
    }
  }
  for (GeometryCase& g : d.geometry) {
    tasks.push_back({"goals", [&g] {
                       progress("geometry: " + g.scene + ", " + g.geometry);
                       const auto overrides =
                           g.friction ? goal("200") : with(goal("200"), kFrictionless);
                       g.result = compare(g.scene, overrides, "calibrated", g.geometry);
                     }});
  }
  for (const std::string& s : kScenes) {
    for (const std::string integrator : {"semi_implicit_euler", "rk4", "implicit_euler"})
      d.integrators.push_back({s, integrator, {}});
  }
  for (IntegratorCase& c : d.integrators) {
    tasks.push_back({"goals", [&c] {
                       progress("integrator: " + c.scene + ", " + c.integrator);
                       const auto overrides =
                           with(with(goal("200"), kFrictionless),
                                {{"sim.integrator", "\"" + c.integrator + "\""}});
                       c.result = compare(c.scene, overrides);
                     }});
  }
}

void write_random_scenes(const ReportRequest& o, const std::vector<RandomScene>& randoms) {
  std::error_code ec;
  fs::create_directories(o.out + "/random", ec);
  for (const RandomScene& r : randoms) {
    write_page(o.out + "/random/" + r.name + ".toml",
               scene_to_toml(r.scene, "Random scene " + r.name + " of contact2d report (seed " +
                                          std::to_string(o.seed) +
                                          "). Without friction: --set contact.mu=0"));
  }
}

// friction.md's scenes as files (OUT/friction/NAME.toml), so that the
// front page's damper figures re-run with `contact2d compare`.
void write_friction_scenes(const ReportRequest& o) {
  std::error_code ec;
  fs::create_directories(o.out + "/friction", ec);
  for (const analysis::FrictionScene& f : friction_scene_list()) {
    write_page(o.out + "/friction/" + f.name + ".toml",
               scene_to_toml(f.scene,
                             "Scene " + f.name + " of friction.md (contact2d report): " + f.what));
  }
}

// The seeded random scenes, each also as a file (OUT/random/NAME.toml) so
// that a row can be re-run on its own, under the calibrated and the
// compensated mapping.
void random_tasks(const ReportRequest& o, bool v3, ReadmeData& d, Tasks& tasks) {
  d.random_config = {o.seed, kRandomSceneCount, 1e-5, 1e-4};
  auto randoms = std::make_shared<const std::vector<RandomScene>>(
      draw_random_scenes(o.seed, d.random_config.count));
  d.random_dir = o.out + "/random";
  d.random.resize(randoms->size());
  d.random_compensated.resize(randoms->size());
  if (v3) {
    d.random_v3.resize(randoms->size());
    d.random_compensated_v3.resize(randoms->size());
  }
  tasks.push_back({"random scenes", [&o, randoms] { write_random_scenes(o, *randoms); }});
  for (size_t i = 0; i < randoms->size(); ++i) {
    for (const bool compensated : {false, true}) {
      RandomCase& out = (compensated ? d.random_compensated : d.random)[i];
      RandomCase* out_v3 = v3 ? &(compensated ? d.random_compensated_v3 : d.random_v3)[i] : nullptr;
      tasks.push_back({"random scenes", [&out, out_v3, randoms, i, compensated] {
                         const RandomScene& r = (*randoms)[i];
                         progress("random scene " + r.name);
                         out = compare_random_scene(r, compensated ? "compensated" : "calibrated",
                                                    out_v3);
                       }});
    }
  }
}

void readme_tasks(const ReportRequest& o, bool v3, ReadmeData& d, std::vector<ThreeWayRuns>& runs,
                  Tasks& tasks) {
  d.scenes = kScenes;
  d.mappings = kMappings;
  mapping_tasks(o, v3, d, tasks);
  tasks.push_back({"goal replay", [&o, &d] {
                     progress("the goal replay on both engines");
                     d.replay = replay_on_both("validation/replays/goal.replay",
                                               o.out + "/goal_replay.png");
                   }});
  three_way_tasks(v3, d, runs, tasks);
  goal_tasks(v3, d, tasks);
  geometry_and_integrator_tasks(d, tasks);
  random_tasks(o, v3, d, tasks);
}

// ------------------------------------------- sweep.md, stability.md, extreme.md

// Each sweep on one thread of the report's pool (the other runs beside it,
// as the sweep's own two threads did).
void sweep_tasks(const ReportRequest& o, bool mujoco, SweepData& sweep, Tasks& tasks) {
  sweep.mujoco = mujoco;
  sweep.engines = mujoco ? "ref,mujoco" : "ref";
  sweep.mujoco_dts = "1e-3,5e-4,2e-4,1e-4";
  sweep.scenes = kScenes;
  SweepRequest request;
  request.engines =
      mujoco ? std::vector<std::string>{"ref", "mujoco"} : std::vector<std::string>{"ref"};
  request.mujoco_dts = {1e-3, 5e-4, 2e-4, 1e-4};
  request.mujoco_integrators = {"semi_implicit_euler", "rk4"};
  request.repeats = 2;
  request.threads = 1;
  sweep.sweeps.resize(kScenes.size() + 1);
  for (size_t i = 0; i < kScenes.size(); ++i) {
    request.study = true;
    tasks.push_back({"sweeps", [&o, &sweep, request, i] {
                       const std::string& s = kScenes[i];
                       progress("sweep " + s);
                       sweep.sweeps[i] = sweep_scene(load(scene_path(s)), s, request,
                                                     o.out + "/sweep." + s + ".png");
                     }});
  }
  // The point mass with the Kelvin–Voigt law and c = 200, where MuJoCo's
  // model can follow the reference's (README.md, section 2).
  request.study = false;
  request.integrators = {"semi_implicit_euler", "rk4", "implicit_euler"};
  tasks.push_back({"sweeps", [&o, &sweep, request] {
                     progress("sweep point_mass_kv");
                     sweep.sweeps.back() = sweep_scene(
                         load(scene_path("point_mass"), with(kKelvinVoigt, {{"contact.c", "200"}})),
                         "point_mass_kv", request, o.out + "/sweep.point_mass_kv.png");
                   }});
}

void stability_tasks(const ReportRequest& o, bool mujoco, StabilityData& stability, Tasks& tasks) {
  stability.mujoco = mujoco;
  stability.scenes = kScenes;
  stability.reference.resize(kScenes.size());
  for (size_t i = 0; i < kScenes.size(); ++i) {
    tasks.push_back({"stability", [&o, &stability, i] {
                       const std::string& s = kScenes[i];
                       progress("stability " + s);
                       StabilityRequest r;
                       r.zeta = 1.0;
                       r.threads = 1;
                       stability.reference[i] = stability_map(load(scene_path(s)), s, r,
                                                              o.out + "/stability." + s + ".png");
                     }});
  }
  tasks.push_back({"stability", [&o, &stability] {
                     progress("stability point_mass_scene_c");
                     StabilityRequest r;
                     r.threads = 1;
                     stability.scene_c =
                         stability_map(load(scene_path("point_mass")), "point_mass_scene_c", r,
                                       o.out + "/stability.point_mass_scene_c.png");
                   }});
  if (!mujoco) return;
  stability.mujoco_scenes = {"point_mass", "box"};
  stability.mujoco_maps.resize(stability.mujoco_scenes.size());
  for (size_t i = 0; i < stability.mujoco_scenes.size(); ++i) {
    tasks.push_back({"stability", [&o, &stability, i] {
                       const std::string& s = stability.mujoco_scenes[i];
                       progress("stability MuJoCo " + s);
                       StabilityRequest r;
                       r.engines = {"mujoco", "mujoco:exact"};
                       r.ks = {1e4, 1e6, 1e8};
                       r.zeta = 1.0;
                       r.threads = 1;
                       stability.mujoco_maps[i] = stability_map(
                           load(scene_path(s), {{"sim.duration", "0.7"}}), "mujoco." + s, r,
                           o.out + "/stability.mujoco." + s + ".png");
                     }});
  }
}

std::vector<std::string> extreme_files() {
  glob_t g{};
  std::vector<std::string> files;
  if (::glob("validation/scenes/extreme/*.toml", 0, nullptr, &g) == 0) {
    for (size_t i = 0; i < g.gl_pathc; ++i) files.push_back(g.gl_pathv[i]);
  }
  ::globfree(&g);
  return files;  // glob sorts them
}

// The `# expect: ` lines of a scene file.
std::vector<std::string> expectations(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  const std::string mark = "# expect: ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(mark, 0) == 0) lines.push_back(line.substr(mark.size()));
  }
  return lines;
}

void extreme_tasks(bool mujoco, ExtremeData& extreme, Tasks& tasks) {
  for (const std::string& path : extreme_files())
    extreme.cases.push_back({path, expectations(path), {}, std::nullopt});
  for (ExtremeCase& c : extreme.cases) {
    tasks.push_back({"extreme", [&c, mujoco] {
                       progress("extreme " + c.path);
                       c.ref = simulate_outcome(c.path, "ref");
                       if (mujoco) c.mujoco = simulate_outcome(c.path, "mujoco");
                     }});
  }
}

// The per-step cost (stability.md, section 6), when there is a bench: run
// alone, after every other run, so that nothing of the report's shares the
// machine with it; 0.05 s a benchmark bounds it to ~3 s (0.2 s took ~10 s
// on one core while the other idled). Its ratios carry the shared
// machine's ±30 % either way (docs/speed.md).
void bench_runs(const ReportRequest& o, SweepData& sweep) {
  if (o.bench.empty() || ::access(o.bench.c_str(), X_OK) != 0) return;
  progress("bench");
  sweep.bench = run_bench(o.bench, "0.05");
  for (const std::string& s : kScenes) {
    if (points_turn(load(scene_path(s)))) sweep.bench.turning.push_back(s);
  }
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

// Everything the pages show, filled by the tasks.
struct Results {
  ReadmeData readme;
  SweepData sweep;
  StabilityData stability;
  ExtremeData extreme;
  analysis::ClosedFormTable closed_forms;
  std::vector<analysis::FrictionRow> friction;
  std::vector<analysis::VersionTable> versions;  // one per scene
  AtlasRun atlas;
  std::vector<ThreeWayRuns> three_way;  // as shipped, for the animations
  RealImpactsData real_impacts;
};

// real_impacts.md: the fit against the recorded ellipse impacts, one task
// (its replays on one thread; about two minutes of it).
void real_impacts_task(const ReportRequest& o, bool mujoco, Results& r, Tasks& tasks) {
  tasks.push_back({"real impacts", [&o, &r, mujoco] {
                     const std::string recording = "validation/real/ellipse/recording.toml";
                     progress("real impacts " + recording);
                     r.real_impacts = real_impacts_run(recording, o.out, mujoco);
                   }});
}

// closed_forms.md and friction.md.
void table_tasks(Results& r, Tasks& tasks) {
  tasks.push_back({"closed forms", [&r] {
                     progress("closed forms");
                     r.closed_forms = closed_form_rows(1);
                   }});
  tasks.push_back({"friction", [&r] {
                     progress("friction");
                     r.friction = friction_rows(1);
                   }});
}

// After the three-way comparisons: their animations, the pool's first task,
// on the thread that called write_report (a GLFW window must be drawn
// there), beside versions.md and the atlas's heat maps.
void last_tasks(const ReportRequest& o, bool mujoco, Results& r, Tasks& tasks) {
  tasks.push_back({"animations", [&o, &r] { animations(o, r.three_way, r.readme); }});
  // versions.md: MuJoCo 3.14 beside 2.2.2 on the four bodies with the
  // Kelvin–Voigt damper both have; a scene a task, each on the one Node
  // process of the thread that runs it.
  r.versions.resize(kScenes.size(), analysis::VersionTable{{}, "built without MuJoCo"});
  for (size_t i = 0; mujoco && i < kScenes.size(); ++i) {
    tasks.push_back({"versions", [&r, i] {
                       const std::string& s = kScenes[i];
                       progress("versions " + s);
                       r.versions[i] = version_rows({{s, load(scene_path(s), kKelvinVoigt)}}, 1);
                     }});
  }
  tasks.push_back({"atlas plots", [&o, &r] {
                     progress("atlas heat maps");
                     draw_atlas(r.atlas, o.out, "atlas.");
                   }});
}

analysis::VersionTable joined(const std::vector<analysis::VersionTable>& parts) {
  analysis::VersionTable all;
  for (const analysis::VersionTable& part : parts) {
    if (!part.not_run.empty()) return part;
    all.rows.insert(all.rows.end(), part.rows.begin(), part.rows.end());
  }
  return all;
}

// MuJoCo 3.14's friction damper on the front page: where it helps most
// (friction.md's scenes: 3.14 compensated without and with it) and where
// it hurts most (the built-in scenes with friction, versions.md's rows).
void damper_cases(const ReportRequest& o, Results& r) {
  double best = 0.0, worst = 0.0;
  for (const analysis::FrictionRow& f : r.friction) {
    const double without = f.mujoco3_compensated.max_pos, with = f.mujoco3_damper.max_pos;
    if (!(with > 0.0) || !(without / with > best)) continue;
    best = without / with;
    r.readme.damper_helps = {
        {f.what, "contact2d compare " + o.out + "/friction/" + f.name + ".toml", without, with}};
  }
  for (const analysis::VersionTable& t : r.versions) {
    for (const analysis::VersionRow& v : t.rows) {
      if (!(v.ref_v3 > 0.0) || !(v.ref_v3_damper / v.ref_v3 > worst)) continue;
      worst = v.ref_v3_damper / v.ref_v3;
      r.readme.damper_hurts = {
          {"the built-in " + v.scene + " with the Kelvin–Voigt law",
           "contact2d compare " + scene_path(v.scene) + " --set contact.damping=kelvin_voigt",
           v.ref_v3, v.ref_v3_damper}};
    }
  }
}

// Longest first, so that the pool's threads end together: the tasks of the
// sections that take longest (measured by scripts/report-timings) go to the
// front, each section's own tasks in their order; the first task stays
// first (it may have to run on this thread).
void longest_first(Tasks& tasks) {
  if (tasks.empty()) return;
  const std::vector<std::string> order{"real impacts",  "three-way", "sweeps",      "stability",
                                       "friction",      "versions",  "atlas plots", "goals",
                                       "random scenes", "mappings",  "extreme",     "goal replay",
                                       "closed forms",  "models"};
  auto rank = [&](const Task& t) {
    return std::find(order.begin(), order.end(), t.section) - order.begin();
  };
  std::stable_sort(tasks.begin() + 1, tasks.end(),
                   [&](const Task& a, const Task& b) { return rank(a) < rank(b); });
}

void write_pages(const ReportRequest& o, const Results& r) {
  const std::vector<std::string>& names = page_names();
  write_page(o.out + "/" + names[0], readme_page(r.readme));
  write_page(o.out + "/" + names[1], sweep_page(r.sweep));
  write_page(o.out + "/" + names[2], stability_page(r.stability, r.sweep.bench));
  write_page(o.out + "/" + names[3], extreme_page(r.extreme));
  write_page(o.out + "/" + names[4], closed_forms_page(r.closed_forms));
  write_page(o.out + "/" + names[5], friction_page(r.friction, 1e-3));
  write_page(o.out + "/" + names[6], atlas_page(r.atlas.summary, r.atlas.info));
  write_page(o.out + "/" + names[7], versions_page(joined(r.versions)));
  write_page(o.out + "/" + names[8], real_impacts_page(r.real_impacts));
}

}  // namespace

const std::vector<std::string>& page_names() {
  static const std::vector<std::string> names{"README.md",  "sweep.md",        "stability.md",
                                              "extreme.md", "closed_forms.md", "friction.md",
                                              "atlas.md",   "versions.md",     "real_impacts.md"};
  return names;
}

// First the atlas on its own threads (its page states their number), then
// every other run on the report's pool (the animations, versions.md and the
// atlas's heat maps after the rest), then the bench alone (so that no run of
// the report disturbs its timings), then the pages.
ReportTimings write_report(const ReportRequest& o) {
  SectionClock clock;
  const bool mujoco = mujoco_built();
  Results r;
  // atlas.md: the small default atlas (its rows in OUT/atlas/).
  clock.time("atlas", [&] {
    progress("atlas validation/atlas/default.toml");
    run_atlas("validation/atlas/default.toml", o.out + "/atlas", r.atlas);
  });
  Tasks tasks;
  // MuJoCo 3.14 beside 2.2.2 on the front page, when it can run here.
  r.readme.mujoco3_not_run = mujoco ? mujoco3_missing() : "built without MuJoCo";
  const bool v3 = r.readme.mujoco3_not_run.empty();
  readme_tasks(o, v3, r.readme, r.three_way, tasks);
  if (v3) tasks.push_back({"friction", [&o] { write_friction_scenes(o); }});
  sweep_tasks(o, mujoco, r.sweep, tasks);
  stability_tasks(o, mujoco, r.stability, tasks);
  extreme_tasks(mujoco, r.extreme, tasks);
  table_tasks(r, tasks);
  real_impacts_task(o, mujoco, r, tasks);
  longest_first(tasks);
  run_tasks(tasks, o.jobs, clock);
  Tasks last;
  last_tasks(o, mujoco, r, last);
  longest_first(last);
  run_tasks(last, o.jobs, clock);
  drop_law_independent_plots(o, r.readme);
  if (v3) damper_cases(o, r);
  clock.time("bench", [&] { bench_runs(o, r.sweep); });

  const ReportTimings so_far = clock.done();
  RunInfo& info = r.sweep.info;
  info.cores = std::thread::hardware_concurrency();
  info.load = load_average();
  for (const SectionTime& s : so_far.sections) {
    if (s.name == "sweeps") info.sweep_seconds = static_cast<long long>(s.seconds);
    if (s.name == "stability") info.stability_seconds = static_cast<long long>(s.seconds);
  }
  info.total_seconds = static_cast<long long>(so_far.total);
  // Each page written as soon as it is made, in the order of page_names().
  clock.time("pages", [&] { write_pages(o, r); });
  return clock.done();
}

}  // namespace contact2d::report
