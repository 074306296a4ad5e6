#include "io/scene_file.hpp"

#include "core/format.hpp"
#include "io/read_file.hpp"
#include "io/toml_table.hpp"

#include <toml++/toml.h>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace contact2d {
namespace {

std::string format_value(double v) { return format_number("%g", v); }

const toml::table* subtable(const toml::table& root, const char* name, const std::string& origin) {
  const toml::node* node = root.get(name);
  if (!node) return nullptr;
  if (!node->is_table()) throw InputError(origin + ": [" + name + "] must be a table");
  return node->as_table();
}

}  // namespace

void read_body(const toml::table* table, Scene& scene, const std::string& origin) {
  TableReader body(table, "body.", origin);
  switch (scene.shape) {
    case Shape::PointMass:
      body.number("mass", scene.mass);
      body.number("half_height", scene.half_height);
      body.reject_unknown("mass, half_height");
      return;
    case Shape::Box:
      body.number("mass", scene.mass);
      body.number("width", scene.width);
      body.number("height", scene.height);
      body.reject_unknown("mass, width, height");
      return;
    case Shape::Circle:
      body.number("mass", scene.mass);
      body.number("radius", scene.radius);
      body.reject_unknown("mass, radius");
      return;
    case Shape::Ellipse:
      body.number("mass", scene.mass);
      body.number("a", scene.a);
      body.number("b", scene.b);
      body.number("inertia", scene.inertia);
      body.reject_unknown("mass, a, b, inertia");
      return;
    case Shape::TShape: break;
  }
  const toml::array* parts = body.array("parts");
  body.reject_unknown("parts (a tshape's mass comes from its parts)");
  if (!parts) return;  // the default T
  scene.parts.clear();
  for (size_t i = 0; i < parts->size(); ++i) {
    const std::string prefix = "body.parts[" + std::to_string(i) + "].";
    const toml::table* part_table = (*parts)[i].as_table();
    if (!part_table)
      throw InputError(origin + ": " + prefix.substr(0, prefix.size() - 1) +
                       " must be a table { width, height, x, y, mass }");
    TableReader part(part_table, prefix, origin);
    BoxPart p{0.0, 0.0, 0.0, 0.0, 0.0};
    part.number("width", p.width);
    part.number("height", p.height);
    part.number("x", p.x);
    part.number("y", p.y);
    part.number("mass", p.mass);
    part.reject_unknown("width, height, x, y, mass");
    if (!part_table->contains("width") || !part_table->contains("height") ||
        !part_table->contains("mass")) {
      throw InputError(origin + ": " + prefix +
                       "width, height and mass are required in every part");
    }
    scene.parts.push_back(p);
  }
}

