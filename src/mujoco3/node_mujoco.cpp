#include "mujoco3/node_mujoco.hpp"

#include <unistd.h>
#include <filesystem>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/input_error.hpp"
#include "io/child_process.hpp"
#include "io/json.hpp"
#include "io/json_reader.hpp"

#ifndef CONTACT2D_MUJOCO3_DIR
#error "CONTACT2D_MUJOCO3_DIR: the folder of driver.mjs (CMakeLists.txt sets it)"
#endif

namespace contact2d::mujoco3 {
namespace {

// The oldest Node that runs the package (its WebAssembly features).
constexpr int kOldestNode = 18;

std::string fix_command() {
  return "run scripts/setup, or: npm ci --prefix " + package_directory();
}

bool is_file(const std::string& path) { return ::access(path.c_str(), R_OK) == 0; }

// `node` in PATH ("" when none).
std::string find_node() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    std::string candidate = (dir.empty() ? "." : dir) + "/node";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string text_of(const json::Value* v) { return v ? v->text : std::string(); }

std::string numbers(const std::vector<double>& values) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i ? "," : "") + json::number(values[i]);
  return out + "]";
}

std::vector<double> numbers_of(const json::Value* v) {
  std::vector<double> out;
  if (v == nullptr) return out;
  for (const json::Value& item : v->items) out.push_back(item.number);
  return out;
}

}  // namespace

std::string package_directory() {
  const char* dir = std::getenv("CONTACT2D_MUJOCO3_DIR");
  return dir && *dir ? dir : CONTACT2D_MUJOCO3_DIR;
}

std::string missing() {
  const std::string dir = package_directory();
  if (find_node().empty())
    return "mujoco3: Node.js (the command node) is not installed: run scripts/setup, or: apt-get "
           "install nodejs npm";
  if (!is_file(dir + "/driver.mjs"))
    return "mujoco3: " + dir +
           "/driver.mjs is missing (set CONTACT2D_MUJOCO3_DIR to the folder "
           "that holds it, src/mujoco3 of the source tree)";
  const std::string package = dir + "/node_modules/@mujoco/mujoco/package.json";
  if (!is_file(package))
    return "mujoco3: the package @mujoco/mujoco is not installed in " + dir +
           "/node_modules: " + fix_command();
  std::string version;
  try {
    version = text_of(json::parse(read_text(package), package).get("version"));
  } catch (const std::exception& e) {
    return "mujoco3: " + std::string(e.what()) + ": " + fix_command();
  }
  if (version != kVersion)
    return "mujoco3: " + dir + "/node_modules has @mujoco/mujoco " + version +
           ", contact2d is pinned to " + std::string(kVersion) + ": " + fix_command();
  return {};
}

struct Node::Answer {
  json::Value value;
  const json::Value* get(const std::string& key) const { return value.get(key); }
};

std::shared_ptr<Node> Node::of_this_thread() {
  thread_local std::shared_ptr<Node> node;
  if (!node || node->failed_) node.reset(new Node());
  return node;
}

Node::Node() {
  const std::string why = missing();
  if (!why.empty()) throw InputError(why);
  try {
    process_ = std::make_unique<ChildProcess>(std::vector<std::string>{find_node(), "driver.mjs"},
                                              package_directory());
  } catch (const ChildProcessError& e) {
    throw InputError("mujoco3: " + std::string(e.what()) + ": " + fix_command());
  }
  const Answer hello = request(R"({"op":"hello"})");
  const std::string version = text_of(hello.get("version"));
  if (version != kVersion)
    throw InputError("mujoco3: Node loaded MuJoCo " + version + ", contact2d is pinned to " +
                     std::string(kVersion) + ": " + fix_command());
  const int node_major =
      static_cast<int>(std::strtol(text_of(hello.get("node")).c_str(), nullptr, 10));
  if (node_major < kOldestNode)
    throw InputError("mujoco3: Node " + text_of(hello.get("node")) + " is older than " +
                     std::to_string(kOldestNode) +
                     ", which @mujoco/mujoco needs: " + fix_command());
}

