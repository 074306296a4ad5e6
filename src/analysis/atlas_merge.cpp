// Merging atlas shards (analysis/atlas.hpp): reading shard directories back,
// checking that together they hold every point once, writing the merged
// directory, and the summary's numbers and heat maps (gnuplot) drawn from
// the merged rows. The summary's page text is the report's
// (report/atlas_page.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "analysis/atlas.hpp"
#include "analysis/atlas_shard.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/plot.hpp"
#include "io/read_file.hpp"

namespace contact2d::analysis {
namespace {

namespace fs = std::filesystem;

// A shard's files, bounded as every input is (io/read_file.hpp): its
// points.csv holds one row per point (158 bytes on average in the report's
// atlas), so 256 MiB is over a million points in one shard.
constexpr std::size_t kMaxShardFileBytes = 256u << 20;

std::string slurp(const std::string& path) {
  return read_input_file(path, "an atlas shard's file", kMaxShardFileBytes,
                         "larger than 256 MiB: not a shard's file, or a device or FIFO");
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

double parse_double(const std::string& field) {
  if (field.empty()) return kAtlasNaN;
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end != field.c_str() + field.size()) throw std::invalid_argument(field);
  return v;
}

}  // namespace

// ------------------------------------------------------------------ merge

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        out.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      out.emplace_back();
    } else {
      out.back() += ch;
    }
  }
  return out;
}

AtlasRow parse_atlas_row(const std::string& line, const std::string& origin) {
  const std::vector<std::string> f = split_csv_line(line);
  if (f.size() != 22)
    throw InputError(origin + ": a row of " + std::to_string(f.size()) +
                     " fields, expected 22: " + line.substr(0, 60));
  AtlasRow row;
  row.line = line;
  try {
    size_t used = 0;
    row.index = std::stoll(f[0], &used);
    if (used != f[0].size() || row.index < 0) throw std::invalid_argument(f[0]);
    row.body = f[1];
    row.mapping = f[2];
    row.damping = f[3];
    row.mass = parse_double(f[4]);
    row.k = parse_double(f[5]);
    row.zeta = parse_double(f[6]);
    row.c = parse_double(f[7]);
    row.mu = parse_double(f[8]);
    row.mu_roll = parse_double(f[9]);
    row.dt = parse_double(f[10]);
    row.status = f[13];
    row.ref_conv_pos = parse_double(f[14]);
    row.ref_conv_angle = parse_double(f[15]);
    row.mujoco_conv_pos = parse_double(f[16]);
    row.mujoco_conv_angle = parse_double(f[17]);
    row.ref_mujoco_pos = parse_double(f[18]);
    row.ref_mujoco_angle = parse_double(f[19]);
    row.converged_own_error = parse_double(f[20]);
  } catch (const std::exception&) {
    throw InputError(origin + ": a row with a field that is not a number: " + line.substr(0, 60));
  }
  if (row.status != "ok" && row.status != "diverged" && row.status != "error")
    throw InputError(origin + ": point " + f[0] + ": status '" + row.status +
                     "' (expected ok, diverged or error)");
  return row;
}