namespace {

void read_contact(const toml::table* table, Scene& scene, const std::string& origin) {
  TableReader contact(table, "contact.", origin);
  ContactParams& p = scene.contact;
  contact.number("k", p.k);
  contact.number("c", p.c);
  contact.number("mu", p.mu);
  contact.number("alpha", p.alpha);
  contact.number("mu_roll", p.mu_roll);
  contact.number("mu_torsion", p.mu_torsion);
  std::string damping(damping_law_name(p.damping));
  contact.string("damping", damping);
  std::string friction(friction_law_name(p.friction));
  contact.string("friction_law", friction);
  contact.number("cone_ratio", p.cone_ratio);
  contact.reject_unknown("k, c, mu, alpha, mu_roll, mu_torsion, damping, friction_law, cone_ratio");
  if (const auto law = parse_damping_law(damping)) {
    p.damping = *law;
  } else {
    contact.fail("damping", "= \"" + damping +
                                "\" is not a damping law: use \"compression\" or \"kelvin_voigt\"");
  }
  if (const auto law = parse_friction_law(friction)) {
    p.friction = *law;
  } else {
    contact.fail("friction_law", "= \"" + friction +
                                     "\" is not a friction law: use \"tanh\", \"viscous_cone\" "
                                     "or \"soft_cone\"");
  }
}

void read_initial(const toml::table* table, Scene& scene, const std::string& origin) {
  TableReader initial(table, "initial.", origin);
  initial.number("x", scene.initial.q.x());
  initial.number("y", scene.initial.q.y());
  initial.number("theta", scene.initial.q.z());
  initial.number("vx", scene.initial.v.x());
  initial.number("vy", scene.initial.v.y());
  initial.number("omega", scene.initial.v.z());
  initial.reject_unknown("x, y, theta, vx, vy, omega");
}

void read_sim(const toml::table* table, Scene& scene, const std::string& origin) {
  TableReader sim(table, "sim.", origin);
  sim.number("dt", scene.sim.dt);
  sim.number("duration", scene.sim.duration);
  sim.number("output_dt", scene.sim.output_dt);
  sim.number("gravity", scene.sim.gravity);
  std::string integrator(integrator_name(scene.sim.integrator));
  sim.string("integrator", integrator);
  sim.reject_unknown("dt, duration, output_dt, integrator, gravity");
  const auto parsed = parse_integrator(integrator);
  if (!parsed) {
    sim.fail("integrator", "= \"" + integrator +
                               "\" is not an integrator: use explicit_euler, semi_implicit_euler, "
                               "implicit_euler or rk4");
  }
  scene.sim.integrator = *parsed;
}

// An obstacle's own contact keys (k, c, mu, alpha, mu_roll, mu_torsion,
// damping); a key left out follows the scene's [contact].
void read_obstacle_contact(TableReader& reader, const toml::table& table, ContactOverride& out) {
  auto optional = [&](const char* key, std::optional<double>& value) {
    if (!table.contains(key)) {
      reader.mark_used(key);
      return;
    }
    double v = 0.0;
    reader.number(key, v);
    value = v;
  };
  optional("k", out.k);
  optional("c", out.c);
  optional("mu", out.mu);
  optional("alpha", out.alpha);
  optional("mu_roll", out.mu_roll);
  optional("mu_torsion", out.mu_torsion);
  if (table.contains("damping")) {
    std::string damping;
    reader.string("damping", damping);
    if (const auto law = parse_damping_law(damping)) {
      out.damping = law;
    } else {
      reader.fail(
          "damping",
          "= \"" + damping + "\" is not a damping law: use \"compression\" or \"kelvin_voigt\"");
    }
  } else {
    reader.mark_used("damping");
  }
}

constexpr const char* kObstacleContactKeys = "k, c, mu, alpha, mu_roll, mu_torsion, damping";

// [[obstacle]]: an array of tables, each a box { x, y, width, height } (centre
// and size) or a segment { x1, y1, x2, y2, radius } chosen by `type`.
void read_obstacles(const toml::table& root, Scene& scene, const std::string& origin) {
  const toml::node* node = root.get("obstacle");
  if (!node) return;
  const toml::array* list = node->as_array();
  if (!list) throw InputError(origin + ": obstacle must be an array of tables ([[obstacle]])");
  scene.obstacles.clear();
  for (size_t i = 0; i < list->size(); ++i) {
    const std::string name = "obstacle[" + std::to_string(i) + "]";
    const toml::table* table = (*list)[i].as_table();
    if (!table)
      throw InputError(origin + ": " + name +
                       " must be a table ([[obstacle]] with type = \"box\" or \"segment\")");
    TableReader reader(table, name + ".", origin);
    std::string type;
    reader.string("type", type);
    auto require_keys = [&](std::initializer_list<const char*> keys) {
      for (const char* key : keys) {
        if (!table->contains(key))
          reader.fail(key, "is required for an obstacle of type \"" + type + "\"");
      }
    };
    if (type == "box") {
      double x = 0.0, y = 0.0, width = 0.0, height = 0.0;
      reader.number("x", x);
      reader.number("y", y);
      reader.number("width", width);
      reader.number("height", height);
      ContactOverride contact;
      read_obstacle_contact(reader, *table, contact);
      reader.reject_unknown(std::string("type, x, y, width, height, ") + kObstacleContactKeys);
      require_keys({"x", "y", "width", "height"});
      // validate() sees the corners; check the keys as written, so that an
      // infinite width is reported as the width and not as a centre of NaN.
      auto check = [&](const char* key, double value, bool ok, const char* range) {
        if (!ok) {
          throw InputError(origin + ": " + name + "." + key + " = " + format_value(value) +
                           " is out of range: " + range);
        }
      };
      check("x", x, std::isfinite(x) && std::abs(x) <= 1e6, "must be finite, |x| <= 1e6 m");
      check("y", y, std::isfinite(y) && std::abs(y) <= 1e6, "must be finite, |y| <= 1e6 m");
      check("width", width, width > 0.0 && width <= 1e6, "must be in (0, 1e6] m");
      check("height", height, height > 0.0 && height <= 1e6, "must be in (0, 1e6] m");
      scene.obstacles.push_back(make_box_obstacle(x, y, width, height));
      scene.obstacles.back().contact = contact;
    } else if (type == "segment") {
      Vec2 a = Vec2::Zero(), b = Vec2::Zero();
      double radius = 0.0;
      reader.number("x1", a.x());
      reader.number("y1", a.y());
      reader.number("x2", b.x());
      reader.number("y2", b.y());
      reader.number("radius", radius);
      ContactOverride contact;
      read_obstacle_contact(reader, *table, contact);
      reader.reject_unknown(std::string("type, x1, y1, x2, y2, radius, ") + kObstacleContactKeys);
      require_keys({"x1", "y1", "x2", "y2"});
      scene.obstacles.push_back(make_segment_obstacle(a, b, radius));
      scene.obstacles.back().contact = contact;
    } else if (!table->contains("type")) {
      reader.fail(
          "type",
          "is required: \"box\" (x, y, width, height) or \"segment\" (x1, y1, x2, y2, radius)");
    } else {
      reader.fail("type", "= \"" + type + "\" is not an obstacle type: use \"box\" or \"segment\"");
    }
  }
}

// "--set contact.k=-5" or "--dt 0": the command-line text of an override.
std::string option_text(const Override& o) {
  if (o.option.empty()) return "--set " + o.key + "=" + o.value;
  // --integrator's value is passed as a TOML string: shown as typed.
  const bool quoted = o.value.size() >= 2 && o.value.front() == '"' && o.value.back() == '"';
  return o.option + " " + (quoted ? o.value.substr(1, o.value.size() - 2) : o.value);
}

// Inserts "a.b=value" into the document, creating tables as needed. A
// part of the key that the document holds as a value, not a table, is the
// document's fault (`origin`'s: "sim = 5"), named so.
void apply_override(toml::table& root, const Override& o, const std::string& origin) {
  toml::table* table = &root;
  std::string_view path = o.key;
  size_t dot;
  while ((dot = path.find('.')) != std::string_view::npos) {
    std::string part(path.substr(0, dot));
    // "obstacle[1]": the second [[obstacle]] table, as messages name it.
    if (const size_t open = part.find('['); open != std::string::npos && part.back() == ']') {
      const std::string name = part.substr(0, open),
                        digits = part.substr(open + 1, part.size() - open - 2);
      toml::array* list = table->get(name) ? table->get(name)->as_array() : nullptr;
      const bool number = !digits.empty() && digits.size() < 7 &&
                          digits.find_first_not_of("0123456789") == std::string::npos;
      const size_t index = number ? std::stoul(digits) : 0;
      if (list == nullptr || !number || index >= list->size() || !(*list)[index].is_table())
        throw InputError(option_text(o) + ": " + origin + " has no " + part + " (" +
                         (list == nullptr ? "no [[" + name + "]] table"
                                          : std::to_string(list->size()) + " [[" + name +
                                                "]] tables, numbered from 0") +
                         ")");
      table = (*list)[index].as_table();
      path.remove_prefix(dot + 1);
      continue;
    }
    toml::node* node = table->get(part);
    if (!node) {
      table->insert(part, toml::table{});
      node = table->get(part);
    }
    if (node->is_array()) {
      // "obstacle.0.k" means obstacle[0].k; "obstacle.k" names none of them.
      const std::string rest(path.substr(dot + 1));
      const size_t digits = rest.find_first_not_of("0123456789");
      const std::string example =
          digits > 0 && digits != std::string::npos && rest[digits] == '.'
              ? part + "[" + rest.substr(0, digits) + "]" + rest.substr(digits)
              : part + "[0]." + rest;
      throw InputError(option_text(o) + ": '" + part + "' is a list of tables: name one, as " +
                       example);
    }
    if (!node->is_table())
      throw InputError(origin + ": '" + part + "' is a value, not a table, so " + option_text(o) +
                       " cannot set " + o.key + " (write [" + part + "] as a table)");
    table = node->as_table();
    path.remove_prefix(dot + 1);
  }
  const std::string leaf(path);
  // Read the value as TOML; a bare word that is not TOML is a string.
  toml::table value_doc;
  check_toml_shape("v = " + o.value, option_text(o));
  try {
    value_doc = toml::parse("v = " + o.value);
  } catch (const toml::parse_error&) {
    value_doc = toml::table{{"v", o.value}};
  }
  table->insert_or_assign(leaf, *value_doc.get("v"));
}

}  // namespace

