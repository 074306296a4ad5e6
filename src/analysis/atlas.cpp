// The fidelity atlas (analysis/atlas.hpp).
#include "analysis/atlas.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include "analysis/engine.hpp"
#include "analysis/reference.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "engines/engines.hpp"
#include "io/csv.hpp"
#include "io/plot.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {
namespace {

namespace fs = std::filesystem;

// Creates OUT (or says it cannot) and removes an older run's shard.txt first:
// shard.txt marks a finished run, so a run that stops halfway leaves no
// directory that looks complete.
void prepare_out_dir(const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir))
    throw InputError("--out " + out_dir + ": cannot create directory");
  fs::remove(fs::path(out_dir) / "shard.txt", ec);
}

double thread_cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double total_mass(const Scene& s) {
  if (s.shape != Shape::TShape) return s.mass;
  double m = 0.0;
  for (const BoxPart& p : (s.parts.empty() ? default_tshape_parts() : s.parts)) m += p.mass;
  return m;
}

void set_total_mass(Scene& s, double m) {
  if (s.shape != Shape::TShape) {
    s.mass = m;
    return;
  }
  if (s.parts.empty()) s.parts = default_tshape_parts();
  const double factor = m / total_mass(s);
  for (BoxPart& p : s.parts) p.mass *= factor;
}

size_t axis_size(const AtlasAxis& a) { return a.values.empty() ? 1 : a.values.size(); }

// A random draw of an axis from u ∈ [0, 1); `fallback` when the axis is not
// given.
double draw(const AtlasAxis& a, double u, double fallback) {
  if (a.log_uniform) return a.min == a.max ? a.min : a.min * std::pow(a.max / a.min, u);
  if (a.values.empty()) return fallback;
  const size_t i =
      std::min(a.values.size() - 1, static_cast<size_t>(u * static_cast<double>(a.values.size())));
  return a.values[i];
}

double pick(const AtlasAxis& a, size_t i, double fallback) {
  return a.values.empty() ? fallback : a.values[i];
}

// The spec's field behind a scene key that failed validation.
std::string field_of(const std::string& key, bool by_zeta) {
  if (key == "body.mass" || key.rfind("body.parts", 0) == 0) return "axes.mass";
  if (key == "contact.k") return "axes.k";
  if (key == "contact.c") return by_zeta ? "axes.zeta" : "axes.c";
  if (key == "contact.mu") return "axes.mu";
  if (key == "contact.mu_roll") return "axes.mu_roll";
  if (key == "sim.dt") return "axes.dt";
  if (key == "sim.duration") return "atlas.duration";
  if (key == "sim.output_dt") return "atlas.output_dt";
  return "atlas.bodies";
}

std::string one_line(std::string text) {
  for (char& ch : text)
    if (ch == '\n' || ch == '\r') ch = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

std::string csv_quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : one_line(text)) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

std::string number_or_empty(double v) { return std::isnan(v) ? "" : format_number(v, 6); }

// MuJoCo 2.2.2's model loading (mj_loadXML: XML parse and compile) is not
// documented as thread safe, so models are created one at a time; stepping
// a model in its own mjData is (every thread has its own).
std::mutex& model_mutex() {
  static std::mutex m;
  return m;
}

engines::EngineRun run_one(const engines::EngineSpec& spec, const Scene& scene) {
  std::unique_ptr<Stepper> stepper;
  if (spec.kind == "ref") {
    stepper = engines::make_stepper(spec, scene);
  } else {
    const std::lock_guard<std::mutex> lock(model_mutex());
    stepper = engines::make_stepper(spec, scene);
  }
  engines::EngineRun run;
  run.engine = spec.name();
  const auto start = std::chrono::steady_clock::now();
  run.trajectory = simulate(*stepper, scene.sim);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.trajectory.divergence)
    run.divergence_message = stepper->explain(*run.trajectory.divergence, scene);
  return run;
}

std::string shard_text(const Shard& s) {
  return std::to_string(s.index) + "/" + std::to_string(s.count);
}

void write_text(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  std::fputs(text.c_str(), file.get());
  file.commit();
}

