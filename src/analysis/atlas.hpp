// The fidelity atlas (`contact2d atlas`, docs/atlas.md): the three-way
// comparison of compare (analysis/comparison.hpp) over a parameter space,
// one independent point at a time, so that any subset (a shard) can run on
// any machine and the shards merge into the run of the whole.
//
// A point is a body (a shape or a scene file), a MuJoCo mapping, a damping
// law and a value of every axis (mass, k, ζ or c, μ, μ_roll, Δt). Points are
// numbered 0 … n−1 in a fixed order: a grid varies the last axis fastest
// (body, mapping, damping, mass, k, ζ|c, μ, μ_roll, Δt); a random sample
// runs `count` drawn samples for every body × mapping × damping law, the same
// samples for each, so mappings are compared on the same physical points.
// Sample j is drawn from its own SplitMix64 stream (seed, j), so a point does
// not depend on which others run.
//
// Each point runs the reference (the spec's integrator at the point's Δt),
// MuJoCo (the point's mapping, Euler for semi-implicit Euler as compare
// does) and the converged solution at the spec's tolerance, and records
// the three maximum position and angle distances, the converged solution's
// own error (its distance to the run at 10× the tolerance) and an exit
// status: ok, diverged (an engine's divergence rule tripped) or error (an
// engine refused the point or the converged solution failed), with the
// message. A point that fails is a row, never the end of the run.
//
// Output of a run (a shard of it) in one directory, every file written to a
// temporary and renamed when complete:
//   points.csv   one row per point, in index order: parameters, distances,
//                status. Deterministic: the same bytes whatever the thread
//                count and sharding (times are kept apart for that reason);
//   times.csv    index, CPU seconds of each engine, of the converged solution
//                and of the point, and the point's wall-clock seconds;
//   shard.txt    the spec, its digest, the number of points and the shard.
//
// The points and shards are analysis/atlas_shard.cpp (with the files of a
// shard's directory, analysis/atlas_shard.hpp), running them
// analysis/atlas_run.cpp, the merge, the summary's numbers and the heat maps
// analysis/atlas_merge.cpp; the summary's Markdown is the report's
// (report/pages.hpp, atlas_summary_markdown).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "io/atlas_spec.hpp"