Override parse_override(const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == assignment.size()) {
    throw InputError("--set " + assignment + ": expected key=value, e.g. contact.k=1e6");
  }
  return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

namespace {

Scene read_scene(const std::string& toml_text, const std::string& origin,
                 const std::vector<Override>& overrides);

}  // namespace

Scene parse_scene(const std::string& toml_text, const std::string& origin,
                  const std::vector<Override>& overrides) {
  try {
    return read_scene(toml_text, origin, overrides);
  } catch (const InputError& e) {
    // An error about a key an override set names the option, not the file:
    // "origin: contact.k = -5 ..." becomes "--set contact.k=-5: contact.k = -5 ...".
    const std::string message = e.what();
    const std::string prefix = origin + ": ";
    if (message.rfind(prefix, 0) != 0) throw;
    const std::string rest = message.substr(prefix.size());
    // "unknown key 'nosuch'" for --set nosuch.key=1: the override made the
    // table it names.
    std::string unknown;
    if (const size_t at = rest.find("unknown key '"); at != std::string::npos) {
      const size_t begin = at + std::string("unknown key '").size();
      unknown = rest.substr(begin, rest.find('\'', begin) - begin);
    }
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o) {
      const bool about_key = rest.rfind(o->key + " ", 0) == 0 ||
                             rest.find("'" + o->key + "'") != std::string::npos ||
                             (!unknown.empty() && o->key.rfind(unknown + ".", 0) == 0);
      if (about_key) throw InputError(option_text(*o) + ": " + rest);
    }
    throw;
  }
}

