// The atlas spec (io/atlas_spec.hpp).
#include "io/atlas_spec.hpp"

#include "io/read_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/format.hpp"
#include "core/rng.hpp"
#include "io/scene_file.hpp"
#include "io/toml_table.hpp"

namespace contact2d {
namespace {

// A parameter's allowed range, as checked and as written in messages.
struct Range {
  double lo, hi;
  bool lo_open;
  const char* text;  // e.g. "(0, 1e12] N/m"
  bool holds(double v) const { return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi; }
};

const Range kMass{0.0, 1e9, true, "(0, 1e9] kg"};
const Range kK{0.0, 1e12, true, "(0, 1e12] N/m"};
const Range kZeta{0.0, 1e3, false, "[0, 1e3]"};
const Range kC{0.0, 1e9, false, "[0, 1e9] N·s/m"};
const Range kMu{0.0, 100.0, false, "[0, 100]"};
const Range kMuRoll{0.0, 10.0, false, "[0, 10] m"};
const Range kDt{0.0, 1.0, true, "(0, 1] s"};
const Range kDuration{0.0, 1e4, true, "(0, 1e4] s"};
const Range kTol{1e-14, 1e-6, false, "[1e-14, 1e-6]"};

const char* const kMappings[] = {"seed", "exact", "calibrated", "compensated"};

[[noreturn]] void fail(const std::string& origin, const std::string& field,
                       const std::string& why) {
  throw InputError(origin + ": " + field + " " + why);
}

double number_of(const toml::node& node, const std::string& origin, const std::string& field) {
  if (const auto* f = node.as_floating_point()) return f->get();
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  fail(origin, field, "must be a number");
}

void check(double v, const Range& range, const std::string& origin, const std::string& field) {
  if (!range.holds(v))
    fail(origin, field,
         "= " + format_number(v) + " is out of range: must be in " + std::string(range.text));
}

// A number, a list of numbers or (random) { min, max }.
AtlasAxis read_axis(const toml::table* axes, const char* key, const Range& range, bool random,
                    const std::string& origin) {
  AtlasAxis axis;
  if (!axes) return axis;
  const toml::node* node = axes->get(key);
  if (!node) return axis;
  const std::string field = std::string("axes.") + key;
  if (const auto* list = node->as_array()) {
    if (list->empty()) fail(origin, field, "must list at least one value");
    for (size_t i = 0; i < list->size(); ++i) {
      const std::string item = field + "[" + std::to_string(i) + "]";
      const double v = number_of(*list->get(i), origin, item);
      check(v, range, origin, item);
      axis.values.push_back(v);
    }
    return axis;
  }
  if (const auto* table = node->as_table()) {
    if (!random)
      fail(origin, field,
           "= { min, max } is for sample = \"random\"; a grid takes a number or a list");
    TableReader reader(table, field + ".", origin);
    double lo = NAN, hi = NAN;
    reader.number("min", lo);
    reader.number("max", hi);
    reader.reject_unknown("min, max");
    if (std::isnan(lo) || std::isnan(hi)) fail(origin, field, "needs both min and max");
    check(lo, range, origin, field + ".min");
    check(hi, range, origin, field + ".max");
    if (!(lo <= hi)) fail(origin, field, ".min must be <= .max");
    if (lo < hi && !(lo > 0.0))
      fail(origin, field + ".min",
           "= 0 cannot start a log-uniform range: must be > 0 (or give a list, e.g. [0, 0.5])");
    axis.log_uniform = true;
    axis.min = lo;
    axis.max = hi;
    return axis;
  }
  const double v = number_of(*node, origin, field);
  check(v, range, origin, field);
  axis.values.push_back(v);
  return axis;
}

std::vector<std::string> string_list(const toml::table* atlas, const char* key,
                                     const std::string& origin, const std::string& allowed) {
  std::vector<std::string> out;
  const std::string field = std::string("atlas.") + key;
  const toml::node* node = atlas ? atlas->get(key) : nullptr;
  if (!node) fail(origin, field, "is required: a list of " + allowed);
  const auto* list = node->as_array();
  if (!list) fail(origin, field, "must be a list of " + allowed);
  if (list->empty()) fail(origin, field, "must list at least one of " + allowed);
  for (size_t i = 0; i < list->size(); ++i) {
    const auto* s = list->get(i)->as_string();
    if (!s) fail(origin, field + "[" + std::to_string(i) + "]", "must be a string: " + allowed);
    if (std::find(out.begin(), out.end(), s->get()) != out.end())
      fail(origin, field, "lists '" + s->get() + "' twice");
    out.push_back(s->get());
  }
  return out;
}

}  // namespace

namespace {

// The [atlas] table: sample, bodies, mappings, damping laws, integrator,
// duration, output_dt, converged_tol and, for a random sample, count and
// seed.
void read_atlas_table(AtlasSpec& spec, const toml::table* atlas, const std::string& origin,
                      const std::string& base_dir) {
  TableReader reader(atlas, "atlas.", origin);

  std::string sample = "grid";
  reader.string("sample", sample);
  if (sample != "grid" && sample != "random")
    reader.fail("sample", "= \"" + sample + "\": must be \"grid\" or \"random\"");
  spec.random = sample == "random";

  reader.mark_used("bodies");
  for (const std::string& body :
       string_list(atlas, "bodies", origin,
                   "point_mass, box, tshape, circle, ellipse or scene files (*.toml)")) {
    AtlasBody b;
    if (body.size() > 5 && body.compare(body.size() - 5, 5, ".toml") == 0) {
      const std::filesystem::path path = std::filesystem::path(base_dir) / body;
      b.scene = load_scene(path.string());
      if (!b.scene.obstacles.empty())
        fail(origin, "atlas.bodies",
             "'" + body +
                 "' has static obstacles: the converged solution handles ground "
                 "contact only");
      b.label = std::filesystem::path(body).stem().string();
    } else {
      const std::optional<Shape> shape = parse_shape(body);
      if (!shape)
        fail(origin, "atlas.bodies",
             "'" + body +
                 "' is not a body: point_mass, box, tshape, circle, ellipse or a scene file "
                 "(*.toml)");
      b.scene = default_scene(*shape);
      b.label = body;
    }
    for (const AtlasBody& other : spec.bodies)
      if (other.label == b.label) fail(origin, "atlas.bodies", "names '" + b.label + "' twice");
    spec.bodies.push_back(b);
  }
  reader.mark_used("mappings");
  spec.mappings = string_list(atlas, "mappings", origin, "seed, exact, calibrated, compensated");
  for (const std::string& m : spec.mappings)
    if (std::find(std::begin(kMappings), std::end(kMappings), m) == std::end(kMappings))
      fail(origin, "atlas.mappings",
           "'" + m + "' is not a mapping: seed, exact, calibrated or compensated");
  reader.mark_used("damping");
  if (atlas->get("damping")) {
    for (const std::string& d :
         string_list(atlas, "damping", origin, "kelvin_voigt, compression")) {
      if (const auto law = parse_damping_law(d))
        spec.damping.push_back(*law);
      else
        fail(origin, "atlas.damping",
             "'" + d + "' is not a damping law: kelvin_voigt or compression");
    }
  } else {
    spec.damping.push_back(DampingLaw::KelvinVoigt);
  }
  reader.string("engine", spec.engine);
  std::string integrator(integrator_name(spec.integrator));
  reader.string("integrator", integrator);
  const std::optional<Integrator> parsed = parse_integrator(integrator);
  if (!parsed)
    reader.fail("integrator", "= \"" + integrator +
                                  "\": must be explicit_euler, semi_implicit_euler, "
                                  "implicit_euler or rk4");
  if (*parsed == Integrator::ExplicitEuler)
    reader.fail("integrator",
                "= \"explicit_euler\": MuJoCo has no explicit Euler; use "
                "semi_implicit_euler, implicit_euler or rk4");
  spec.integrator = *parsed;
  reader.number("duration", spec.duration);
  check(spec.duration, kDuration, origin, "atlas.duration");
  reader.number("output_dt", spec.output_dt);
  if (!(spec.output_dt > 0.0 && spec.output_dt <= spec.duration))
    fail(origin, "atlas.output_dt",
         "= " + format_number(spec.output_dt) + " is out of range: must be in (0, duration]");
  reader.number("converged_tol", spec.converged_tol);
  check(spec.converged_tol, kTol, origin, "atlas.converged_tol");
  long long count = -1, seed = 1;
  reader.integer("count", count);
  reader.integer("seed", seed);
  reader.reject_unknown(
      "sample, bodies, mappings, engine, damping, integrator, duration, output_dt, converged_tol, "
      "count, seed");
  if (spec.random) {
    if (count == -1) fail(origin, "atlas.count", "is required for sample = \"random\"");
    if (count < 1 || count > kAtlasMaxPoints)
      fail(origin, "atlas.count",
           "= " + std::to_string(count) + " is out of range: must be in [1, 1e7]");
    if (seed < 0)
      fail(origin, "atlas.seed", "= " + std::to_string(seed) + " is out of range: must be >= 0");
    spec.count = count;
    spec.seed = static_cast<std::uint64_t>(seed);
  } else if (atlas->get("count") || atlas->get("seed")) {
    fail(origin, atlas->get("count") ? "atlas.count" : "atlas.seed",
         "is for sample = \"random\" (a grid takes every value of every list)");
  }
}

// The [axes] table: every axis a number, a list or (random) { min, max }.
void read_atlas_axes(AtlasSpec& spec, const toml::table& root, const std::string& origin) {
  const toml::table* axes = root.get_as<toml::table>("axes");
  if (axes) {
    for (const auto& [key, node] : *axes) {
      static const char* const kAxes[] = {"mass", "k", "zeta", "c", "mu", "mu_roll", "dt"};
      const std::string name(key.str());
      if (std::find(std::begin(kAxes), std::end(kAxes), name) == std::end(kAxes))
        fail(origin, "axes." + name, "is not an axis (mass, k, zeta, c, mu, mu_roll, dt)");
    }
    if (axes->get("zeta") && axes->get("c"))
      fail(origin, "axes.zeta", "and axes.c both given: give one (c = 2·zeta·sqrt(k·m))");
  }
  spec.mass = read_axis(axes, "mass", kMass, spec.random, origin);
  spec.k = read_axis(axes, "k", kK, spec.random, origin);
  spec.by_zeta = !(axes && axes->get("c"));
  spec.damping_value = spec.by_zeta ? read_axis(axes, "zeta", kZeta, spec.random, origin)
                                    : read_axis(axes, "c", kC, spec.random, origin);
  spec.mu = read_axis(axes, "mu", kMu, spec.random, origin);
  spec.mu_roll = read_axis(axes, "mu_roll", kMuRoll, spec.random, origin);
  spec.dt = read_axis(axes, "dt", kDt, spec.random, origin);
  for (double dt : spec.dt.values)
    if (dt > spec.duration) fail(origin, "axes.dt", "= " + format_number(dt) + " exceeds duration");
  if (spec.dt.log_uniform && spec.dt.max > spec.duration)
    fail(origin, "axes.dt.max", "= " + format_number(spec.dt.max) + " exceeds duration");
}

}  // namespace

AtlasSpec parse_atlas_spec(const std::string& text, const std::string& origin,
                           const std::string& base_dir) {
  toml::table root;
  check_toml_shape(text, origin);
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw InputError(origin + ":" + std::to_string(where.line) + ":" +
                     std::to_string(where.column) + ": " + std::string(e.description()));
  }
  AtlasSpec spec;
  spec.origin = origin;
  spec.digest = format_text("%016llx", static_cast<unsigned long long>(fnv1a(text)));
  for (const auto& [key, node] : root) {
    const std::string name(key.str());
    if (name != "atlas" && name != "axes" && name != "initial")
      fail(origin, "[" + name + "]", "is not a table of an atlas spec (atlas, axes, initial)");
    if (!node.is_table()) fail(origin, name, "must be a table ([" + name + "])");
  }
  const toml::table* atlas = root.get_as<toml::table>("atlas");
  if (!atlas) fail(origin, "[atlas]", "is required (sample, bodies, mappings, ...)");
  read_atlas_table(spec, atlas, origin, base_dir);
  read_atlas_axes(spec, root, origin);

