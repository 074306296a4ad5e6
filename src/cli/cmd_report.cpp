// contact2d report [--out DIR] [--models DIR | --snapshot] [--bench PATH] [--seed N]
//
// Writes every page of validation/report/ — README.md (the reference against
// MuJoCo), sweep.md, stability.md, extreme.md, closed_forms.md — and their PNG plots, and the
// generated MJCF models, from one run. This file is the plan: which scenes,
// with which overrides, through which seam function (report/runs.hpp, the
// only code that runs an engine); the pages are written by report/pages.hpp
// from the structs the seam returns, each through io's AtomicFile. Run it
// from the repository root: scene paths are relative to it (they name the
// scenes in the models and messages, as the CLI's do). Exit status: 0 done,
// 2 bad input (one line, before any run), 3 a run failed (an engine
// diverged, gnuplot or the bench failed): no page is written then.
#include <glob.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "analysis/atlas.hpp"
#include "analysis/closed_forms.hpp"
#include "analysis/comparison.hpp"
#include "analysis/engine.hpp"
#include "analysis/friction_table.hpp"
#include "cli/common.hpp"
#include "io/atomic_file.hpp"
#include "io/scene_file.hpp"
#include "io/scene_writer.hpp"
#include "report/pages.hpp"
#include "report/random_scenes.hpp"
#include "report/runs.hpp"

