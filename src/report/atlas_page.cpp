// atlas.md of the validation report: the small default atlas
// (validation/atlas/default.toml) run by `contact2d report`, summarised
// under a header that says what ran, how long it took and how to run a
// larger one; and that summary's Markdown, which `contact2d atlas merge`
// writes to summary.md too. The numbers come from analysis/atlas.hpp.
#include <cmath>
#include <sstream>

#include "core/format.hpp"
#include "report/pages.hpp"

namespace contact2d::report {

std::string atlas_summary_markdown(const analysis::AtlasSummary& s, const std::string& image_dir) {
  std::ostringstream md;
  auto fraction = [](long long met, long long of) {
    if (of == 0) return std::string("–");
    return std::to_string(met) + "/" + std::to_string(of) + " (" +
           format_text("%.0f", 100.0 * static_cast<double>(met) / static_cast<double>(of)) + " %)";
  };
  md << s.points << " points of `" << s.spec << "` (spec digest " << s.digest << "): " << s.ok
     << " ok, " << s.diverged << " diverged, " << s.errors << " failed.\n\n";
  md << "## How often MuJoCo meets the goals\n\n"
     << "A point meets the goal when MuJoCo's largest position error against the converged "
        "solution is at most "
     << format_number(analysis::kAtlasGoalFrictionless)
     << " m without friction (μ = μ_roll = 0) or " << format_number(analysis::kAtlasGoalFriction)
     << " m with friction; the \"ref ↔ MuJoCo\" columns apply the same goals to the distance "
        "between the engines. A point that diverged or failed does not meet them.\n\n"
     << "| body | mapping | damping | points | diverged, failed | frictionless: MuJoCo ↔ "
        "converged | ref ↔ MuJoCo | friction: MuJoCo ↔ converged | ref ↔ MuJoCo | largest "
        "MuJoCo ↔ converged (m) | largest ref ↔ converged (m) |\n"
     << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const analysis::AtlasGroup& g : s.groups) {
    md << "| " << g.body << " | " << g.mapping << " | " << g.damping << " | " << g.points << " | "
       << g.diverged << ", " << g.errors << " | " << fraction(g.frictionless_met, g.frictionless)
       << " | " << fraction(g.frictionless_met_engines, g.frictionless) << " | "
       << fraction(g.friction_met, g.friction) << " | "
       << fraction(g.friction_met_engines, g.friction) << " | "
       << (g.ok ? format_number(g.worst_mujoco, 3) : "–") << " | "
       << (g.ok ? format_number(g.worst_ref, 3) : "–") << " |\n";
  }
  md << "\n## The converged solution's own error\n\n";
  if (std::isnan(s.min_measured)) {
    md << "No point was measured against the converged solution.\n";
  } else {
    md << "Its largest own error (the distance to the run at 10× its tolerance) is "
       << format_number(s.max_own_error, 3) << " m; the smallest error it measures is "
       << format_number(s.min_measured, 3) << " m ("
       << (s.max_own_error > 0.0 ? format_number(s.min_measured / s.max_own_error, 3) + "× larger"
                                 : std::string("its own error is 0"))
       << ").\n";
  }
  if (!s.worst.empty()) {
    md << "\n## The largest MuJoCo errors\n\n"
       << "| point | body | mapping | damping | m (kg) | k (N/m) | ζ | μ | μ_roll | Δt (s) | "
          "MuJoCo ↔ converged (m) | ref ↔ converged (m) |\n"
       << "|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const analysis::AtlasRow* r : s.worst)
      md << "| " << r->index << " | " << r->body << " | " << r->mapping << " | " << r->damping
         << " | " << format_number(r->mass, 3) << " | " << format_number(r->k, 3) << " | "
         << format_number(r->zeta, 3) << " | " << format_number(r->mu, 3) << " | "
         << format_number(r->mu_roll, 3) << " | " << format_number(r->dt, 3) << " | "
         << format_number(r->mujoco_conv_pos, 3) << " | " << format_number(r->ref_conv_pos, 3)
         << " |\n";
  }
  if (!s.failed.empty()) {
    md << "\n## Points that diverged or failed\n\n| point | body | mapping | status | message |\n"
       << "|---:|---|---|---|---|\n";
    for (size_t i = 0; i < s.failed.size() && i < 5; ++i) {
      const analysis::AtlasRow* r = s.failed[i];
      std::string message = analysis::split_csv_line(r->line).back();
      if (message.size() > 200) message = message.substr(0, 200) + " …";
      for (char& ch : message)
        if (ch == '|') ch = '/';
      md << "| " << r->index << " | " << r->body << " | " << r->mapping << " | " << r->status
         << " | " << message << " |\n";
    }
    if (s.failed.size() > 5) md << "\n(" << s.failed.size() - 5 << " more in points.csv.)\n";
  }
  bool any = false;
  for (const analysis::AtlasGroup& g : s.groups) any = any || !g.heatmap.empty();
  if (any) {
    md << "\n## Heat maps over k × ζ\n\n"
       << "Left, MuJoCo against the converged solution (its step error included); right, the "
          "two engines against each other at the same Δt; the points without friction "
          "(μ = μ_roll = 0) in the top row, those with friction below. Each cell shows the largest "
          "maximum position error of its points (over the other axes); \"diverged\" marks a cell "
          "whose points all failed, \"*\" one where some did. The colour is how many decades a "
          "cell lies from its row's goal (1e-5 m without friction, 1e-3 m with): white at the "
          "goal, blue below it (met), orange above (missed), each panel on its own scale.\n\n";
    for (const analysis::AtlasGroup& g : s.groups)
      if (!g.heatmap.empty())
        md << "![" << g.body << ", " << g.mapping << ", " << g.damping << "](" << image_dir
           << g.heatmap << ")\n\n";
  }
  return md.str();
}

std::string atlas_page(const analysis::AtlasSummary& summary, const AtlasRunInfo& info) {
  std::string md =
      "# A small fidelity atlas\n\n"
      "`contact2d atlas " +
      info.spec +
      "` runs the three-way comparison of `contact2d compare` (the reference, MuJoCo and the "
      "converged solution) at every point of a parameter grid and records where MuJoCo "
      "reproduces the penalty model and how closely. This is the small default atlas of the "
      "report; [docs/atlas.md](../../docs/atlas.md) describes the spec, sharding, the merge and "
      "running a large one on a Slurm cluster or over ssh.\n\n"
      "This run: " +
      std::to_string(info.points) + " points in " + format_duration(info.wall_seconds) + " on " +
      std::to_string(info.threads) + " thread(s), " + format_duration(info.cpu_per_point) +
      " of CPU per point (" + format_number(info.points_per_core, 3) +
      " points/s per core). The rows are in [`atlas/points.csv`](atlas/points.csv).\n\n";
  return md + atlas_summary_markdown(summary);
}

}  // namespace contact2d::report