std::string manifest(const std::string& spec, const std::string& digest, long long points,
                     const Shard& shard, long long rows) {
  return "# contact2d atlas: which points this directory's points.csv holds\n"
         "spec = \"" +
         spec + "\"\ndigest = \"" + digest + "\"\npoints = " + std::to_string(points) +
         "\nshard = \"" + shard_text(shard) + "\"\nrows = " + std::to_string(rows) + "\n";
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
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

// ------------------------------------------------------------------ points

AtlasPoint atlas_point(const AtlasSpec& spec, long long index) {
  AtlasPoint p;
  p.index = index;
  long long rest = index;
  const long long per_combo = spec.random ? spec.count : [&] {
    long long n = 1;
    for (const AtlasAxis* a :
         {&spec.mass, &spec.k, &spec.damping_value, &spec.mu, &spec.mu_roll, &spec.dt})
      n *= static_cast<long long>(axis_size(*a));
    return n;
  }();
  const long long within = rest % per_combo;
  rest /= per_combo;
  const size_t d = static_cast<size_t>(rest % static_cast<long long>(spec.damping.size()));
  rest /= static_cast<long long>(spec.damping.size());
  const size_t m = static_cast<size_t>(rest % static_cast<long long>(spec.mappings.size()));
  rest /= static_cast<long long>(spec.mappings.size());
  const AtlasBody& body = spec.bodies.at(static_cast<size_t>(rest));
  p.body = body.label;
  p.mapping = spec.mappings[m];
  p.damping = spec.damping[d];
  Scene s = body.scene;
  const double base_mass = total_mass(s);
  const double base_damping =
      spec.by_zeta ? s.contact.c / (2.0 * std::sqrt(s.contact.k * base_mass)) : s.contact.c;
  double damping_value = 0.0;
  if (spec.random) {
    // Sample `within` from its own stream: the same point whatever else runs.
    std::uint64_t state = spec.seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(within);
    splitmix64(state);
    auto u = [&state] { return next_uniform(state); };
    // One draw per axis, in a fixed order, given or not: fixing one axis
    // leaves the others' draws unchanged.
    p.mass = draw(spec.mass, u(), base_mass);
    p.k = draw(spec.k, u(), s.contact.k);
    damping_value = draw(spec.damping_value, u(), base_damping);
    p.mu = draw(spec.mu, u(), s.contact.mu);
    p.mu_roll = draw(spec.mu_roll, u(), s.contact.mu_roll);
    p.dt = draw(spec.dt, u(), s.sim.dt);
  } else {
    // The last axis varies fastest.
    long long r = within;
    auto next = [&r](const AtlasAxis& a) {
      const long long n = static_cast<long long>(axis_size(a));
      const size_t i = static_cast<size_t>(r % n);
      r /= n;
      return i;
    };
    const size_t i_dt = next(spec.dt), i_mu_roll = next(spec.mu_roll), i_mu = next(spec.mu);
    const size_t i_damping = next(spec.damping_value), i_k = next(spec.k), i_mass = next(spec.mass);
    p.mass = pick(spec.mass, i_mass, base_mass);
    p.k = pick(spec.k, i_k, s.contact.k);
    damping_value = pick(spec.damping_value, i_damping, base_damping);
    p.mu = pick(spec.mu, i_mu, s.contact.mu);
    p.mu_roll = pick(spec.mu_roll, i_mu_roll, s.contact.mu_roll);
    p.dt = pick(spec.dt, i_dt, s.sim.dt);
  }
  const double scale = 2.0 * std::sqrt(p.k * p.mass);
  p.c = spec.by_zeta ? damping_value * scale : damping_value;
  p.zeta = spec.by_zeta ? damping_value : (scale > 0.0 ? p.c / scale : kAtlasNaN);
  set_total_mass(s, p.mass);
  s.contact.k = p.k;
  s.contact.c = p.c;
  s.contact.mu = p.mu;
  s.contact.mu_roll = p.mu_roll;
  s.contact.damping = p.damping;
  s.sim.dt = p.dt;
  s.sim.duration = spec.duration;
  s.sim.output_dt = spec.output_dt;
  s.sim.integrator = spec.integrator;
  if (const std::optional<ValidationError> e = validate(s)) {
    const std::string field = field_of(e->key, spec.by_zeta);
    const std::string gives = field == "axes.zeta" ? " gives contact.c = 2·zeta·sqrt(k·m) = "
                                                   : " gives " + e->key + " = ";
    throw InputError(spec.origin + ": point " + std::to_string(index) + " (" + p.body + "): " +
                     field + gives + format_number(e->value) + ", out of range: " + e->range);
  }
  p.scene = std::move(s);
  return p;
}

Shard parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  auto bad = [&text] {
    return InputError("--shard " + text + ": must be I/N with 1 <= I <= N <= 1000000, e.g. 2/4");
  };
  if (slash == std::string::npos) throw bad();
  const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
  auto integer = [&](const std::string& s) {
    if (s.empty() || s.size() > 7 || s.find_first_not_of("0123456789") != std::string::npos)
      throw bad();
    return std::stoll(s);
  };
  Shard shard{integer(a), integer(b)};
  if (shard.index < 1 || shard.count < 1 || shard.index > shard.count || shard.count > 1000000)
    throw bad();
  return shard;
}