namespace contact2d::cli {
namespace {

namespace rp = contact2d::report;
namespace fs = std::filesystem;

// By default the report goes to build/ (outside the tracked tree: its pages
// hold wall-clock times); --snapshot writes the committed snapshot,
// validation/report/ and models/.
struct ReportOptions {
  std::string out = "build/report";
  std::string models = "build/report/models";
  bool snapshot = false;
  std::string bench;  // default: bench/contact2d_bench beside this program
  std::uint64_t seed = 20260101;
  OutputOptions outputs;  // --out, --models
};

const std::vector<std::string> kScenes{"point_mass", "box", "tshape", "circle"};
const std::vector<std::string> kMappings{"seed", "exact", "calibrated", "compensated"};

std::string scene_path(const std::string& name) { return "validation/scenes/" + name + ".toml"; }

Scene load(const std::string& path, const std::vector<Override>& overrides = {}) {
  return load_scene(path, overrides);
}

// --set contact.damping=kelvin_voigt
const std::vector<Override> kKelvinVoigt{{"contact.damping", "kelvin_voigt"}};
// The agreement goal's runs: --dt 1e-4 --set contact.damping=kelvin_voigt --set contact.c=C
std::vector<Override> goal(const std::string& c) {
  return {{"contact.damping", "kelvin_voigt"}, {"contact.c", c}, {"sim.dt", "1e-4"}};
}
std::vector<Override> with(std::vector<Override> a, const std::vector<Override>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
const std::vector<Override> kFrictionless{{"contact.mu", "0"}, {"contact.mu_roll", "0"}};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void write_page(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  std::fputs(text.c_str(), file.get());
  file.commit();
}

void progress(const std::string& what) { std::cerr << "report: " << what << "\n"; }

// ------------------------------------------------------------ README.md

rp::ReadmeData readme_runs(const ReportOptions& o) {
  rp::ReadmeData d;
  d.scenes = kScenes;
  d.mappings = kMappings;
  progress("models and README.md");
  for (const std::string& s : kScenes) {
    for (const std::string& m : kMappings) {
      rp::write_model(load(scene_path(s)), scene_path(s), m, o.models + "/" + s + "." + m + ".xml");
    }
  }
  auto compare = [](const std::string& s, const std::vector<Override>& overrides,
                    const std::string& mapping = "calibrated",
                    const std::string& geometry = "corners", const std::string& plot = "") {
    return rp::compare_engines(load(scene_path(s), overrides), scene_path(s), mapping, geometry,
                               plot);
  };
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
    const rp::Comparison* shipped = nullptr;
    const rp::Comparison* kv = nullptr;
    for (const rp::MappingCase& c : d.shipped)
      if (c.scene == s && c.mapping == "calibrated") shipped = &c.result;
    for (const rp::MappingCase& c : d.kelvin_voigt)
      if (c.scene == s && c.mapping == "calibrated") kv = &c.result;
    if (shipped && kv && shipped->max_pos == kv->max_pos && shipped->rms_pos == kv->rms_pos &&
        shipped->max_angle == kv->max_angle && shipped->max_vel == kv->max_vel &&
        shipped->end_pos == kv->end_pos) {
      d.law_independent.push_back(s);
      fs::remove(o.out + "/" + s + ".kelvin_voigt.png");
    }
  }
  progress("the goal replay on both engines");
  d.replay = rp::replay_on_both("validation/replays/goal.replay", o.out + "/goal_replay.png");
  progress("three-way comparisons, diagnoses and animations");
  d.named_share = analysis::kNamedShare;
  for (const std::string& s : kScenes) {
    std::string failure;
    const std::string video = d.animation_note.empty() ? o.out + "/" + s + ".gif" : "";
    d.three_way.push_back(rp::compare_three_way(load(scene_path(s)), scene_path(s), "as shipped",
                                                d.converged_tol, video, failure));
    if (!failure.empty()) d.animation_note = failure;
    d.three_way.push_back(rp::compare_three_way(load(scene_path(s), kKelvinVoigt), scene_path(s),
                                                "Kelvin–Voigt", d.converged_tol, "", failure));
  }
  for (const std::string c : {"200", "1000"}) {
    for (const std::string& s : kScenes) {
      d.goals.push_back({s + ", c = " + c + ", frictionless", 1e-5, 1e-4,
                         compare(s, with(goal(c), kFrictionless))});
    }
    for (const std::string& s : kScenes) {
      const double pos_goal = s == "point_mass" || s == "circle" ? 1e-3 : 3e-3;
      rp::GoalCase g{s + ", c = " + c + ", friction", pos_goal, std::nullopt, compare(s, goal(c))};
      const analysis::FrictionParts parts =
          analysis::friction_parts(load(scene_path(s), goal(c)), "calibrated");
      g.friction_shape = parts.shape;
      g.friction_push = parts.push;
      g.friction_rest = parts.rest;
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
  d.random_config = {o.seed, rp::kRandomSceneCount, 1e-5, 1e-4};
  // Independent scenes: one per core at a time (their run times are not shown).
  const std::vector<rp::RandomScene> randoms =
      rp::draw_random_scenes(o.seed, d.random_config.count);
  d.random.resize(randoms.size());
  // Each random scene as a file, so that a row can be re-run on its own.
  d.random_dir = o.out + "/random";
  std::error_code ec;
  fs::create_directories(o.out + "/random", ec);
  for (const rp::RandomScene& r : randoms) {
    write_page(o.out + "/random/" + r.name + ".toml",
               scene_to_toml(r.scene, "Random scene " + r.name + " of contact2d report (seed " +
                                          std::to_string(o.seed) +
                                          "). Without friction: --set contact.mu=0"));
  }
  d.random_compensated.resize(randoms.size());
  analysis::parallel_for(2 * randoms.size(), 0, [&](size_t job) {
    // Even jobs: calibrated (the default mapping); odd: compensated.
    const size_t i = job / 2;
    const bool compensated = job % 2 == 1;
    const char* const mapping = compensated ? "compensated" : "calibrated";
    const rp::RandomScene& r = randoms[i];
    Scene frictionless = r.scene;
    frictionless.contact.mu = 0.0;
    const std::string source = "random scene " + r.name;
    const rp::Comparison without = rp::compare_engines(frictionless, source, mapping, "corners");
    const rp::Comparison friction = rp::compare_engines(r.scene, source, mapping, "corners");
    const analysis::FrictionParts parts = analysis::friction_parts(r.scene, mapping);
    (compensated ? d.random_compensated : d.random)[i] = {r.name,
                                                          without.shape,
                                                          r.mass,
                                                          r.scene.contact.k,
                                                          r.scene.contact.c,
                                                          r.scene.contact.mu,
                                                          without.max_pos,
                                                          without.max_angle,
                                                          friction.max_pos,
                                                          parts.shape,
                                                          parts.push,
                                                          parts.rest};
  });
  return d;
}

// ------------------------------------------- sweep.md, stability.md, extreme.md

std::vector<std::string> extreme_files() {
  glob_t g{};
  std::vector<std::string> files;
  if (::glob("validation/scenes/extreme/*.toml", 0, nullptr, &g) == 0) {
    for (size_t i = 0; i < g.gl_pathc; ++i) files.push_back(g.gl_pathv[i]);
  }
  ::globfree(&g);
  return files;  // glob sorts them
}

std::vector<std::string> expectations(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  const std::string mark = "# expect: ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(mark, 0) == 0) lines.push_back(line.substr(mark.size()));
  }
  return lines;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

std::string default_bench() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : (self.parent_path() / "bench" / "contact2d_bench").string();
}

int report(const ReportOptions& o) {
  if (!fs::is_directory("validation/scenes")) {
    throw InputError("validation/scenes: not found; run contact2d report from the repository root");
  }
  o.outputs.check();
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (!fs::is_directory(o.out)) throw InputError("--out " + o.out + ": cannot create directory");
  fs::create_directories(o.models, ec);
  if (!fs::is_directory(o.models)) {
    throw InputError("--models " + o.models + ": cannot create directory");
  }
  const std::string bench = o.bench.empty() ? default_bench() : o.bench;
  if (!o.bench.empty() && ::access(bench.c_str(), X_OK) != 0) {
    throw InputError("--bench " + bench + ": not an executable file");
  }
  const bool mujoco = rp::mujoco_built();
  if (!mujoco)
    throw InputError("contact2d report needs MuJoCo (built with CONTACT2D_WITH_MUJOCO=OFF)");

  const rp::ReadmeData readme = readme_runs(o);

  const auto start = std::chrono::steady_clock::now();
  rp::SweepData sweep;
  sweep.mujoco = mujoco;
  sweep.engines = mujoco ? "ref,mujoco" : "ref";
  sweep.mujoco_dts = "1e-3,5e-4,2e-4,1e-4";
  sweep.scenes = kScenes;
  rp::SweepRequest request;
  request.engines =
      mujoco ? std::vector<std::string>{"ref", "mujoco"} : std::vector<std::string>{"ref"};
  request.mujoco_dts = {1e-3, 5e-4, 2e-4, 1e-4};
  request.mujoco_integrators = {"semi_implicit_euler", "rk4"};
  request.repeats = 2;
  for (const std::string& s : kScenes) {
    progress("sweep " + s);
    request.study = true;
    sweep.sweeps.push_back(
        rp::sweep_scene(load(scene_path(s)), s, request, o.out + "/sweep." + s + ".png"));
  }
  // The point mass with the Kelvin–Voigt law and c = 200, where MuJoCo's
  // model can follow the reference's (README.md, section 2).
  progress("sweep point_mass_kv");
  request.study = false;
  request.integrators = {"semi_implicit_euler", "rk4", "implicit_euler"};
  sweep.sweeps.push_back(
      rp::sweep_scene(load(scene_path("point_mass"), with(kKelvinVoigt, {{"contact.c", "200"}})),
                      "point_mass_kv", request, o.out + "/sweep.point_mass_kv.png"));
  const double sweep_seconds = seconds_since(start);

  rp::StabilityData stability;
  stability.mujoco = mujoco;
  stability.scenes = kScenes;
  for (const std::string& s : kScenes) {
    progress("stability " + s);
    rp::StabilityRequest r;
    r.zeta = 1.0;
    stability.reference.push_back(
        rp::stability_map(load(scene_path(s)), s, r, o.out + "/stability." + s + ".png"));
  }
  stability.scene_c = rp::stability_map(load(scene_path("point_mass")), "point_mass_scene_c", {},
                                        o.out + "/stability.point_mass_scene_c.png");
  if (mujoco) {
    stability.mujoco_scenes = {"point_mass", "box"};
    for (const std::string& s : stability.mujoco_scenes) {
      progress("stability MuJoCo " + s);
      rp::StabilityRequest r;
      r.engines = {"mujoco", "mujoco:exact"};
      r.ks = {1e4, 1e6, 1e8};
      r.zeta = 1.0;
      stability.mujoco_maps.push_back(
          rp::stability_map(load(scene_path(s), {{"sim.duration", "0.7"}}), "mujoco." + s, r,
                            o.out + "/stability.mujoco." + s + ".png"));
    }
  }
  const double stability_seconds = seconds_since(start) - sweep_seconds;

  if (!bench.empty() && ::access(bench.c_str(), X_OK) == 0) {
    progress("bench");
    sweep.bench = rp::run_bench(bench, "0.2");
    for (const std::string& s : kScenes) {  // whose force evaluations start with a sincos
      const RigidBody body = make_model(load(scene_path(s))).body;
      if (body.rotates && body.points_rotate) sweep.bench.turning.push_back(s);
    }
  }
  rp::ExtremeData extreme;
  for (const std::string& path : extreme_files()) {
    progress("extreme " + path);
    extreme.cases.push_back(
        {path, expectations(path), rp::simulate_outcome(path, "ref"),
         mujoco ? std::optional(rp::simulate_outcome(path, "mujoco")) : std::nullopt});
  }
  progress("closed forms");
  const analysis::ClosedFormTable closed_forms = analysis::closed_form_table();
  progress("friction");
  const std::vector<analysis::FrictionRow> friction = analysis::friction_table();
  // atlas.md: the small default atlas (its rows in OUT/atlas/).
  progress("atlas validation/atlas/default.toml");
  const AtlasSpec atlas_spec = load_atlas_spec("validation/atlas/default.toml");
  analysis::AtlasRunOptions atlas_options;
  atlas_options.threads = analysis::default_threads();
  const analysis::AtlasRunStats atlas_stats =
      analysis::run_atlas(atlas_spec, o.out + "/atlas", atlas_options);
  const analysis::AtlasData atlas_data = analysis::read_atlas_shards({o.out + "/atlas"});
  analysis::AtlasSummary atlas_summary = analysis::summarize_atlas(atlas_data);
  analysis::draw_atlas_heatmaps(atlas_data, atlas_summary, o.out, "atlas.");
  const rp::AtlasRunInfo atlas_info{"validation/atlas/default.toml", atlas_stats.points,
                                    atlas_options.threads,           atlas_stats.wall_seconds,
                                    atlas_stats.cpu_per_point(),     atlas_stats.points_per_core()};
  sweep.info.cores = std::thread::hardware_concurrency();
  sweep.info.load = load_average();
  sweep.info.sweep_seconds = static_cast<long long>(sweep_seconds);
  sweep.info.stability_seconds = static_cast<long long>(stability_seconds);
  sweep.info.total_seconds = static_cast<long long>(seconds_since(start));

  write_page(o.out + "/README.md", rp::readme_page(readme));
  write_page(o.out + "/sweep.md", rp::sweep_page(sweep));
  write_page(o.out + "/stability.md", rp::stability_page(stability, sweep.bench));
  write_page(o.out + "/extreme.md", rp::extreme_page(extreme));
  write_page(o.out + "/closed_forms.md", rp::closed_forms_page(closed_forms));
  write_page(o.out + "/friction.md", rp::friction_page(friction, 1e-3));
  write_page(o.out + "/atlas.md", rp::atlas_page(atlas_summary, atlas_info));
  std::cout << "report written to " << o.out
            << "/ (README.md, sweep.md, stability.md, extreme.md, closed_forms.md, friction.md, "
               "atlas.md)\n";
  return kExitOk;
}

}  // namespace

Command add_report(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Run every case of the validation report and write its pages and plots (from the "
      "repository root)");
  CLI::Option* out = o->outputs.directory(
      *cmd, "--out", o->out, "Directory of the pages and plots (default build/report)");
  CLI::Option* models =
      o->outputs.directory(*cmd, "--models", o->models,
                           "Directory of the generated MJCF models (default build/report/models)");
  cmd->add_flag("--snapshot", o->snapshot,
                "Write the committed snapshot: validation/report and models (excludes --out, "
                "--models)")
      ->excludes(out)
      ->excludes(models);
  cmd->add_option("--bench", o->bench,
                  "The contact2d_bench program (default: bench/contact2d_bench beside contact2d; "
                  "the cost section is left out when there is none)")
      ->type_name("PATH");
  cmd->add_option("--seed", o->seed, "Seed of the random scenes (default 20260101)")
      ->type_name("N");
  return {cmd, [o] {
            if (o->snapshot) {
              o->out = "validation/report";
              o->models = "models";
            }
            try {
              return report(*o);
            } catch (const InputError&) {
              throw;
            } catch (const std::exception& e) {
              std::cerr << "contact2d: report: " << e.what() << "\n";
              return kExitDiverged;
            }
          }};
}

}  // namespace contact2d::cli
