// contact2d report [--out DIR] [--models DIR | --snapshot] [--bench PATH] [--seed N] [--jobs N]
//                  [--timings]
//
// Writes every page of validation/report/ — README.md (the reference against
// MuJoCo), sweep.md, stability.md, extreme.md, closed_forms.md, friction.md,
// atlas.md — and their PNG plots, and the generated MJCF models, from one
// run. This file checks the options and hands them to the report layer:
// what runs, on which scenes, and which pages are written is the report's
// plan (report/plan.hpp), which runs everything through its seam
// (report/runs.hpp). Run it from the repository root: scene paths are
// relative to it. Exit status: 0 done, 2 bad input (one line, before any
// run), 3 a run failed (an engine diverged, gnuplot or the bench failed): no
// page is written then.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "report/plan.hpp"
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
  bool timings = false;   // where the wall-clock time went, on stderr
  unsigned jobs = 0;      // threads of the report's pool (0: one per core)
  OutputOptions outputs;  // --out, --models
};

std::string default_bench() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : (self.parent_path() / "bench" / "contact2d_bench").string();
}

// One line per section (scripts/report-timings reads them): its tasks'
// seconds added up, then from when to when it ran, in seconds since the
// report began.
void print_timings(const rp::ReportTimings& t) {
  char line[200];
  for (const rp::SectionTime& s : t.sections) {
    std::snprintf(line, sizeof line, "report: timing %-14s %7.2f s  (%.2f to %.2f s)\n",
                  (s.name + ":").c_str(), s.seconds, s.start, s.end);
    std::cerr << line;
  }
  std::snprintf(line, sizeof line, "report: timing %-14s %7.2f s\n", "total:", t.total);
  std::cerr << line;
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
  if (!rp::mujoco_built())
    throw InputError("contact2d report needs MuJoCo (built with CONTACT2D_WITH_MUJOCO=OFF)");

  const rp::ReportTimings timings = rp::write_report({o.out, o.models, bench, o.seed, o.jobs});
  if (o.timings) print_timings(timings);
  std::string pages;
  for (const std::string& name : rp::page_names()) pages += (pages.empty() ? "" : ", ") + name;
  std::cout << "report written to " << o.out << "/ (" << pages << ")\n";
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
  cmd->add_option("--jobs", o->jobs,
                  "Threads that run the report's sections side by side (default 0: one per core)")
      ->type_name("N");
  cmd->add_flag("--timings", o->timings,
                "Print the wall-clock seconds of each section of the run to standard error");
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