// -------------------------------------------------------------------- run

AtlasResult run_atlas_point(const AtlasPoint& point, double converged_tol) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_seconds();
  AtlasResult r;
  r.index = point.index;
  std::vector<std::string> errors, divergences;
  std::optional<engines::EngineRun> ref, mujoco;
  engines::EngineSpec ref_spec;
  engines::EngineSpec mj_spec;
  mj_spec.kind = "mujoco";
  mj_spec.mapping = point.mapping;
  mj_spec.source = "atlas point " + std::to_string(point.index);
  for (const auto* spec : {&ref_spec, &mj_spec}) {
    const bool is_ref = spec == &ref_spec;
    std::optional<engines::EngineRun>& slot = is_ref ? ref : mujoco;
    const double cpu = thread_cpu_seconds();
    try {
      slot = run_one(*spec, point.scene);
      if (slot->trajectory.divergence) {
        divergences.push_back(spec->kind + " diverged: " + one_line(slot->divergence_message));
      }
    } catch (const std::exception& e) {
      errors.push_back(spec->kind + ": " + one_line(e.what()));
      slot.reset();
    }
    (is_ref ? r.ref_seconds : r.mujoco_seconds) = thread_cpu_seconds() - cpu;
  }
  const double cpu_converged = thread_cpu_seconds();
  const DenseTrajectory converged = converged_reference(point.scene, converged_tol);
  std::optional<DenseTrajectory> coarser;
  if (converged.ok()) coarser = converged_reference(point.scene, 10.0 * converged_tol);
  r.converged_seconds = thread_cpu_seconds() - cpu_converged;
  if (!converged.ok()) errors.push_back("converged solution: " + one_line(converged.failure()));
  const bool ref_ok = ref && !ref->trajectory.divergence;
  const bool mj_ok = mujoco && !mujoco->trajectory.divergence;
  if (converged.ok()) {
    if (coarser->ok())
      r.converged_own_error =
          error_between(converged, *coarser, output_times(point.scene.sim)).max_pos;
    if (ref_ok) {
      const TrajectoryError e = error_against(ref->trajectory, converged);
      r.ref_conv_pos = e.max_pos;
      r.ref_conv_angle = e.max_angle;
    }
    if (mj_ok) {
      const TrajectoryError e = error_against(mujoco->trajectory, converged);
      r.mujoco_conv_pos = e.max_pos;
      r.mujoco_conv_angle = e.max_angle;
    }
  }
  if (ref_ok && mj_ok) {
    const TrajectoryError e = error_between(ref->trajectory, mujoco->trajectory);
    r.ref_mujoco_pos = e.max_pos;
    r.ref_mujoco_angle = e.max_angle;
  }
  std::vector<std::string> all = errors;
  all.insert(all.end(), divergences.begin(), divergences.end());
  r.status = !errors.empty() ? "error" : !divergences.empty() ? "diverged" : "ok";
  for (const std::string& m : all) r.message += (r.message.empty() ? "" : "; ") + m;
  r.cpu_seconds = thread_cpu_seconds() - cpu0;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

std::string atlas_csv_header() {
  return "index,body,mapping,damping,mass,k,zeta,c,mu,mu_roll,dt,duration,integrator,status,"
         "ref_conv_max_pos,ref_conv_max_angle,mujoco_conv_max_pos,mujoco_conv_max_angle,"
         "ref_mujoco_max_pos,ref_mujoco_max_angle,converged_own_error,message";
}