Node::~Node() = default;

int Node::pid() const { return static_cast<int>(process_->pid()); }

Node::Answer Node::request(const std::string& line, const std::string& origin, bool verbatim) {
  Answer a;
  std::string text;
  try {
    process_->write(line + "\n");
    text = process_->read_line();
    a.value = json::parse(text, "the MuJoCo 3 process's answer");
  } catch (const std::exception& e) {
    failed_ = true;
    throw EngineError("mujoco3: the Node process running MuJoCo " + std::string(kVersion) +
                      " failed: " + e.what() + " (" + fix_command() + ")");
  }
  if (const json::Value* said = a.get("messages"))
    for (const json::Value& m : said->items) messages_.push_back(m.text);
  if (text_of(a.get("ok")) != "true") {
    const std::string error = text_of(a.get("error"));
    if (verbatim && error.rfind("diverged: ", 0) == 0) throw EngineError(error.substr(10));
    if (verbatim) throw InputError(error);
    if (!origin.empty())
      throw InputError(origin + ": MuJoCo " + std::string(kVersion) +
                       " cannot load the model: " + error);
    // The driver could not import the package: it says so, then exits.
    failed_ = true;
    throw EngineError("mujoco3: " + error + " (" + fix_command() + ")");
  }
  return a;
}

LoadedModel Node::load(const std::string& xml, const std::string& origin) {
  const Answer a = request(R"({"op":"load","xml":)" + json::string(xml) + "}", origin);
  LoadedModel m;
  m.id = static_cast<int>(a.get("id")->number);
  m.nq = static_cast<int>(a.get("nq")->number);
  m.nv = static_cast<int>(a.get("nv")->number);
  m.nbody = static_cast<int>(a.get("nbody")->number);
  m.timestep = a.get("timestep")->number;
  m.body_pos = numbers_of(a.get("body_pos"));
  m.body_invweight0 = numbers_of(a.get("body_invweight0"));
  return m;
}

void Node::free(int id) { request(R"({"op":"free","id":)" + std::to_string(id) + "}"); }

void Node::reset(int id, const std::vector<double>& qpos, const std::vector<double>& qvel) {
  request(R"({"op":"reset","id":)" + std::to_string(id) + R"(,"qpos":)" + numbers(qpos) +
          R"(,"qvel":)" + numbers(qvel) + "}");
}

void Node::applied(int id, int body, const std::array<double, 6>& xfrc) {
  request(R"({"op":"applied","id":)" + std::to_string(id) + R"(,"body":)" + std::to_string(body) +
          R"(,"xfrc":)" + numbers({xfrc.begin(), xfrc.end()}) + "}");
}

int Node::step(int id, int n, std::vector<double>& out, bool& bad) {
  const Answer a =
      request(R"({"op":"step","id":)" + std::to_string(id) + R"(,"n":)" + std::to_string(n) + "}");
  const auto bytes = static_cast<size_t>(a.get("bytes")->number);
  bad = text_of(a.get("bad")) == "true";
  out.resize(bytes / sizeof(double));
  try {
    process_->read_bytes(out.data(), bytes);
  } catch (const std::exception& e) {
    failed_ = true;
    throw EngineError("mujoco3: the Node process running MuJoCo " + std::string(kVersion) +
                      " failed: " + e.what() + " (" + fix_command() + ")");
  }
  return static_cast<int>(a.get("steps")->number);
}

void Node::rewind(int id, int n) {
  request(R"({"op":"rewind","id":)" + std::to_string(id) + R"(,"n":)" + std::to_string(n) + "}");
}

