// contact2d atlas SPEC.toml [--shard I/N] [--out DIR] [--threads N] [--quiet]
// contact2d atlas merge DIR... [--out DIR] [--no-plots]
// The fidelity atlas (analysis/atlas.hpp, docs/atlas.md): the three-way
// comparison over a parameter space, in shards that merge into the whole.
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "analysis/atlas.hpp"
#include "analysis/engine.hpp"
#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "report/pages.hpp"

namespace contact2d::cli {
namespace {

struct AtlasOptions {
  std::string spec;
  std::string shard = "1/1";
  std::string out = "atlas-out";
  unsigned threads = 0;
  bool quiet = false;
  // merge
  std::vector<std::string> dirs;
  std::string merged = "atlas-merged";
  bool no_plots = false;
  OutputOptions outputs;        // --out
  OutputOptions merge_outputs;  // merge --out
};

int run(const AtlasOptions& o) {
  if (o.spec.empty()) throw InputError("atlas: a spec (SPEC.toml) or 'merge DIR...' is required");
  o.outputs.check();
  analysis::AtlasRunOptions options;
  options.shard = analysis::parse_shard(o.shard);  // before the spec: options first
  const AtlasSpec spec = load_atlas_spec(o.spec);
  options.threads = o.threads == 0 ? analysis::default_threads() : o.threads;
  options.progress = progress_reporter("atlas shard " + o.shard, o.quiet);
  const analysis::AtlasRunStats stats = analysis::run_atlas(spec, o.out, options);
  std::cout << "atlas " << o.spec << " shard " << o.shard << ": " << stats.points << " of "
            << atlas_point_count(spec) << " points (" << stats.ok << " ok, " << stats.diverged
            << " diverged, " << stats.errors << " failed) in "
            << format_duration(stats.wall_seconds) << " on " << options.threads << " thread(s); "
            << format_number(stats.points_per_core(), 3) << " points/s per core ("
            << format_duration(stats.cpu_per_point()) << " CPU per point); written to " << o.out
            << "/points.csv\n";
  return kExitOk;
}

int merge(const AtlasOptions& o) {
  o.merge_outputs.check();
  const analysis::AtlasData data = analysis::read_atlas_shards(o.dirs);
  std::error_code ec;
  std::filesystem::create_directories(o.merged, ec);
  if (!std::filesystem::is_directory(o.merged))
    throw InputError("--out " + o.merged + ": cannot create directory");
  const DirectoryLock lock("--out", o.merged);  // as for a shard (docs/atlas.md)
  analysis::AtlasSummary summary = analysis::summarize_atlas(data);
  analysis::write_atlas_data(data, o.merged);
  if (!o.no_plots) analysis::draw_atlas_heatmaps(data, summary, o.merged);
  AtomicFile md(o.merged + "/summary.md");
  const std::string text = "# contact2d atlas\n\nMerged from " + std::to_string(o.dirs.size()) +
                           " director" + (o.dirs.size() == 1 ? "y" : "ies") +
                           " by `contact2d atlas merge`.\n\n" +
                           report::atlas_summary_markdown(summary);
  std::fputs(text.c_str(), md.get());
  md.commit();
  std::cout << "atlas merge: " << data.rows.size() << " points from " << o.dirs.size()
            << " director" << (o.dirs.size() == 1 ? "y" : "ies") << " (" << summary.ok << " ok, "
            << summary.diverged << " diverged, " << summary.errors << " failed); written to "
            << o.merged << "/ (points.csv, summary.md" << (o.no_plots ? "" : ", heat maps")
            << ")\n";
  return kExitOk;
}

}  // namespace

Command add_atlas(CLI::App& app) {
  auto o = std::make_shared<AtlasOptions>();
  CLI::App* cmd = app.add_subcommand(
      "atlas",
      "Fidelity atlas: the three-way comparison over a parameter space (docs/atlas.md); "
      "'atlas merge DIR...' combines shards");
  cmd->add_option("spec", o->spec, "Atlas spec (TOML, docs/atlas.md)")->type_name("SPEC.toml");
  cmd->add_option("--shard", o->shard,
                  "Run the points with index % N == I-1 only (default 1/1: all)")
      ->type_name("I/N");
  o->outputs.directory(*cmd, "--out", o->out,
                       "Directory of points.csv, times.csv and shard.txt (default atlas-out)");
  cmd->add_option("--threads", o->threads, "Worker threads (default: one per core)")
      ->type_name("N")
      ->check(CLI::Range(1u, 256u));
  cmd->add_flag("--quiet", o->quiet,
                "No progress on stderr (else: the time left, in place on a terminal, a line "
                "every 5 s otherwise)");
  CLI::App* merge_cmd = cmd->add_subcommand(
      "merge",
      "Combine shard directories: check that every point is there once, write the merged CSV, "
      "heat maps and summary.md");
  merge_cmd->add_option("dirs", o->dirs, "Shard directories (the --out of each atlas run)")
      ->required()
      ->type_name("DIR");
  o->merge_outputs.directory(*merge_cmd, "--out", o->merged,
                             "Directory of the merged output (default atlas-merged)");
  merge_cmd->add_flag("--no-plots", o->no_plots, "Skip the heat maps (no gnuplot needed)");
  return {cmd, [o, merge_cmd] { return *merge_cmd ? merge(*o) : run(*o); }};
}

}  // namespace contact2d::cli