AtlasData read_atlas_shards(const std::vector<std::string>& dirs) {
  if (dirs.empty()) throw InputError("atlas merge: no directory given");
  AtlasData data;
  struct Source {
    std::string dir;
    Shard shard;
  };
  std::vector<Source> sources;
  std::map<long long, size_t> owner;  // point → its source
  std::map<long long, std::string> times;
  bool all_times = true;
  for (const std::string& dir : dirs) {
    const std::string manifest_path = (fs::path(dir) / "shard.txt").string();
    const std::string csv_path = (fs::path(dir) / "points.csv").string();
    if (!fs::exists(manifest_path))
      throw InputError(dir +
                       ": no shard.txt: not the output of contact2d atlas, or its run did "
                       "not finish");
    std::map<std::string, std::string> keys;
    for (const std::string& line : lines_of(slurp(manifest_path))) {
      if (line.empty() || line[0] == '#') continue;
      const size_t eq = line.find(" = ");
      if (eq == std::string::npos) throw InputError(manifest_path + ": not a shard file: " + line);
      std::string value = line.substr(eq + 3);
      if (value.size() >= 2 && value.front() == '"') value = value.substr(1, value.size() - 2);
      keys[line.substr(0, eq)] = value;
    }
    for (const char* key : {"spec", "digest", "points", "shard", "rows"})
      if (!keys.count(key)) throw InputError(manifest_path + ": no '" + key + "'");
    Source source{dir, Shard{}};
    long long points = 0, rows = 0;
    try {
      source.shard = parse_shard(keys["shard"]);
      points = std::stoll(keys["points"]);
      rows = std::stoll(keys["rows"]);
    } catch (const std::exception&) {
      throw InputError(manifest_path + ": a bad shard, points or rows value");
    }
    if (sources.empty()) {
      data.spec = keys["spec"];
      data.digest = keys["digest"];
      data.points = points;
    } else if (keys["digest"] != data.digest || points != data.points) {
      throw InputError(dir + ": a shard of another spec (" + keys["spec"] + ", digest " +
                       keys["digest"] + ", " + std::to_string(points) + " points) than " +
                       sources.front().dir + " (" + data.spec + ", digest " + data.digest + ", " +
                       std::to_string(data.points) + " points)");
    }
    if (!fs::exists(csv_path)) throw InputError(dir + ": no points.csv");
    const std::vector<std::string> lines = lines_of(slurp(csv_path));
    if (lines.empty() || lines.front() != atlas_csv_header())
      throw InputError(csv_path + ": not an atlas points.csv (its header differs)");
    if (static_cast<long long>(lines.size()) - 1 != rows)
      throw InputError(csv_path + ": " + std::to_string(lines.size() - 1) +
                       " rows, shard.txt says " + std::to_string(rows) + " (a damaged file?)");
    for (size_t i = 1; i < lines.size(); ++i) {
      AtlasRow row = parse_atlas_row(lines[i], csv_path);
      if (row.index >= data.points || !source.shard.holds(row.index))
        throw InputError(csv_path + ": point " + std::to_string(row.index) +
                         " does not belong to shard " + shard_text(source.shard) + " of " +
                         std::to_string(data.points) + " points");
      const auto [it, fresh] = owner.emplace(row.index, sources.size());
      if (!fresh)
        throw InputError("atlas merge: point " + std::to_string(row.index) + " is in both " +
                         sources[it->second].dir + " (shard " +
                         shard_text(sources[it->second].shard) + ") and " + dir + " (shard " +
                         shard_text(source.shard) + "): a shard given twice?");
      data.rows.push_back(std::move(row));
    }
    const std::string times_path = (fs::path(dir) / "times.csv").string();
    if (fs::exists(times_path)) {
      const std::vector<std::string> t = lines_of(slurp(times_path));
      for (size_t i = 1; i < t.size(); ++i) {
        char* end = nullptr;
        const long long index = std::strtoll(t[i].c_str(), &end, 10);
        if (end == t[i].c_str() || *end != ',')
          throw InputError(times_path + ": line " + std::to_string(i + 1) +
                           " does not start with a point index");
        times[index] = t[i];
      }
    } else {
      all_times = false;
    }
    sources.push_back(source);
  }
  if (static_cast<long long>(owner.size()) != data.points) {
    std::vector<long long> missing;
    for (long long i = 0; i < data.points; ++i)
      if (!owner.count(i)) missing.push_back(i);
    std::string list;
    for (size_t i = 0; i < missing.size() && i < 8; ++i)
      list += (i ? ", " : "") + std::to_string(missing[i]);
    if (missing.size() > 8) list += ", …";
    // The shards (of the first directory's N) that no directory covers.
    std::string shards;
    const long long n = sources.front().shard.count;
    std::set<long long> given;
    for (const Source& s : sources)
      if (s.shard.count == n) given.insert(s.shard.index);
    for (long long i = 1; i <= n; ++i)
      if (!given.count(i))
        shards += (shards.empty() ? "" : ", ") + std::to_string(i) + "/" + std::to_string(n);
    throw InputError("atlas merge: " + std::to_string(missing.size()) + " of " +
                     std::to_string(data.points) + " points missing (" + list + ")" +
                     (shards.empty() ? "" : ": shard " + shards + " not given"));
  }
  std::sort(data.rows.begin(), data.rows.end(),
            [](const AtlasRow& a, const AtlasRow& b) { return a.index < b.index; });
  if (all_times && static_cast<long long>(times.size()) == data.points)
    for (const auto& [index, line] : times) data.times.push_back(line);
  return data;
}

