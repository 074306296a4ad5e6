// Which points an atlas shard owns, what each of them is, and the files a
// shard's directory holds (analysis/atlas_shard.hpp, analysis/atlas.hpp).
#include "analysis/atlas_shard.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "core/shape.hpp"

namespace contact2d::analysis {
namespace {

namespace fs = std::filesystem;

double total_mass(const Scene& s) {
  if (!shape_features(s.shape).compound) return s.mass;
  double m = 0.0;
  for (const BoxPart& p : (s.parts.empty() ? default_tshape_parts() : s.parts)) m += p.mass;
  return m;
}

void set_total_mass(Scene& s, double m) {
  if (!shape_features(s.shape).compound) {
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

std::string csv_quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : atlas_one_line(text)) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

std::string number_or_empty(double v) { return std::isnan(v) ? "" : format_number(v, 6); }

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
  p.engine = spec.engine.empty() ? "mujoco" : spec.engine;
  if (p.engine != "mujoco" && p.engine != "mujoco3")
    throw InputError(spec.origin + ": atlas.engine = \"" + spec.engine +
                     "\" is not a MuJoCo engine: mujoco (2.2.2, the default) or mujoco3 (3.14)");
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

std::vector<long long> shard_points(const Shard& shard, long long total) {
  std::vector<long long> indices;
  for (long long i = shard.index - 1; i < total; i += shard.count) indices.push_back(i);
  return indices;
}

// -------------------------------------------------------------------- rows

std::string atlas_csv_header() {
  return "index,body,mapping,damping,mass,k,zeta,c,mu,mu_roll,dt,duration,integrator,status,"
         "ref_conv_max_pos,ref_conv_max_angle,mujoco_conv_max_pos,mujoco_conv_max_angle,"
         "ref_mujoco_max_pos,ref_mujoco_max_angle,converged_own_error,message";
}

std::string atlas_csv_row(const AtlasPoint& p, const AtlasResult& r) {
  std::string row = std::to_string(p.index) + "," + p.body + "," + p.mapping + "," +
                    std::string(damping_law_name(p.damping));
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

// ------------------------------------------------------------------- files

std::string shard_text(const Shard& s) {
  return std::to_string(s.index) + "/" + std::to_string(s.count);
}

std::string atlas_one_line(std::string text) {
  for (char& ch : text)
    if (ch == '\n' || ch == '\r') ch = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

void prepare_atlas_dir(const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir))
    throw InputError("--out " + out_dir + ": cannot create directory");
  fs::remove(fs::path(out_dir) / "shard.txt", ec);
}

void write_atlas_file(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  std::fputs(text.c_str(), file.get());
  file.commit();
}

std::string atlas_manifest(const std::string& spec, const std::string& digest, long long points,
                           const Shard& shard, long long rows) {
  return "# contact2d atlas: which points this directory's points.csv holds\n"
         "spec = \"" +
         spec + "\"\ndigest = \"" + digest + "\"\npoints = " + std::to_string(points) +
         "\nshard = \"" + shard_text(shard) + "\"\nrows = " + std::to_string(rows) + "\n";
}

AtlasShardWriter::AtlasShardWriter(const std::string& out_dir) : out_dir_(out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir))
    throw InputError("--out " + out_dir + ": cannot create directory");
  lock_.emplace("--out", out_dir);
  prepare_atlas_dir(out_dir);
  points_csv_.emplace((fs::path(out_dir) / "points.csv").string());
  times_csv_.emplace((fs::path(out_dir) / "times.csv").string());
  std::fprintf(points_csv_->get(), "%s\n", atlas_csv_header().c_str());
  std::fprintf(times_csv_->get(), "%s\n", atlas_times_header().c_str());
}

void AtlasShardWriter::add(size_t position, std::string points_row, std::string times_row) {
  pending_[position] = std::make_pair(std::move(points_row), std::move(times_row));
  for (auto it = pending_.find(next_to_write_); it != pending_.end();
       it = pending_.find(next_to_write_)) {
    std::fprintf(points_csv_->get(), "%s\n", it->second.first.c_str());
    std::fprintf(times_csv_->get(), "%s\n", it->second.second.c_str());
    pending_.erase(it);
    ++next_to_write_;
  }
}

void AtlasShardWriter::finish(const std::string& manifest) {
  points_csv_->commit();
  times_csv_->commit();
  write_atlas_file((fs::path(out_dir_) / "shard.txt").string(), manifest);
}

}  // namespace contact2d::analysis