std::string atlas_csv_row(const AtlasPoint& p, const AtlasResult& r) {
  std::string row =
      std::to_string(p.index) + "," + p.body + "," + p.mapping + "," + damping_law_name(p.damping);
  for (double v : {p.mass, p.k, p.zeta, p.c, p.mu, p.mu_roll, p.dt, p.scene.sim.duration})
    row += "," + (std::isnan(v) ? std::string() : format_shortest(v, 6));
  row += "," + std::string(integrator_name(p.scene.sim.integrator)) + "," + r.status;
  for (double v : {r.ref_conv_pos, r.ref_conv_angle, r.mujoco_conv_pos, r.mujoco_conv_angle,
                   r.ref_mujoco_pos, r.ref_mujoco_angle, r.converged_own_error})
    row += "," + number_or_empty(v);
  row += "," + (r.message.empty() ? std::string() : csv_quoted(r.message));
  return row;
}

std::string atlas_times_header() {
  return "index,ref_cpu_s,mujoco_cpu_s,converged_cpu_s,point_cpu_s,point_wall_s";
}

std::string atlas_times_row(const AtlasResult& r) {
  return std::to_string(r.index) + "," + format_number(r.ref_seconds, 4) + "," +
         format_number(r.mujoco_seconds, 4) + "," + format_number(r.converged_seconds, 4) + "," +
         format_number(r.cpu_seconds, 4) + "," + format_number(r.wall_seconds, 4);
}

AtlasRunStats run_atlas(const AtlasSpec& spec, const std::string& out_dir,
                        const AtlasRunOptions& options) {
  const long long total = atlas_point_count(spec);
  std::vector<long long> indices;
  for (long long i = options.shard.index - 1; i < total; i += options.shard.count)
    indices.push_back(i);
  // Every point is checked before anything is written or run.
  for (long long i : indices) atlas_point(spec, i);

  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir))
    throw InputError("--out " + out_dir + ": cannot create directory");
  // Two shards run into one --out would overwrite each other's files: the
  // second one stops here, before it touches any (docs/atlas.md).
  const DirectoryLock lock("--out", out_dir);
  prepare_out_dir(out_dir);
  AtomicFile points_csv((fs::path(out_dir) / "points.csv").string());
  AtomicFile times_csv((fs::path(out_dir) / "times.csv").string());
  std::fprintf(points_csv.get(), "%s\n", atlas_csv_header().c_str());
  std::fprintf(times_csv.get(), "%s\n", atlas_times_header().c_str());

  AtlasRunStats stats;
  stats.points = static_cast<long long>(indices.size());
  // Rows are written in index order as soon as every earlier row is done;
  // only the rows waiting for an earlier one are held (the pool hands out
  // points in order, so about one per thread).
  std::map<size_t, std::pair<std::string, std::string>> pending;
  size_t next_to_write = 0, done = 0;
  std::mutex mutex;
  const auto start = std::chrono::steady_clock::now();
  parallel_for(indices.size(), options.threads, [&](size_t i) {
    const AtlasPoint point = atlas_point(spec, indices[i]);
    const AtlasResult result = run_atlas_point(point, spec.converged_tol);
    const std::lock_guard<std::mutex> lock(mutex);
    pending[i] = std::make_pair(atlas_csv_row(point, result), atlas_times_row(result));
    for (auto it = pending.find(next_to_write); it != pending.end();
         it = pending.find(next_to_write)) {
      std::fprintf(points_csv.get(), "%s\n", it->second.first.c_str());
      std::fprintf(times_csv.get(), "%s\n", it->second.second.c_str());
      pending.erase(it);
      ++next_to_write;
    }
    ++done;
    stats.cpu_seconds += result.cpu_seconds;
    if (result.status == "ok") ++stats.ok;
    if (result.status == "diverged") ++stats.diverged;
    if (result.status == "error") ++stats.errors;
    if (options.progress)
      options.progress(done, indices.size(),
                       "point " + std::to_string(point.index) + " " + point.body + " " +
                           point.mapping + " k " + format_number(point.k, 3) + " ζ " +
                           format_number(point.zeta, 3));
  });
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  points_csv.commit();
  times_csv.commit();
  write_text((fs::path(out_dir) / "shard.txt").string(),
             manifest(spec.origin, spec.digest, total, options.shard, stats.points));
  return stats;
}

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
  prepare_out_dir(out_dir);
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
  write_text((fs::path(out_dir) / "shard.txt").string(),
             manifest(data.spec, data.digest, data.points, Shard{}, data.points));
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

