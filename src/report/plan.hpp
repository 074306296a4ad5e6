// The plan of `contact2d report`: which scenes it runs, with which
// overrides, on which engines, and which pages it writes. plan.cpp reads as
// the report's table of contents: every run goes through the seam
// (report/runs.hpp, the only code of the report that runs an engine or an
// analysis), every page is written by report/pages.hpp from the structs the
// seam returns, each through io's AtomicFile. The program's subcommand
// (src/cli/cmd_report.cpp) checks the options and calls write_report().
//
// Scene paths are relative to the current directory, which must be the
// repository root (they name the scenes in the models and messages, as the
// CLI's do).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace contact2d::report {

// Where the report goes and what it runs with; the options are checked
// (directories exist, the bench is executable when named).
struct ReportRequest {
  std::string out;     // the pages and plots
  std::string models;  // the generated MJCF models
  // contact2d_bench; the cost section is left out when it is empty or not
  // an executable file.
  std::string bench;
  std::uint64_t seed = 0;  // of the random scenes
  unsigned jobs = 0;       // threads of the report's pool (0: one per core)
};

// The pages write_report() writes into `out`, in the order it writes them.
const std::vector<std::string>& page_names();

// Where one run's wall-clock time went, section by section (`contact2d
// report --timings`, scripts/report-timings): the seconds its tasks took,
// added up, and when its first task began and its last ended, in seconds
// since the run began.
struct SectionTime {
  std::string name;
  double seconds = 0.0, start = 0.0, end = 0.0;
};
struct ReportTimings {
  std::vector<SectionTime> sections;  // in the order they first began
  double total = 0.0;                 // the whole run, its pages written
};

// Runs every case of the report and then writes its pages (no page when a
// run fails). Throws InputError for a scene or spec that cannot be read,
// std::runtime_error when a run fails (an engine diverged, gnuplot or the
// bench failed).
ReportTimings write_report(const ReportRequest& o);

}  // namespace contact2d::report