void write_atlas_data(const AtlasData& data, const std::string& out_dir) {
  prepare_atlas_dir(out_dir);
  {
    AtomicFile csv((fs::path(out_dir) / "points.csv").string());
    std::fprintf(csv.get(), "%s\n", atlas_csv_header().c_str());
    for (const AtlasRow& row : data.rows) std::fprintf(csv.get(), "%s\n", row.line.c_str());
    csv.commit();
  }
  if (!data.times.empty()) {
    AtomicFile csv((fs::path(out_dir) / "times.csv").string());
    std::fprintf(csv.get(), "%s\n", atlas_times_header().c_str());
    for (const std::string& line : data.times) std::fprintf(csv.get(), "%s\n", line.c_str());
    csv.commit();
  }
  write_atlas_file((fs::path(out_dir) / "shard.txt").string(),
                   atlas_manifest(data.spec, data.digest, data.points, Shard{}, data.points));
}

// ---------------------------------------------------------------- summary

AtlasSummary summarize_atlas(const AtlasData& data) {
  AtlasSummary s;
  s.spec = data.spec;
  s.digest = data.digest;
  s.points = static_cast<long long>(data.rows.size());
  auto group_of = [&s](const AtlasRow& row) -> AtlasGroup& {
    for (AtlasGroup& g : s.groups)
      if (g.body == row.body && g.mapping == row.mapping && g.damping == row.damping) return g;
    AtlasGroup g;
    g.body = row.body;
    g.mapping = row.mapping;
    g.damping = row.damping;
    s.groups.push_back(g);
    return s.groups.back();
  };
  for (const AtlasRow& row : data.rows) {
    AtlasGroup& g = group_of(row);
    ++g.points;
    const bool ok = row.status == "ok";
    if (ok) ++g.ok, ++s.ok;
    if (row.status == "diverged") ++g.diverged, ++s.diverged;
    if (row.status == "error") ++g.errors, ++s.errors;
    const bool frictionless = row.mu == 0.0 && row.mu_roll == 0.0;
    const double goal = frictionless ? kAtlasGoalFrictionless : kAtlasGoalFriction;
    (frictionless ? g.frictionless : g.friction) += 1;
    if (ok && row.mujoco_conv_pos <= goal)
      (frictionless ? g.frictionless_met : g.friction_met) += 1;
    if (ok && row.ref_mujoco_pos <= goal)
      (frictionless ? g.frictionless_met_engines : g.friction_met_engines) += 1;
    if (ok) {
      if (row.mujoco_conv_pos > g.worst_mujoco) g.worst_mujoco = row.mujoco_conv_pos;
      if (row.ref_conv_pos > g.worst_ref) g.worst_ref = row.ref_conv_pos;
      if (row.converged_own_error > s.max_own_error) s.max_own_error = row.converged_own_error;
      for (double v : {row.ref_conv_pos, row.mujoco_conv_pos})
        if (v > 0.0 && !(v >= s.min_measured)) s.min_measured = v;
      s.worst.push_back(&row);
    } else {
      s.failed.push_back(&row);
    }
  }
  std::stable_sort(s.worst.begin(), s.worst.end(), [](const AtlasRow* a, const AtlasRow* b) {
    return a->mujoco_conv_pos > b->mujoco_conv_pos;
  });
  if (s.worst.size() > 5) s.worst.resize(5);
  return s;
}

