// contact2d compare SCENE [--engines LIST | --mapping NAME --geometry NAME] [--csv FILE]
// [--json] [--plot FILE.png] [--video FILE.mp4|.gif] [--converged-tol TOL]
// [--no-diagnosis | --full-diagnosis]
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
  EngineOptions engine_options;      // --mapping, --geometry, --model-dt: the engines' own
  std::string csv;
  std::string plot;
  std::string video;
  bool json = false;
  double converged_tol = 1e-12;
  bool no_diagnosis = false;
  bool full_diagnosis = false;
  OutputOptions outputs;  // --csv, --plot, --video
  bool allow_nonphysical = false;
};

using analysis::Comparison;
using analysis::energies;
using analysis::Energies;

// Words wrapped at `width` columns after an indent.
std::string wrapped(const std::string& text, const std::string& indent, size_t width = 78) {
  std::string out, line = indent;
  std::istringstream words(text);
  std::string word;
  size_t length = indent.size();  // in characters (UTF-8 sequences count as one)
  auto chars = [](const std::string& w) {
    size_t n = 0;
    for (unsigned char ch : w) n += (ch & 0xC0) != 0x80;
    return n;
  };
  while (words >> word) {
    if (length > indent.size() && length + 1 + chars(word) > width) {
      out += line + "\n";
      line = indent;
      length = indent.size();
    }
    if (length > indent.size()) {
      line += " ";
      ++length;
    }
    line += word;
    length += chars(word);
  }
  return out + line + "\n";
}

using analysis::ComparedRun;

// "mapping calibrated, geometry corners" (`name_first`) or "calibrated
// mapping" (the first option only): the run's engine options, given or
// their fallbacks; empty for an engine without options.
std::string option_text(const ComparedRun& r, bool name_first) {
  const engines::EngineInfo* info = engines::find_engine(r.spec.kind);
  std::string out;
  for (const engines::EngineOption& option : info->options) {
    const std::string value = engines::option_value(r.spec, option.name);
    if (!name_first) return value + " " + std::string(option.name);
    out += (out.empty() ? "" : ", ") + std::string(option.name) + " " + value;
  }
  return out;
}

// "ref vs MuJoCo, semi_implicit_euler (MuJoCo Euler), mapping calibrated,
// geometry corners"; with more than one engine after the first, each one's
// integrator and options after its label.
std::string engines_text(const Comparison& c) {
  std::string who = c.runs[0].label + " vs ", what;
  for (size_t i = 1; i < c.runs.size(); ++i) {
    const ComparedRun& r = c.runs[i];
    who += (i > 1 ? " and " : "") + r.label;
    std::string one = engines::integrator_label(r.spec.kind, c.scene.sim.integrator);
    if (const std::string options = option_text(r, true); !options.empty()) one += ", " + options;
    what += (i > 1 ? "; " : "") + (c.runs.size() > 2 ? r.label + ": " : "") + one;
  }
  return who + ", " + what;
}

