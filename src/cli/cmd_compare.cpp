// contact2d compare SCENE [--engines LIST | --mapping NAME --geometry NAME] [--csv FILE]
// [--json] [--plot FILE.png] [--video FILE.mp4|.gif] [--converged-tol TOL]
// [--no-diagnosis | --full-diagnosis] [--threads N]
// [overrides]
//
// Runs the reference solver and every other engine (by default each one
// built in: MuJoCo) on the same scene (same Δt, same sample times),
// measures each against the converged solution and against the reference,
// and diagnoses the difference of the reference and the first engine with
// soft constraints (MuJoCo) by re-running without each suspected cause
// (analysis/comparison.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "analysis/compare_run.hpp"
#include "analysis/trajectory_error.hpp"
#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "engines/engines.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/interrupt.hpp"
#include "io/json.hpp"
#include "io/plot.hpp"
#include "io/table.hpp"
#ifdef CONTACT2D_WITH_WINDOW
#include "game/comparison_video.hpp"
#endif

namespace contact2d::cli {
namespace {

struct CompareOptions {
  SceneOptions scene;
  std::vector<std::string> engines;  // --engines; empty: every engine built in but the reference
  std::string engine;                // --engine: one engine, as --engines with one name
  EngineOptions engine_options;      // --mapping, --geometry, --model-dt: the engines' own
  std::string csv;
  std::string plot;
  std::string video;
  bool json = false;
  double converged_tol = 1e-12;
  bool no_diagnosis = false;
  bool full_diagnosis = false;
  unsigned threads = 0;   // --threads; 0: one per core this process may use
  OutputOptions outputs;  // --csv, --plot, --video
  bool allow_nonphysical = false;
};

using analysis::ComparedRun;
using analysis::Comparison;

// t, then x_KEY … omega_KEY for every run in order, then the converged
// solution's when available; one row per sample the runs share.
void write_csv(AtomicFile& out, const Comparison& c) {
  const bool conv = c.converged.available;
  std::string header = "t";
  for (const ComparedRun& r : c.runs)
    for (const char* q : {"x", "y", "theta", "vx", "vy", "omega"})
      header += "," + std::string(q) + "_" + r.key;
  if (conv)
    header += ",x_converged,y_converged,theta_converged,vx_converged,vy_converged,omega_converged";
  std::fprintf(out.get(), "%s\n", header.c_str());
  size_t rows = c.runs[0].run.trajectory.samples.size();
  for (const ComparedRun& r : c.runs) rows = std::min(rows, r.run.trajectory.samples.size());
  const auto& first = c.runs[0].run.trajectory.samples;
  for (size_t i = 0; i < rows; ++i) {
    std::fprintf(out.get(), "%.10g", first[i].t);
    for (const ComparedRun& r : c.runs) {
      const State& s = r.run.trajectory.samples[i].state;
      std::fprintf(out.get(), ",%.12g,%.12g,%.12g,%.12g,%.12g,%.12g", s.q.x(), s.q.y(), s.q.z(),
                   s.v.x(), s.v.y(), s.v.z());
    }
    if (conv) {
      const State g = c.converged.trajectory.at(first[i].t);
      std::fprintf(out.get(), ",%.12g,%.12g,%.12g,%.12g,%.12g,%.12g", g.q.x(), g.q.y(), g.q.z(),
                   g.v.x(), g.v.y(), g.v.z());
    }
    std::fputc('\n', out.get());
  }
}

int compare(const CompareOptions& options) {
  options.outputs.check();
  if (!options.engine.empty() && !options.engines.empty())
    throw InputError("--engine " + options.engine +
                     ": not with --engines (put every engine in --engines)");
  const std::vector<std::string> names =
      options.engine.empty() ? options.engines : std::vector<std::string>{options.engine};
  const engines::OptionValues given(options.engine_options.values.begin(),
                                    options.engine_options.values.end());
  Comparison c = analysis::prepare_comparison(
      options.scene.load(),
      analysis::comparison_engines(names, given, options.engine_options.model_dt,
                                   options.scene.path, flag_spelling));
  if (!options.video.empty()) {
#ifdef CONTACT2D_WITH_WINDOW
    game::check_video_path(options.video);
#else
    throw InputError("--video " + options.video +
                     ": this contact2d was built without the game's window (GLFW, OpenGL, "
                     "stb_easy_font), which draws the video");
#endif
  }
  std::unique_ptr<AtomicFile> csv;
  if (!options.csv.empty()) csv = std::make_unique<AtomicFile>(options.csv);
  analysis::run_engines(c, !options.no_diagnosis, options.threads);
  for (const ComparedRun& r : c.runs)
    for (const std::string& w : r.run.warnings)
      std::cerr << "contact2d: " << r.label << " warning: " << w << "\n";
  const std::vector<analysis::RunProblem> problems = analysis::run_problems(c);
  bool stop = false;
  for (const analysis::RunProblem& p : problems) {
    if (p.diverged) {
      std::cerr << "contact2d: " << options.scene.path << ": " << p.engine << ": " << p.message
                << "\n";
      stop = true;
    } else {
      stop |=
          reject_nonphysical(p.message, options.allow_nonphysical, options.scene.path, p.engine);
    }
  }
  if (stop) return kExitDiverged;
  analysis::DiagnosisOptions how;
  how.full = options.full_diagnosis;
  how.threads = options.threads;
  analysis::measure(c, options.converged_tol, !options.no_diagnosis, how);
  // Every output is made first and committed at the end, together: a plot
  // or video that fails, or an interrupt, leaves none of them.
  if (csv) write_csv(*csv, c);
  std::unique_ptr<AtomicFile> plot, video;
  if (!options.plot.empty()) {
    const ComparedRun& a = c.runs[0];
    const ComparedRun& b = c.runs[1];  // the plot draws the first two
    const std::string options_first = analysis::run_options_text(b, false);
    const std::string title = std::string(shape_name(c.scene.shape)) + ": " + a.label + " vs " +
                              b.label + ", " +
                              engines::integrator_label(b.spec.kind, c.scene.sim.integrator) +
                              ", Δt = " + format_number(c.scene.sim.dt) + " s, " +
                              (options_first.empty() ? "" : options_first + ", ") +
                              std::string(damping_law_title(c.scene.contact.damping)) + " damping";
    plot = std::make_unique<AtomicFile>(options.plot);
    plot_comparison(*plot, title, a.run.trajectory, b.run.trajectory, a.label, b.label);
  }
#ifdef CONTACT2D_WITH_WINDOW
  if (!options.video.empty()) {
    game::ComparisonVideoInput in;
    in.scene = &c.scene;
    const ComparedRun& a = c.runs[0];
    const ComparedRun& b = c.runs[1];  // the video draws the first two
    const std::string options_first = analysis::run_options_text(b, false);
    in.reference = &a.run.trajectory;
    in.second = &b.run.trajectory;
    in.converged = c.converged.available ? &c.converged.trajectory : nullptr;
    in.title = std::string(shape_name(c.scene.shape)) + ": " + a.label + " vs " + b.label + ", " +
               engines::integrator_label(b.spec.kind, c.scene.sim.integrator) +
               (options_first.empty() ? "" : ", " + options_first);
    in.reference_label = a.label;
    in.second_label = b.label;
    video = game::render_comparison_video(options.video, in);
  }
#endif
  {
    // Renames are instant: with interrupts held they happen all or none. A
    // FIFO or device is written through and may wait for its reader, so
    // with one among them Ctrl-C stays possible (and may come between).
    std::optional<InterruptsHeld> held;
    if ((!csv || !csv->streams()) && (!plot || !plot->streams()) && (!video || !video->streams()))
      held.emplace();
    if (csv) csv->commit();
    if (plot) plot->commit();
    if (video) video->commit();
  }
  if (options.json) {
    std::cout << analysis::comparison_json(c, options.scene.path);
  } else {
    std::cout << analysis::comparison_text(c);
  }
  return kExitOk;
}

// What compare runs without --engines, for its help: the engines built
// into this program, by name and title.
std::string built_in_engines() {
  std::string list, named;
  for (const engines::EngineInfo* info : engines::engine_list()) {
    if (info->make == nullptr || info->kind == "ref") continue;
    std::string& to = info->compared_by_default ? list : named;
    to += (to.empty() ? "" : " and ") + std::string(info->kind) + " (" + std::string(info->title) +
          ")";
  }
  return (list.empty() ? "the reference alone" : list) +
         (named.empty() ? "" : "; " + named + " only when named");
}

}  // namespace

Command add_compare(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Run the reference solver and MuJoCo on a scene and compare them");
  options->scene.add_to(*cmd);
  options->outputs.input("scene file", options->scene.path);
  options->engine_options.add_to(*cmd);
  cmd->add_option("--engines", options->engines,
                  "Comma-separated engines to compare with the reference, each measured against "
                  "it and the converged solution: " +
                      engines::engine_names_help() +
                      "; a name carries its options (mujoco:exact:boxes) (default: " +
                      built_in_engines() + ", each with --mapping and --geometry)")
      ->type_name("ENGINE")
      ->delimiter(',');
  cmd->add_option("--engine", options->engine,
                  "One engine to compare with the reference, as --engines with one name; it "
                  "takes --mapping, --geometry and --friction as simulate's --engine does")
      ->type_name("ENGINE");
  options->outputs.file(*cmd, "--csv", options->csv,
                        "Write the trajectories side by side to this file", "FILE.csv");
  cmd->add_flag("--json", options->json, "Print one JSON object instead of the table");
  options->outputs.file(
      *cmd, "--plot", options->plot,
      "Draw x, y, theta of the reference and the first engine and their distance into this PNG "
      "(gnuplot)",
      "FILE.png");
  options->outputs.file(*cmd, "--video", options->video,
                        "Draw the reference and the first engine overlaid in real time into this "
                        ".mp4 or .gif (reference filled, the engine outlined, the converged "
                        "solution as a thin line)",
                        "FILE.mp4|.gif");
  cmd->add_option("--converged-tol", options->converged_tol,
                  "Tolerance of the converged solution (rtol = atol; default 1e-12)")
      ->type_name("TOL")
      ->check(number_in(1e-14, 1e-6, false, "[1e-14, 1e-6]"));
  add_allow_nonphysical(*cmd, options->allow_nonphysical);
  cmd->add_flag("--no-diagnosis", options->no_diagnosis,
                "Skip the diagnosis (the re-runs that remove each cause of the difference)");
  cmd->add_flag("--full-diagnosis", options->full_diagnosis,
                "Also make the diagnosis's re-runs at a smaller step (time_step, "
                "dt_dependent_model, refsafe: ten times the steps or more) when the others "
                "already explain the difference")
      ->excludes("--no-diagnosis");
  cmd->add_option("--threads", options->threads,
                  "Threads for the diagnosis's re-runs and the runs made beside the engines "
                  "(default: one per core this process may run on; each MuJoCo 3 thread starts "
                  "a Node process of its own)")
      ->type_name("N")
      ->check(CLI::Range(1U, 256U));
  return {cmd, [options] { return compare(*options); }};
}

}  // namespace contact2d::cli