namespace {

// The cells of one heat-map axis: the distinct values, or 8 log-spaced bins
// when there are more than 12.
struct Cells {
  std::vector<double> values;  // distinct values (empty when binned)
  double lo = 0.0, hi = 0.0;   // binned: the range
  size_t size() const { return values.empty() ? 8 : values.size(); }
  size_t cell(double v) const {
    if (!values.empty())
      return static_cast<size_t>(std::lower_bound(values.begin(), values.end(), v) -
                                 values.begin());
    if (!(hi > lo) || !(v > lo)) return 0;
    const double f = lo > 0.0 ? std::log(v / lo) / std::log(hi / lo) : (v - lo) / (hi - lo);
    return std::min<size_t>(7, static_cast<size_t>(f * 8.0));
  }
  std::string label(size_t i) const {
    if (!values.empty()) return format_number(values[i], 3);
    const double f = (static_cast<double>(i) + 0.5) / 8.0;
    return format_number(lo > 0.0 ? lo * std::pow(hi / lo, f) : lo + f * (hi - lo), 2);
  }
};

Cells cells_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  Cells c;
  if (v.size() <= 12) {
    c.values = v;
  } else {
    c.lo = v.front();
    c.hi = v.back();
  }
  return c;
}

std::string tics(const char* axis, const Cells& c) {
  std::string out = std::string("set ") + axis + "tics (";
  for (size_t i = 0; i < c.size(); ++i)
    out += (i ? ", " : "") + std::string("'") + c.label(i) + "' " + std::to_string(i);
  return out + ")\n";
}

}  // namespace

double atlas_colour_span(const std::vector<double>& decades_from_goal) {
  double span = 1.0;
  for (double d : decades_from_goal)
    if (std::isfinite(d)) span = std::max(span, std::ceil(std::abs(d)));
  return span;
}