namespace {

// One contact of the driver's "state" answer (mujoco/model_state.hpp).
mujoco::StateContact contact_of(const json::Value& c) {
  auto number_of = [](const json::Value* v) { return v ? v->number : 0.0; };
  mujoco::StateContact out;
  out.geom1 = static_cast<int>(number_of(c.get("geom1")));
  out.geom2 = static_cast<int>(number_of(c.get("geom2")));
  out.body1 = static_cast<int>(number_of(c.get("body1")));
  out.body2 = static_cast<int>(number_of(c.get("body2")));
  out.explicit_pair = text_of(c.get("explicit_pair")) == "true";
  out.dist = number_of(c.get("dist"));
  auto fill = [&](const char* key, auto& array) {
    const std::vector<double> v = numbers_of(c.get(key));
    for (size_t i = 0; i < array.size() && i < v.size(); ++i) array[i] = v[i];
  };
  fill("pos", out.pos);
  fill("normal", out.normal);
  fill("friction", out.friction);
  fill("solref", out.solref);
  fill("solimp", out.solimp);
  out.condim = static_cast<int>(number_of(c.get("condim")));
  out.margin = number_of(c.get("margin"));
  out.gap = number_of(c.get("gap"));
  out.A = number_of(c.get("A"));
  out.A_t = number_of(c.get("A_t"));
  out.force = number_of(c.get("force"));
  out.rows = static_cast<int>(number_of(c.get("rows")));
  out.quadratic = static_cast<int>(number_of(c.get("quadratic")));
  // The normal row and M⁻¹ times it arrive sparse: non-zero columns and values.
  auto sparse = [&](const char* index_key, const char* value_key) {
    mujoco::SparseRow row;
    const std::vector<double> index = numbers_of(c.get(index_key));
    row.value = numbers_of(c.get(value_key));
    for (const double i : index) row.index.push_back(static_cast<int>(i));
    return row;
  };
  out.jacobian = sparse("jacobian_index", "jacobian_value");
  out.solved = sparse("solved_index", "solved_value");
  if (const json::Value* tangents = c.get("tangents")) {
    for (size_t k = 0; k < 2 && k < tangents->items.size(); ++k) {
      const json::Value& t = tangents->items[k];
      auto read_row = [&](const char* key) {
        mujoco::SparseRow row;
        if (const json::Value* r = t.get(key)) {
          for (const double i : numbers_of(r->get("index")))
            row.index.push_back(static_cast<int>(i));
          row.value = numbers_of(r->get("value"));
        }
        return row;
      };
      out.tangent[k] = read_row("row");
      out.tangent_solved[k] = read_row("solved");
    }
  }
  return out;
}

// Every index the contact math reads is in range and every sparse row is
// ascending columns of the model: the driver is this program's own, but a
// model is anybody's.
bool fits_together(const mujoco::ModelState& s) {
  const size_t nbody = s.body_names.size(), ngeom = s.geom_names.size();
  const auto nv = static_cast<size_t>(s.nv);
  bool sound = s.body_weld.size() == nbody && s.body_mass.size() == nbody &&
               s.body_inertia.size() == 3 * nbody && s.body_invweight0.size() == 2 * nbody &&
               s.geom_body.size() == ngeom && s.body_parent.size() == nbody &&
               s.body_joints.size() == nbody && s.geom_mu.size() == ngeom &&
               s.geom_condim.size() == ngeom && s.geom_collides.size() == ngeom &&
               s.bias.size() == nv && s.qvel.size() == nv && s.qacc.size() == nv;
  for (const int b : s.geom_body) sound = sound && b >= 0 && static_cast<size_t>(b) < nbody;
  auto in = [](int i, size_t n) { return i >= 0 && static_cast<size_t>(i) < n; };
  for (const mujoco::StateContact& c : s.contacts) {
    sound = sound && in(c.geom1, ngeom) && in(c.geom2, ngeom) && in(c.body1, nbody) &&
            in(c.body2, nbody);
    for (const mujoco::SparseRow* row : {&c.jacobian, &c.solved, &c.tangent[0], &c.tangent[1],
                                         &c.tangent_solved[0], &c.tangent_solved[1]}) {
      sound = sound && row->index.size() == row->value.size();
      for (size_t i = 0; i < row->index.size(); ++i)
        sound = sound && in(row->index[i], nv) && (i == 0 || row->index[i] > row->index[i - 1]);
    }
  }
  return sound;
}

}  // namespace