namespace contact2d::analysis {

struct AtlasPoint {
  long long index = 0;
  std::string body;     // the body's label
  std::string mapping;  // seed | exact | calibrated | compensated
  std::string engine;   // the MuJoCo: "mujoco" (2.2.2) or "mujoco3" (the spec's engine)
  DampingLaw damping = DampingLaw::KelvinVoigt;
  double mass = 0.0;  // total mass, kg
  double k = 0.0, zeta = 0.0, c = 0.0, mu = 0.0, mu_roll = 0.0, dt = 0.0;
  Scene scene;  // the scene this point runs
};

// Point `index` of the spec (0 ≤ index < atlas_point_count(spec)). Throws
// InputError when its scene is outside the core's ranges, naming the point
// and the field.
AtlasPoint atlas_point(const AtlasSpec& spec, long long index);

// `--shard I/N`: the points with index % N == I − 1.
struct Shard {
  long long index = 1;  // I, 1-based
  long long count = 1;  // N
  bool holds(long long point) const { return point % count == index - 1; }
};
Shard parse_shard(const std::string& text);  // "I/N", 1 ≤ I ≤ N ≤ 1e6; throws InputError

constexpr double kAtlasNaN = std::numeric_limits<double>::quiet_NaN();

struct AtlasResult {
  long long index = 0;
  std::string status = "ok";  // ok | diverged | error
  std::string message;        // why, when not ok
  // Maximum position (m) and angle (rad) distances; NaN where not measured
  // (an engine diverged or failed, or no converged solution).
  double ref_conv_pos = kAtlasNaN, ref_conv_angle = kAtlasNaN;
  double mujoco_conv_pos = kAtlasNaN, mujoco_conv_angle = kAtlasNaN;
  double ref_mujoco_pos = kAtlasNaN, ref_mujoco_angle = kAtlasNaN;
  double converged_own_error = kAtlasNaN;  // m
  // Times, kept out of points.csv: CPU seconds on the point's thread (the
  // measure that other load on the machine does not inflate) of the
  // reference run, the MuJoCo run (its model's generation and loading
  // included), the converged solution (both tolerances), the whole point;
  // and the point's wall-clock seconds.
  double ref_seconds = 0.0, mujoco_seconds = 0.0, converged_seconds = 0.0;
  double cpu_seconds = 0.0;
  double wall_seconds = 0.0;
};

// ------------------------------------------------------------------- run

// Runs one point. Never throws for a point that fails: the result says so.
AtlasResult run_atlas_point(const AtlasPoint& point, double converged_tol);

// The CSV of points.csv and times.csv.
std::string atlas_csv_header();
std::string atlas_csv_row(const AtlasPoint& point, const AtlasResult& result);
std::string atlas_times_header();
std::string atlas_times_row(const AtlasResult& result);

// Running a spec, or a shard of it, into a directory.
struct AtlasRunOptions {
  Shard shard;
  unsigned threads = 0;  // 0: one per core
  // (done, total, what): called after every point, from the worker threads
  // one at a time.
  std::function<void(size_t, size_t, const std::string&)> progress;
};
struct AtlasRunStats {
  long long points = 0, ok = 0, diverged = 0, errors = 0;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;  // summed over the points
  double cpu_per_point() const {
    return points > 0 ? cpu_seconds / static_cast<double>(points) : 0.0;
  }
  // Throughput per core: points per CPU second.
  double points_per_core() const {
    return cpu_seconds > 0.0 ? static_cast<double>(points) / cpu_seconds : 0.0;
  }
};
// Checks every point of the shard first (bad input throws InputError before
// any file is created), then writes points.csv, times.csv and shard.txt to
// `out_dir` (created if missing).
AtlasRunStats run_atlas(const AtlasSpec& spec, const std::string& out_dir,
                        const AtlasRunOptions& options);

// ----------------------------------------------------------------- merge

// A row of points.csv read back: its text (written back verbatim by the
// merge) and the fields the summary needs.
struct AtlasRow {
  std::string line;
  long long index = 0;
  std::string body, mapping, damping, status;
  double mass = 0, k = 0, zeta = 0, c = 0, mu = 0, mu_roll = 0, dt = 0;
  double ref_conv_pos = kAtlasNaN, ref_conv_angle = kAtlasNaN;
  double mujoco_conv_pos = kAtlasNaN, mujoco_conv_angle = kAtlasNaN;
  double ref_mujoco_pos = kAtlasNaN, ref_mujoco_angle = kAtlasNaN;
  double converged_own_error = kAtlasNaN;
};

// One field of a CSV line (RFC 4180 quoting); exposed for tests.
std::vector<std::string> split_csv_line(const std::string& line);
AtlasRow parse_atlas_row(const std::string& line, const std::string& origin);  // throws InputError

struct AtlasData {
  std::string spec, digest;
  long long points = 0;
  std::vector<AtlasRow> rows;      // index order, every point once
  std::vector<std::string> times;  // times.csv rows, index order (empty when a shard had none)
};

// Reads shard directories and checks that together they hold every point of
// one spec exactly once. Throws InputError naming the missing points (and
// shards) or the duplicated ones and where they are.
AtlasData read_atlas_shards(const std::vector<std::string>& dirs);

// Writes the merged points.csv, times.csv and shard.txt (1/1) to out_dir.
void write_atlas_data(const AtlasData& data, const std::string& out_dir);

// --------------------------------------------------------------- summary

// The error goals of the summary: MuJoCo within 1e-5 m of the converged
// solution without friction, 1e-3 m with friction (the project's goals,
// validation/report/README.md).
constexpr double kAtlasGoalFrictionless = 1e-5;  // m
constexpr double kAtlasGoalFriction = 1e-3;      // m

struct AtlasGroup {  // one body × mapping × damping law
  std::string body, mapping, damping;
  long long points = 0, ok = 0, diverged = 0, errors = 0;
  long long frictionless = 0, frictionless_met = 0, frictionless_met_engines = 0;
  long long friction = 0, friction_met = 0, friction_met_engines = 0;
  double worst_mujoco = 0.0;  // max MuJoCo ↔ converged position distance over ok points
  double worst_ref = 0.0;     // max ref ↔ converged
  std::string heatmap;        // the PNG's file name, empty when none was drawn
};

struct AtlasSummary {
  std::string spec, digest;
  long long points = 0, ok = 0, diverged = 0, errors = 0;
  std::vector<AtlasGroup> groups;
  double max_own_error = 0.0;           // the converged solutions' largest own error, m
  double min_measured = kAtlasNaN;      // the smallest nonzero distance they measure, m
  std::vector<const AtlasRow*> worst;   // largest MuJoCo ↔ converged distances (at most 5)
  std::vector<const AtlasRow*> failed;  // diverged or error (at most 5 shown)
};

AtlasSummary summarize_atlas(const AtlasData& data);

// The colour scale of one heat-map panel: each cell shaded by how many decades
// its distance lies from its row's goal (kAtlasGoalFrictionless without
// friction, kAtlasGoalFriction with), log10(distance / goal), on ±span:
// the whole decades that cover every cell's value (at least 1), so that
// white is the goal, blue meets it and orange misses it, each panel's cells
// told apart on its own scale. Values that are not finite are left out.
double atlas_colour_span(const std::vector<double>& decades_from_goal);

// Heat maps of the maximum position distance over k × ζ, one PNG per body ×
// mapping × damping law, named PREFIX<body>.<mapping>.<damping>.png in
// out_dir (gnuplot); sets each group's heatmap: MuJoCo ↔ converged and
// ref ↔ MuJoCo side by side, the frictionless points (μ = μ_roll = 0) in one
// row and those with friction in another (a row only where the group has
// such points), each panel on its own atlas_colour_span. Cells take the largest distance of their
// points; an axis with more than 12 distinct values is cut into 8 log-spaced bins.
void draw_atlas_heatmaps(const AtlasData& data, AtlasSummary& summary, const std::string& out_dir,
                         const std::string& prefix = "heatmap.");

}  // namespace contact2d::analysis