AtlasColourRange atlas_colour_range(const AtlasData& data, const std::string& body) {
  Extent range;
  for (const AtlasRow& r : data.rows) {
    if (r.body != body || r.status != "ok") continue;
    for (double v : {r.mujoco_conv_pos, r.ref_mujoco_pos})
      if (v > 0.0) range.add(std::log10(v));
  }
  AtlasColourRange c;
  c.lo = std::isfinite(range.lo) ? std::floor(range.lo) : -16.0;
  c.hi = std::isfinite(range.hi) ? std::max(std::ceil(range.hi), c.lo + 1.0) : c.lo + 1.0;
  return c;
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
    // One colour scale for every map of the body (all its mappings, laws,
    // with and without friction): a colour means the same error on each.
    const AtlasColourRange range = atlas_colour_range(data, g.body);
    const double lo = range.lo, hi = range.hi;
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
            // Columns: k cell, ζ cell, log10 of the distance (an exact 0 at
            // the bottom of the colour range), the label.
            const double shade = w > 0.0 ? std::log10(w) : lo;
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
                      g.damping +
                      " (largest over the other axes in each cell; colour scale "
                      "shared by every map of " +
                      g.body + ")")
      << "' font ',13'\n"
      << "set xlabel 'k (N/m)'\nset ylabel 'ζ = c/(2√(k·m))'\n"
      << "set xrange [-0.5:" << static_cast<double>(kc.size()) - 0.5
      << "]\nset yrange [-0.5:" << static_cast<double>(zc.size()) - 0.5 << "]\n"
      << tics("x", kc) << (kc.size() > 5 ? "set xtics rotate by -30\n" : "") << tics("y", zc)
      << "set cbrange [" << lo << ":" << hi << "]\n"
      << "set cblabel 'log_{10} of the max position error (m)'\n"
      << "set palette defined (0 '#0072B2', 0.5 '#F0E442', 1 '#D55E00')\n"
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

std::string atlas_summary_markdown(const AtlasSummary& s, const std::string& image_dir) {
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
     << format_number(kAtlasGoalFrictionless) << " m without friction (μ = μ_roll = 0) or "
     << format_number(kAtlasGoalFriction)
     << " m with friction; the \"ref ↔ MuJoCo\" columns apply the same goals to the distance "
        "between the engines. A point that diverged or failed does not meet them.\n\n"
     << "| body | mapping | damping | points | diverged, failed | frictionless: MuJoCo ↔ "
        "converged | ref ↔ MuJoCo | friction: MuJoCo ↔ converged | ref ↔ MuJoCo | largest "
        "MuJoCo ↔ converged (m) | largest ref ↔ converged (m) |\n"
     << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const AtlasGroup& g : s.groups) {
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
    for (const AtlasRow* r : s.worst)
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
      const AtlasRow* r = s.failed[i];
      std::string message = split_csv_line(r->line).back();
      if (message.size() > 200) message = message.substr(0, 200) + " …";
      for (char& ch : message)
        if (ch == '|') ch = '/';
      md << "| " << r->index << " | " << r->body << " | " << r->mapping << " | " << r->status
         << " | " << message << " |\n";
    }
    if (s.failed.size() > 5) md << "\n(" << s.failed.size() - 5 << " more in points.csv.)\n";
  }
  bool any = false;
  for (const AtlasGroup& g : s.groups) any = any || !g.heatmap.empty();
  if (any) {
    md << "\n## Heat maps over k × ζ\n\n"
       << "Left, MuJoCo against the converged solution (its step error included); right, the "
          "two engines against each other at the same Δt; the points without friction "
          "(μ = μ_roll = 0) in the top row, those with friction below. Each cell shows the largest "
          "maximum position error of its points (over the other axes); \"diverged\" marks a cell "
          "whose points all failed, \"*\" one where some did. The maps of one body share one "
          "colour scale.\n\n";
    for (const AtlasGroup& g : s.groups)
      if (!g.heatmap.empty())
        md << "![" << g.body << ", " << g.mapping << ", " << g.damping << "](" << image_dir
           << g.heatmap << ")\n\n";
  }
  return md.str();
}

}  // namespace contact2d::analysis