mujoco::ModelState Node::state(const mujoco::StateRequest& r) {
  const std::string path = std::filesystem::absolute(r.path).string();
  const Answer a = request(R"({"op":"state","path":)" + json::string(path) + R"(,"key":)" +
                               json::string(r.key) + R"(,"settle":)" + json::number(r.settle) +
                               R"(,"option":)" + json::string(r.option) + "}",
                           {}, true);
  mujoco::ModelState s;
  auto texts = [](const json::Value* v) {
    std::vector<std::string> out;
    if (v)
      for (const json::Value& item : v->items) out.push_back(item.text);
    return out;
  };
  auto ints = [](const json::Value* v) {
    std::vector<int> out;
    for (double x : numbers_of(v)) out.push_back(static_cast<int>(x));
    return out;
  };
  auto number = [](const json::Value* v) { return v ? v->number : 0.0; };
  s.version = text_of(a.get("version"));
  s.load_warning = text_of(a.get("load_warning"));
  s.messages = texts(a.get("step_warnings"));
  s.timestep = number(a.get("timestep"));
  s.integrator = text_of(a.get("integrator"));
  s.elliptic = text_of(a.get("elliptic")) == "true";
  s.impratio = number(a.get("impratio"));
  const std::vector<double> g = numbers_of(a.get("gravity"));
  for (size_t i = 0; i < 3 && i < g.size(); ++i) s.gravity[i] = g[i];
  s.refsafe = text_of(a.get("refsafe")) == "true";
  s.disabled = text_of(a.get("disabled"));
  s.body_names = texts(a.get("body_names"));
  s.geom_names = texts(a.get("geom_names"));
  s.body_weld = ints(a.get("body_weld"));
  s.body_mass = numbers_of(a.get("body_mass"));
  s.body_inertia = numbers_of(a.get("body_inertia"));
  s.body_invweight0 = numbers_of(a.get("body_invweight0"));
  s.geom_body = ints(a.get("geom_body"));
  s.body_parent = ints(a.get("body_parent"));
  s.body_joints = texts(a.get("body_joints"));
  s.geom_mu = numbers_of(a.get("geom_mu"));
  s.geom_condim = ints(a.get("geom_condim"));
  if (const json::Value* list = a.get("geom_collides"))
    for (const json::Value& v : list->items) s.geom_collides.push_back(v.text == "true");
  s.nv = static_cast<int>(number(a.get("nv")));
  s.settled = number(a.get("settled"));
  s.speed = number(a.get("speed"));
  s.accel = number(a.get("accel"));
  s.bias = numbers_of(a.get("bias"));
  s.qvel = numbers_of(a.get("qvel"));
  s.qacc = numbers_of(a.get("qacc"));
  if (const json::Value* list = a.get("contacts"))
    for (const json::Value& c : list->items) s.contacts.push_back(contact_of(c));
  if (!fits_together(s)) {
    failed_ = true;
    throw EngineError("mujoco3: the Node process running MuJoCo " + std::string(kVersion) +
                      " answered a state whose arrays do not fit together (" + fix_command() + ")");
  }
  return s;
}

mujoco::ModelState read_model_state(const mujoco::StateRequest& request) {
  mujoco::check_state_request(request);
  return Node::of_this_thread()->state(request);
}

std::vector<std::string> Node::counters(int id) {
  const Answer a = request(R"({"op":"counters","id":)" + std::to_string(id) + "}");
  std::vector<std::string> out;
  for (const json::Value& w : a.get("warnings")->items) out.push_back(w.text);
  return out;
}

std::vector<std::string> Node::take_messages() {
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

}  // namespace contact2d::mujoco3
