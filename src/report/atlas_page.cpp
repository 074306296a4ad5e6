// atlas.md of the validation report: the small default atlas
// (validation/atlas/default.toml) run by `contact2d report`, summarised by
// the atlas's own Markdown (analysis/atlas.hpp) under a header that says
// what ran, how long it took and how to run a larger one.
#include "core/format.hpp"
#include "report/pages.hpp"

namespace contact2d::report {

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
  return md + analysis::atlas_summary_markdown(summary);
}

}  // namespace contact2d::report