void print_table(const Comparison& c) {
  const analysis::ConvergedSolution& conv = c.converged;
  std::cout << shape_name(c.scene.shape) << ": " << engines_text(c) << ", "
            << std::string(damping_law_title(c.scene.contact.damping))
            << " damping, dt = " << format_number(c.scene.sim.dt, 4) << " s, "
            << c.runs[1].vs_first.samples << " samples over "
            << format_number(c.scene.sim.duration, 4) << " s\n";
  if (c.scene.contact.friction != FrictionLaw::Tanh) {
    // A cone law is a conformance law, not physics; it matches MuJoCo only
    // at MuJoCo's own impratio: that of the first engine whose model has one.
    size_t with = 1;
    while (with + 1 < c.runs.size() && !std::isfinite(c.runs[with].run.impratio)) ++with;
    const double impratio = c.runs[with].run.impratio;
    std::string note = "friction law: " + std::string(friction_law_name(c.scene.contact.friction)) +
                       " (MuJoCo's cone, not physics), cone ratio " +
                       format_shortest(c.scene.contact.cone_ratio, 6);
    if (std::isfinite(impratio) && impratio != c.scene.contact.cone_ratio)
      note += "; " + c.runs[with].label + "'s model has impratio " + format_shortest(impratio, 6) +
              ": --set contact.cone_ratio=" + format_shortest(impratio, 6) +
              " to compare like with like";
    std::cout << wrapped(note, "") << "\n";
  }
  if (conv.available) {
    std::cout << "converged solution: Dormand-Prince 5(4) with every contact switch located, tol "
              << format_shortest(conv.tol)
              << " (its own error <= " << format_number(conv.own_error, 2)
              << " m: the distance to tol " << format_shortest(10 * conv.tol)
              << ");\nthe scene magnifies a 1e-8 m change of the initial height "
              << format_number(conv.amplification, 3) << "-fold\n\n";
  } else {
    std::string pairs;
    for (size_t i = 1; i < c.runs.size(); ++i)
      pairs += (i > 1 ? ", " : "") + c.runs[0].label + " <-> " + c.runs[i].label;
    std::cout << wrapped("converged solution: not available (" + conv.why_not + "); only " + pairs +
                             " " + (c.runs.size() > 2 ? "are" : "is") + " measured.",
                         "")
              << "\n";
  }
  Table t;
  t.columns = {"", c.runs[0].label + " <-> converged"};
  for (size_t i = 1; i < c.runs.size(); ++i) {
    t.columns.push_back(c.runs[i].label + " <-> converged");
    t.columns.push_back(c.runs[0].label + " <-> " + c.runs[i].label);
  }
  auto row = [&](const std::string& name, auto field) {
    auto converged = [&](const ComparedRun& r) {
      return conv.available ? format_number(field(r.vs_converged), 4) : std::string("-");
    };
    std::vector<std::string> cells{name, converged(c.runs[0])};
    for (size_t i = 1; i < c.runs.size(); ++i) {
      cells.push_back(converged(c.runs[i]));
      cells.push_back(format_number(field(c.runs[i].vs_first), 4));
    }
    add_row(t, cells);
  };
  using E = analysis::TrajectoryError;
  row("max position (m)", [](const E& e) { return e.max_pos; });
  row("RMS position (m)", [](const E& e) { return e.rms_pos; });
  row("end position (m)", [](const E& e) { return e.end_pos; });
  row("max angle (rad)", [](const E& e) { return e.max_angle; });
  row("end angle (rad)", [](const E& e) { return e.end_angle; });
  row("max velocity (m/s)", [](const E& e) { return e.max_vel; });
  row("max omega (rad/s)", [](const E& e) { return e.max_omega; });
  row("time of max position (s)", [](const E& e) { return e.time_of_max_pos; });
  std::cout << to_text(t) << "\n";
  size_t width = 6;  // "energy ref     ": the labels in one column
  for (const ComparedRun& r : c.runs) width = std::max(width, r.label.size());
  for (const ComparedRun& r : c.runs) {
    const Energies en = energies(c.scene, r.run.trajectory);
    std::cout << "energy " << r.label << std::string(width + 2 - r.label.size(), ' ')
              << format_number(en.initial, 4) << " -> " << format_number(en.final, 4) << " J\n";
  }
  std::cout << "wall clock" << std::string(width - 1, ' ');
  for (size_t i = 0; i < c.runs.size(); ++i)
    std::cout << (i ? ", " : "") << c.runs[i].label << " "
              << format_number(c.runs[i].run.seconds, 4) << " s";
  if (conv.available) std::cout << ", converged " << format_number(conv.seconds, 4) << " s";
  std::cout << "\n";
  const std::vector<std::string> versions = analysis::version_notes(c);
  if (!versions.empty()) std::cout << "\nVersions:\n";
  for (const std::string& note : versions) std::cout << wrapped(note, "  ");
  const analysis::Diagnosis& d = c.diagnosis;
  if (!d.ran) {
    if (!d.summary.empty()) std::cout << "\nDiagnosis:\n" << wrapped(d.summary, "  ");
    return;
  }
  std::cout << "\nDiagnosis"
            << (c.runs.size() > 2 ? " of " + c.runs[0].label + " <-> " + c.runs[c.diagnosed].label
                                  : "")
            << " (each cause removed alone, both engines re-run):\n"
            << wrapped(d.summary, "  ");
  int n = 0;
  for (const analysis::Finding& finding : d.findings) {
    if (!finding.named) continue;
    std::cout << "\n"
              << wrapped(std::to_string(++n) + ". " + finding.cause + ": " + finding.explanation,
                         "  ")
              << "     fix: " << finding.fix << "\n";
  }
  std::string ruled_out;
  for (const analysis::Finding& finding : d.findings) {
    if (finding.named) continue;
    ruled_out += (ruled_out.empty() ? "" : "; ") + finding.cause + " (" +
                 (std::isfinite(finding.share)
                      ? format_text("%.0f %%", std::round(100.0 * finding.share) + 0.0) + ", " +
                            format_number(finding.after, 3) +
                            (finding.cause == "dt_dependent_model" ? " m with the model held"
                                                                   : " m without it")
                      : std::string("not measured")) +
                 ")";
  }
  if (!ruled_out.empty())
    std::cout << "\n" << wrapped("Measured and ruled out: " + ruled_out + ".", "  ");
  if (!d.not_rerun.empty()) {
    std::string causes;
    for (const std::string& cause : d.not_rerun) causes += (causes.empty() ? "" : ", ") + cause;
    std::cout << "\n" << wrapped("Not re-run: " + causes + ". " + d.not_rerun_why, "  ");
  }
}

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
  const engines::OptionValues given(options.engine_options.values.begin(),
                                    options.engine_options.values.end());
  Comparison c = analysis::prepare_comparison(
      options.scene.load(),
      analysis::comparison_engines(options.engines, given, options.engine_options.model_dt,
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
  analysis::run_engines(c, !options.no_diagnosis);
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
  analysis::measure(c, options.converged_tol, !options.no_diagnosis, how);
  // Every output is made first and committed at the end, together: a plot
  // or video that fails, or an interrupt, leaves none of them.
  if (csv) write_csv(*csv, c);
  std::unique_ptr<AtomicFile> plot, video;
  if (!options.plot.empty()) {
    const ComparedRun& a = c.runs[0];
    const ComparedRun& b = c.runs[1];  // the plot draws the first two
    const std::string options_first = option_text(b, false);
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
    const std::string options_first = option_text(b, false);
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
    print_table(c);
  }
  return kExitOk;
}

}  // namespace

Command add_compare(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Run the reference solver and MuJoCo on a scene and compare them");
  options->scene.add_to(*cmd);
  options->engine_options.add_to(*cmd);
  cmd->add_option("--engines", options->engines,
                  "Comma-separated engines to compare with the reference, each measured against "
                  "it and the converged solution: " +
                      engines::engine_names_help() +
                      "; a name carries its options (mujoco:exact:boxes) (default: every engine "
                      "built in, with --mapping and --geometry)")
      ->type_name("ENGINE")
      ->delimiter(',');
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
  return {cmd, [options] { return compare(*options); }};
}

}  // namespace contact2d::cli