namespace {

Scene read_scene(const std::string& toml_text, const std::string& origin,
                 const std::vector<Override>& overrides) {
  toml::table root = parse_toml(toml_text, origin);
  for (const Override& o : overrides) apply_override(root, o, origin);

  TableReader top(&root, "", origin);
  std::string shape_text;
  top.string("scene", shape_text);
  if (!root.contains("scene")) {
    throw InputError(origin +
                     ": missing key 'scene' (one of point_mass, box, tshape, circle, ellipse)");
  }
  const auto shape = parse_shape(shape_text);
  if (!shape) {
    top.fail("scene", "= \"" + shape_text +
                          "\" is not a scene: use point_mass, box, tshape, circle or ellipse");
  }
  Scene scene = default_scene(*shape);
  read_body(subtable(root, "body", origin), scene, origin);
  read_contact(subtable(root, "contact", origin), scene, origin);
  read_initial(subtable(root, "initial", origin), scene, origin);
  read_sim(subtable(root, "sim", origin), scene, origin);
  read_obstacles(root, scene, origin);
  // [game] belongs to `contact2d play`, which reads and checks it; a scene
  // that has one still simulates (the rules do not change the physics).
  if (root.contains("game")) subtable(root, "game", origin);
  // Tables were read by the helpers above; mark them used.
  for (const char* name : {"body", "contact", "initial", "sim", "obstacle", "game"})
    top.mark_used(name);
  top.reject_unknown("scene, [body], [contact], [initial], [sim], [[obstacle]], [game]");

  if (const auto error = validate(scene)) {
    throw InputError(origin + ": " + error->key + " = " + format_value(error->value) +
                     " is out of range: " + error->range);
  }
  return scene;
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<Override>& overrides) {
  // A MuJoCo model given where a scene belongs: say what it is, not that
  // the TOML is malformed. XML starts with '<' (after blanks); TOML cannot.
  const std::string content = read_input_file(path, "scene file");
  const size_t first = content.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  if (first != std::string::npos && content[first] == '<') {
    throw InputError(path +
                     ": this is an MJCF (XML) file: contact2d reads scenes (TOML, docs/scenes.md); "
                     "for your own MuJoCo model use `contact2d solref --model " +
                     path + " --body NAME`");
  }
  return parse_scene(content, path, overrides);
}

}  // namespace contact2d