  if (const toml::table* initial = root.get_as<toml::table>("initial")) {
    TableReader in(initial, "initial.", origin);
    State state;
    bool given[6] = {};
    const char* keys[] = {"x", "y", "theta", "vx", "vy", "omega"};
    double values[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 6; ++i) {
      given[i] = initial->get(keys[i]) != nullptr;
      in.number(keys[i], values[i]);
      if (given[i] && !(std::isfinite(values[i]) && std::abs(values[i]) <= 1e6))
        in.fail(keys[i], "= " + format_number(values[i]) +
                             " is out of range: must be finite, |value| <= 1e6");
    }
    in.reject_unknown("x, y, theta, vx, vy, omega");
    for (AtlasBody& b : spec.bodies) {
      const bool turns = shape_features(b.scene.shape).turns;
      Vec3& q = b.scene.initial.q;
      Vec3& v = b.scene.initial.v;
      if (given[0]) q.x() = values[0];
      if (given[1]) q.y() = values[1];
      if (given[2] && turns) q.z() = values[2];
      if (given[3]) v.x() = values[3];
      if (given[4]) v.y() = values[4];
      if (given[5] && turns) v.z() = values[5];
    }
  }
  if (atlas_point_count(spec) > kAtlasMaxPoints)
    fail(origin, "[axes]",
         "describe " + std::to_string(atlas_point_count(spec)) +
             " points: at most 1e7 (split the spec)");
  return spec;
}

AtlasSpec load_atlas_spec(const std::string& path) {
  const std::string text = read_input_file(path, "the atlas spec");
  const std::filesystem::path p(path);
  return parse_atlas_spec(text, path, p.has_parent_path() ? p.parent_path().string() : ".");
}

long long atlas_point_count(const AtlasSpec& spec) {
  long long n = static_cast<long long>(spec.bodies.size()) *
                static_cast<long long>(spec.mappings.size()) *
                static_cast<long long>(spec.damping.size());
  if (spec.random) return n * spec.count;
  for (const AtlasAxis* a :
       {&spec.mass, &spec.k, &spec.damping_value, &spec.mu, &spec.mu_roll, &spec.dt}) {
    const long long len = a->values.empty() ? 1 : static_cast<long long>(a->values.size());
    if (n > kAtlasMaxPoints) return n;  // no overflow: already too many
    n *= len;
  }
  return n;
}

}  // namespace contact2d
