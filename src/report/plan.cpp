// The plan of `contact2d report` (report/plan.hpp): the scenes, the
// overrides of each case and the order of the runs, section by section of
// the pages, and then the pages. Every run is a call of the seam
// (report/runs.hpp); this file reads scene files and writes pages only.
#include "report/plan.hpp"

#include <glob.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

#include "io/atomic_file.hpp"
#include "io/scene_file.hpp"
#include "io/scene_writer.hpp"
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
Comparison compare(const std::string& s, const std::vector<Override>& overrides,
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

void progress(const std::string& what) { std::cerr << "report: " << what << "\n"; }

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

// ------------------------------------------------------------ README.md

// The models, and every scene under every mapping as shipped and with the
// Kelvin–Voigt law (sections 1 and 8); a scene whose two laws agree to the
// bit keeps one plot.
void write_models(const ReportRequest& o) {
  progress("models");
  for (const std::string& s : kScenes) {
    for (const std::string& m : kMappings) {
      write_model(load(scene_path(s)), scene_path(s), m, o.models + "/" + s + "." + m + ".xml");
    }
  }
}

void mapping_runs(const ReportRequest& o, ReadmeData& d) {
  progress("README.md: every scene under every mapping");
  for (const std::string& s : kScenes) {
    for (const std::string& m : kMappings) {
      const bool plotted = m == "calibrated";  // the plots of section 8: the default mapping
      d.shipped.push_back(
          {s, m, compare(s, {}, m, "corners", plotted ? o.out + "/" + s + ".shipped.png" : "")});
      d.kelvin_voigt.push_back({s, m,
                                compare(s, kKelvinVoigt, m, "corners",
                                        plotted ? o.out + "/" + s + ".kelvin_voigt.png" : "")});
    }
  }
  for (const std::string& s : kScenes) {
    const Comparison* shipped = nullptr;
    const Comparison* kv = nullptr;
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

// The three-way comparisons with their diagnoses; the first scene's
// animation, or the reason there is none.
void three_way_runs(const ReportRequest& o, ReadmeData& d) {
  progress("three-way comparisons, diagnoses and animations");
  d.named_share = named_share();
  for (const std::string& s : kScenes) {
    std::string failure;
    const std::string video = d.animation_note.empty() ? o.out + "/" + s + ".gif" : "";
    d.three_way.push_back(compare_three_way(load(scene_path(s)), scene_path(s), "as shipped",
                                            d.converged_tol, video, failure));
    if (!failure.empty()) d.animation_note = failure;
    d.three_way.push_back(compare_three_way(load(scene_path(s), kKelvinVoigt), scene_path(s),
                                            "Kelvin–Voigt", d.converged_tol, "", failure));
  }
}

// The agreement goal at c = 200 and 1000, without and with friction; the
// geometries of the box and the T; the integrators.
void goal_runs(ReadmeData& d) {
  for (const std::string c : {"200", "1000"}) {
    for (const std::string& s : kScenes) {
      d.goals.push_back({s + ", c = " + c + ", frictionless", 1e-5, 1e-4,
                         compare(s, with(goal(c), kFrictionless))});
    }
    for (const std::string& s : kScenes) {
      const double pos_goal = s == "point_mass" || s == "circle" ? 1e-3 : 3e-3;
      GoalCase g{s + ", c = " + c + ", friction", pos_goal, std::nullopt, compare(s, goal(c))};
      add_friction_parts(load(scene_path(s), goal(c)), "calibrated", g);
      d.goals.push_back(g);
    }
    d.goals.push_back({"circle, c = " + c + ", friction, no rolling resistance", 1e-3, std::nullopt,
                       compare("circle", with(goal(c), {{"contact.mu_roll", "0"}}))});
  }
  for (const std::string s : {"box", "tshape"}) {
    for (const bool friction : {false, true}) {
      for (const std::string geometry : {"corners", "boxes"}) {
        const auto overrides = friction ? goal("200") : with(goal("200"), kFrictionless);
        d.geometry.push_back(
            {s, friction, geometry, compare(s, overrides, "calibrated", geometry)});
      }
    }
  }
  for (const std::string& s : kScenes) {
    for (const std::string integrator : {"semi_implicit_euler", "rk4", "implicit_euler"}) {
      const auto overrides =
          with(with(goal("200"), kFrictionless), {{"sim.integrator", "\"" + integrator + "\""}});
      d.integrators.push_back({s, integrator, compare(s, overrides)});
    }
  }
}

// The seeded random scenes, each also as a file (OUT/random/NAME.toml) so
// that a row can be re-run on its own.
void random_runs(const ReportRequest& o, ReadmeData& d) {
  d.random_config = {o.seed, kRandomSceneCount, 1e-5, 1e-4};
  const std::vector<RandomScene> randoms = draw_random_scenes(o.seed, d.random_config.count);
  d.random_dir = o.out + "/random";
  std::error_code ec;
  fs::create_directories(o.out + "/random", ec);
  for (const RandomScene& r : randoms) {
    write_page(o.out + "/random/" + r.name + ".toml",
               scene_to_toml(r.scene, "Random scene " + r.name + " of contact2d report (seed " +
                                          std::to_string(o.seed) +
                                          "). Without friction: --set contact.mu=0"));
  }
  compare_random_scenes(randoms, d.random, d.random_compensated);
}

ReadmeData readme_runs(const ReportRequest& o, SectionClock& clock) {
  ReadmeData d;
  d.scenes = kScenes;
  d.mappings = kMappings;
  clock.time("models", [&] { write_models(o); });
  clock.time("mappings", [&] { mapping_runs(o, d); });
  clock.time("goal replay", [&] {
    progress("the goal replay on both engines");
    d.replay = replay_on_both("validation/replays/goal.replay", o.out + "/goal_replay.png");
  });
  clock.time("three-way", [&] { three_way_runs(o, d); });
  clock.time("goals", [&] {
    progress("the agreement goals, geometries and integrators");
    goal_runs(d);
  });
  clock.time("random scenes", [&] {
    progress("random scenes");
    random_runs(o, d);
  });
  return d;
}

// ------------------------------------------- sweep.md, stability.md, extreme.md

void sweep_runs(const ReportRequest& o, bool mujoco, SweepData& sweep) {
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
  for (const std::string& s : kScenes) {
    progress("sweep " + s);
    request.study = true;
    sweep.sweeps.push_back(
        sweep_scene(load(scene_path(s)), s, request, o.out + "/sweep." + s + ".png"));
  }
  // The point mass with the Kelvin–Voigt law and c = 200, where MuJoCo's
  // model can follow the reference's (README.md, section 2).
  progress("sweep point_mass_kv");
  request.study = false;
  request.integrators = {"semi_implicit_euler", "rk4", "implicit_euler"};
  sweep.sweeps.push_back(
      sweep_scene(load(scene_path("point_mass"), with(kKelvinVoigt, {{"contact.c", "200"}})),
                  "point_mass_kv", request, o.out + "/sweep.point_mass_kv.png"));
}

void stability_runs(const ReportRequest& o, bool mujoco, StabilityData& stability) {
  stability.mujoco = mujoco;
  stability.scenes = kScenes;
  for (const std::string& s : kScenes) {
    progress("stability " + s);
    StabilityRequest r;
    r.zeta = 1.0;
    stability.reference.push_back(
        stability_map(load(scene_path(s)), s, r, o.out + "/stability." + s + ".png"));
  }
  stability.scene_c = stability_map(load(scene_path("point_mass")), "point_mass_scene_c", {},
                                    o.out + "/stability.point_mass_scene_c.png");
  if (mujoco) {
    stability.mujoco_scenes = {"point_mass", "box"};
    for (const std::string& s : stability.mujoco_scenes) {
      progress("stability MuJoCo " + s);
      StabilityRequest r;
      r.engines = {"mujoco", "mujoco:exact"};
      r.ks = {1e4, 1e6, 1e8};
      r.zeta = 1.0;
      stability.mujoco_maps.push_back(stability_map(load(scene_path(s), {{"sim.duration", "0.7"}}),
                                                    "mujoco." + s, r,
                                                    o.out + "/stability.mujoco." + s + ".png"));
    }
  }
}

// The per-step cost (stability.md, section 6), when there is a bench.
void bench_runs(const ReportRequest& o, SweepData& sweep) {
  if (o.bench.empty() || ::access(o.bench.c_str(), X_OK) != 0) return;
  progress("bench");
  sweep.bench = run_bench(o.bench, "0.2");
  for (const std::string& s : kScenes) {
    if (points_turn(load(scene_path(s)))) sweep.bench.turning.push_back(s);
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

ExtremeData extreme_runs(bool mujoco) {
  ExtremeData extreme;
  for (const std::string& path : extreme_files()) {
    progress("extreme " + path);
    extreme.cases.push_back(
        {path, expectations(path), simulate_outcome(path, "ref"),
         mujoco ? std::optional(simulate_outcome(path, "mujoco")) : std::nullopt});
  }
  return extreme;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace

const std::vector<std::string>& page_names() {
  static const std::vector<std::string> names{"README.md",  "sweep.md",        "stability.md",
                                              "extreme.md", "closed_forms.md", "friction.md",
                                              "atlas.md",   "versions.md"};
  return names;
}

ReportTimings write_report(const ReportRequest& o) {
  SectionClock clock;
  const bool mujoco = mujoco_built();
  const ReadmeData readme = readme_runs(o, clock);

  const auto start = std::chrono::steady_clock::now();
  SweepData sweep;
  clock.time("sweeps", [&] { sweep_runs(o, mujoco, sweep); });
  const double sweep_seconds = seconds_since(start);
  StabilityData stability;
  clock.time("stability", [&] { stability_runs(o, mujoco, stability); });
  const double stability_seconds = seconds_since(start) - sweep_seconds;
  clock.time("bench", [&] { bench_runs(o, sweep); });
  ExtremeData extreme;
  clock.time("extreme", [&] { extreme = extreme_runs(mujoco); });
  analysis::ClosedFormTable closed_forms;
  clock.time("closed forms", [&] {
    progress("closed forms");
    closed_forms = closed_form_rows();
  });
  std::vector<analysis::FrictionRow> friction;
  clock.time("friction", [&] {
    progress("friction");
    friction = friction_rows();
  });
  // versions.md: MuJoCo 3.14 beside 2.2.2 on the four bodies with the
  // Kelvin–Voigt damper both have.
  analysis::VersionTable versions;
  clock.time("versions", [&] {
    progress("versions");
    std::vector<analysis::NamedScene> version_scenes;
    version_scenes.reserve(kScenes.size());
    for (const std::string& s : kScenes)
      version_scenes.push_back({s, load(scene_path(s), kKelvinVoigt)});
    versions =
        mujoco ? version_rows(version_scenes) : analysis::VersionTable{{}, "built without MuJoCo"};
  });
  // atlas.md: the small default atlas (its rows in OUT/atlas/).
  AtlasRun atlas;
  clock.time("atlas", [&] {
    progress("atlas validation/atlas/default.toml");
    run_atlas("validation/atlas/default.toml", o.out + "/atlas", atlas);
  });
  clock.time("atlas plots", [&] { draw_atlas(atlas, o.out, "atlas."); });
  sweep.info.cores = std::thread::hardware_concurrency();
  sweep.info.load = load_average();
  sweep.info.sweep_seconds = static_cast<long long>(sweep_seconds);
  sweep.info.stability_seconds = static_cast<long long>(stability_seconds);
  sweep.info.total_seconds = static_cast<long long>(seconds_since(start));

  // Each page written as soon as it is made, in the order of page_names().
  clock.time("pages", [&] {
    const std::vector<std::string>& names = page_names();
    write_page(o.out + "/" + names[0], readme_page(readme));
    write_page(o.out + "/" + names[1], sweep_page(sweep));
    write_page(o.out + "/" + names[2], stability_page(stability, sweep.bench));
    write_page(o.out + "/" + names[3], extreme_page(extreme));
    write_page(o.out + "/" + names[4], closed_forms_page(closed_forms));
    write_page(o.out + "/" + names[5], friction_page(friction, 1e-3));
    write_page(o.out + "/" + names[6], atlas_page(atlas.summary, atlas.info));
    write_page(o.out + "/" + names[7], versions_page(versions));
  });
  return clock.done();
}

}  // namespace contact2d::report