void draw_atlas_heatmaps(const AtlasData& data, AtlasSummary& summary, const std::string& out_dir,
                         const std::string& prefix) {
  for (AtlasGroup& g : summary.groups) {
    std::vector<const AtlasRow*> rows;
    for (const AtlasRow& row : data.rows)
      if (row.body == g.body && row.mapping == g.mapping && row.damping == g.damping)
        rows.push_back(&row);
    std::vector<double> ks, zetas;
    for (const AtlasRow* r : rows) {
      ks.push_back(r->k);
      zetas.push_back(r->zeta);
    }
    const Cells kc = cells_of(ks), zc = cells_of(zetas);
    // Panels: MuJoCo ↔ converged and ref ↔ MuJoCo (columns), without and
    // with friction (rows, where the group has such points). Per cell: the
    // largest distance of its ok points, and whether any point failed.
    const size_t n = kc.size() * zc.size();
    enum { kFrictionless, kFriction };
    std::vector<double> worst[2][2];
    std::vector<bool> failed[2] = {std::vector<bool>(n, false), std::vector<bool>(n, false)};
    bool present[2] = {false, false};
    for (auto& by_friction : worst)
      for (auto& w : by_friction) w.assign(n, -1.0);
    for (const AtlasRow* r : rows) {
      const int f = r->mu == 0.0 && r->mu_roll == 0.0 ? kFrictionless : kFriction;
      present[f] = true;
      const size_t i = kc.cell(r->k) * zc.size() + zc.cell(r->zeta);
      if (r->status != "ok") {
        failed[f][i] = true;
        continue;
      }
      const double values[2] = {r->mujoco_conv_pos, r->ref_mujoco_pos};
      for (int panel = 0; panel < 2; ++panel)
        if (!std::isnan(values[panel]))
          worst[f][panel][i] = std::max(worst[f][panel][i], values[panel]);
    }
    // Each cell's decades from its row's goal, on each panel's own ±span.
    const double goals[2] = {kAtlasGoalFrictionless, kAtlasGoalFriction};
    double spans[2][2];
    for (int f : {kFrictionless, kFriction}) {
      for (int panel = 0; panel < 2; ++panel) {
        std::vector<double> decades;
        for (double v : worst[f][panel])
          if (v > 0.0) decades.push_back(std::log10(v / goals[f]));
        spans[f][panel] = atlas_colour_span(decades);
      }
    }
    const std::string file = prefix + g.body + "." + g.mapping + "." + g.damping + ".png";
    const std::string png_path = (fs::path(out_dir) / file).string();
    AtomicFile png(png_path);
    std::vector<int> shown;  // friction rows drawn
    for (int f : {kFrictionless, kFriction})
      if (present[f]) shown.push_back(f);
    std::unique_ptr<AtomicFile> dat[2][2];
    for (int f : shown) {
      for (int panel = 0; panel < 2; ++panel) {
        auto& file_ptr = dat[f][panel];
        file_ptr = std::make_unique<AtomicFile>(png_path + ".data" + std::to_string(2 * f + panel));
        for (size_t ki = 0; ki < kc.size(); ++ki) {
          for (size_t zi = 0; zi < zc.size(); ++zi) {
            const size_t i = ki * zc.size() + zi;
            const double w = worst[f][panel][i];
            std::string label =
                w < 0.0 ? (failed[f][i] ? "diverged" : "") : format_number("%.0e", w);
            if (w >= 0.0 && failed[f][i]) label += "*";
            // Columns: k cell, ζ cell, decades from the goal (an exact 0 at
            // the bottom of the colour range), the label.
            const double shade = w > 0.0 ? std::log10(w / goals[f]) : -spans[f][panel];
            if (w >= 0.0)
              std::fprintf(file_ptr->get(), "%zu %zu %.6g \"%s\"\n", ki, zi, shade, label.c_str());
            else if (!label.empty())
              std::fprintf(file_ptr->get(), "%zu %zu NaN \"%s\"\n", ki, zi, label.c_str());
          }
        }
        // gnuplot refuses a data file without a point: one outside the range.
        std::fprintf(file_ptr->get(), "-10 -10 NaN \"\"\n");
        if (std::fflush(file_ptr->get()) != 0)
          throw InputError(file_ptr->temp_path() + ": cannot write");
      }
    }
    const int panel_rows = static_cast<int>(shown.size());
    const int height = 80 + 540 * panel_rows;
    const double row_height = 540.0 / height, top = 1.0 - 60.0 / height;
    std::ostringstream s;
    s << gnuplot_png(png.temp_path(), 1400, height) << "set multiplot title '"
      << gnuplot_text("max position error over k × ζ: " + g.body + ", " + g.mapping + " mapping, " +
                      g.damping + " (largest over the other axes in each cell)")
      << "' font ',13'\n"
      << "set xlabel 'k (N/m)'\nset ylabel 'ζ = c/(2√(k·m))'\n"
      << "set xrange [-0.5:" << static_cast<double>(kc.size()) - 0.5
      << "]\nset yrange [-0.5:" << static_cast<double>(zc.size()) - 0.5 << "]\n"
      << tics("x", kc) << (kc.size() > 5 ? "set xtics rotate by -30\n" : "") << tics("y", zc)
      << "set palette defined (0 '#0072B2', 0.5 '#FFFFFF', 1 '#D55E00')\n"
      << "unset key\nset tics nomirror\n";
    const char* titles[2] = {"MuJoCo ↔ converged solution", "ref ↔ MuJoCo (same Δt)"};
    for (int row = 0; row < panel_rows; ++row) {
      const int f = shown[static_cast<size_t>(row)];
      for (int panel = 0; panel < 2; ++panel) {
        const std::string d = gnuplot_quoted(dat[f][panel]->temp_path());
        s << "set size 0.5," << row_height << "\nset origin " << 0.5 * panel << ","
          << top - row_height * (row + 1) << "\n"
          << "set title '"
          << gnuplot_text(std::string(titles[panel]) +
                          (f == kFrictionless ? ", without friction (μ = μ_roll = 0)"
                                              : ", with friction (largest over μ > 0)"))
          << "'\n"
          << "set cbrange [" << -spans[f][panel] << ":" << spans[f][panel] << "]\n"
          << "set cblabel 'decades from the goal " << format_number("%.0e", goals[f])
          << " m: log_{10}(error / goal); blue meets it'\n"
          << "plot " << d
          << " using 1:2:(0.5):(0.5):3 with boxxyerror fill solid 1.0 noborder lc palette, " << d
          << " using 1:2:4 with labels font ',10'\n";
      }
    }
    s << "unset multiplot\n";
    run_gnuplot(s.str(), png_path);
    png.commit();
    g.heatmap = file;
  }
}

}  // namespace contact2d::analysis
