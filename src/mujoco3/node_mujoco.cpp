#include "mujoco3/node_mujoco.hpp"

#include <sys/stat.h>
#include <unistd.h>
#include <filesystem>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <future>
#include <limits>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/cancel.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/child_process.hpp"
#include "io/json.hpp"
#include "io/json_reader.hpp"
#include "io/read_file.hpp"
#include "mujoco/state_arrays.hpp"

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

// `node` in PATH as an absolute path ("" when none): a relative PATH entry
// is this program's working folder's, and Node runs in package_directory().
std::string find_node() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    std::string candidate = (dir.empty() ? "." : dir) + "/node";
    struct stat info {};
    if (::access(candidate.c_str(), X_OK) == 0 && ::stat(candidate.c_str(), &info) == 0 &&
        S_ISREG(info.st_mode)) {
      std::error_code error;
      const std::filesystem::path absolute = std::filesystem::absolute(candidate, error);
      return error ? candidate : absolute.lexically_normal().string();
    }
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

// An answer that lacks a key or has one of the wrong kind: the Node side
// broke the protocol (Node::checked makes it an EngineError).
struct BadAnswer : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* kind_name(json::Value::Kind kind) {
  switch (kind) {
    case json::Value::Kind::Null: return "null";
    case json::Value::Kind::Bool: return "a boolean";
    case json::Value::Kind::Number: return "a number";
    case json::Value::Kind::String: return "a string";
    case json::Value::Kind::Array: return "an array";
    case json::Value::Kind::Object: return "an object";
  }
  return "?";
}

// The member `key` of `v`, of that kind; never a default.
const json::Value& need(const json::Value& v, const std::string& key, json::Value::Kind kind) {
  const json::Value* found = v.get(key);
  if (found == nullptr) throw BadAnswer("no \"" + key + "\"");
  if (found->kind != kind)
    throw BadAnswer("\"" + key + "\" is " + kind_name(found->kind) + ", not " + kind_name(kind));
  return *found;
}

double need_number(const json::Value& v, const std::string& key) {
  return need(v, key, json::Value::Kind::Number).number;
}

// A whole number within [low, high] (|high| at most 2^53, exact as a double).
long long need_integer(const json::Value& v, const std::string& key, long long low = 0,
                       long long high = std::numeric_limits<int>::max()) {
  const double x = need_number(v, key);
  if (!(x >= static_cast<double>(low) && x <= static_cast<double>(high)) || x != std::floor(x))
    throw BadAnswer("\"" + key + "\" is " + json::number(x) + ", not a whole number in [" +
                    std::to_string(low) + ", " + std::to_string(high) + "]");
  return static_cast<long long>(x);
}

bool need_flag(const json::Value& v, const std::string& key) {
  return need(v, key, json::Value::Kind::Bool).text == "true";
}

std::string need_text(const json::Value& v, const std::string& key) {
  return need(v, key, json::Value::Kind::String).text;
}

// An array of numbers (`size` of them unless it is npos).
std::vector<double> need_numbers(const json::Value& v, const std::string& key,
                                 size_t size = std::string::npos) {
  const json::Value& list = need(v, key, json::Value::Kind::Array);
  if (size != std::string::npos && list.items.size() != size)
    throw BadAnswer("\"" + key + "\" has " + std::to_string(list.items.size()) + " numbers, not " +
                    std::to_string(size));
  std::vector<double> out;
  out.reserve(list.items.size());
  for (const json::Value& item : list.items) {
    if (item.kind != json::Value::Kind::Number)
      throw BadAnswer("\"" + key + "\" holds " + kind_name(item.kind) + ", not a number");
    out.push_back(item.number);
  }
  return out;
}

std::vector<int> need_integers(const json::Value& v, const std::string& key) {
  std::vector<int> out;
  for (const double x : need_numbers(v, key)) {
    if (!(std::abs(x) <= std::numeric_limits<int>::max()) || x != std::floor(x))
      throw BadAnswer("\"" + key + "\" holds " + json::number(x) + ", not a whole number");
    out.push_back(static_cast<int>(x));
  }
  return out;
}

std::vector<std::string> need_texts(const json::Value& v, const std::string& key) {
  std::vector<std::string> out;
  for (const json::Value& item : need(v, key, json::Value::Kind::Array).items) {
    if (item.kind != json::Value::Kind::String)
      throw BadAnswer("\"" + key + "\" holds " + kind_name(item.kind) + ", not a string");
    out.push_back(item.text);
  }
  return out;
}

// The deadline of an answer: $CONTACT2D_MUJOCO3_TIMEOUT seconds (60 by
// default: Node's start and the package's import take ~1 s, several on a
// loaded machine) plus the work asked, at `per_unit` seconds each.
double deadline(double units = 0.0, double per_unit = 0.0) {
  double base = 60.0;
  if (const char* set = std::getenv("CONTACT2D_MUJOCO3_TIMEOUT"); set && *set) {
    char* end = nullptr;
    const double x = std::strtod(set, &end);
    if (end != set && *end == '\0' && x > 0.0) base = x;
  }
  return base + units * per_unit;
}

// A step of one of the scenes' models takes microseconds (~60 µs while
// the JIT warms up): 0.5 ms each is room for a machine ten times slower. A
// user's model settles in slices of kSliceMs (their steps sized to it).
constexpr double kStepSeconds = 5e-4;
constexpr double kSliceMs = 50.0;

// A start that failed for memory (V8's or WebAssembly's own words), and
// what to say of it.
bool short_of_memory(const std::string& said) {
  for (const char* sign : {"Out of memory", "out of memory", "Cannot allocate", "OOM"})
    if (said.find(sign) != std::string::npos) return true;
  return false;
}
constexpr const char* kMemoryHint =
    ": MuJoCo 3's WebAssembly could not reserve its memory (Node reserves several GB of address "
    "space for it): is virtual memory limited (ulimit -v)?";

// Memory a Node running MuJoCo 3 takes (measured 95–140 MB).
constexpr double kNodeBytes = 140e6;
std::atomic<int> g_nodes{0};  // running in this process

double available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string name;
  double kb = 0.0;
  std::string unit;
  while (meminfo >> name >> kb >> unit)
    if (name == "MemAvailable:") return kb * 1024.0;
  return -1.0;  // unknown: not limited here
}

std::atomic<long> g_node_starts{0};  // started in this process

// The thread that starts every Node process: it lives as long as the
// program, so a process outlives the worker that first used it (the kernel
// kills a child when the thread that forked it ends) and ends with the
// program. Never freed: a detached thread waits on it until exit.
struct NodeStarter {
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<std::packaged_task<std::unique_ptr<ChildProcess>()>> tasks;
};

std::unique_ptr<ChildProcess> start_node_process() {
  static NodeStarter* const starter = [] {
    auto* made = new NodeStarter;
    std::thread([made] {
      for (;;) {
        std::unique_lock<std::mutex> lock(made->mutex);
        made->wake.wait(lock, [made] { return !made->tasks.empty(); });
        auto task = std::move(made->tasks.front());
        made->tasks.pop_front();
        lock.unlock();
        task();
      }
    }).detach();
    return made;
  }();
  std::packaged_task<std::unique_ptr<ChildProcess>()> task([] {
    return std::make_unique<ChildProcess>(std::vector<std::string>{find_node(), "driver.mjs"},
                                          package_directory(), /*writes_output=*/false,
                                          /*dies_on_interrupt=*/true);
  });
  std::future<std::unique_ptr<ChildProcess>> started = task.get_future();
  {
    const std::lock_guard<std::mutex> lock(starter->mutex);
    starter->tasks.push_back(std::move(task));
  }
  starter->wake.notify_one();
  return started.get();
}

// Processes whose thread ended, for the next thread that needs one. Never
// destroyed (no Node's destructor after the interrupt handler's registry
// is gone): at the program's end the kernel kills them (the starter thread
// ends).
std::mutex g_idle_nodes_mutex;
std::vector<std::shared_ptr<Node>>& idle_nodes() {
  static auto* const nodes = new std::vector<std::shared_ptr<Node>>;
  return *nodes;
}

// A thread's process; at the thread's end an idle one goes to idle_nodes().
struct ThreadNode {
  std::shared_ptr<Node> node;
  ThreadNode() = default;
  ThreadNode(const ThreadNode&) = delete;
  ThreadNode& operator=(const ThreadNode&) = delete;
  ~ThreadNode() {
    // Another owner (a stepper that outlived the thread) may still use it.
    if (!node || node.use_count() != 1 || !node->usable()) return;
    node->take_messages();
    const std::lock_guard<std::mutex> lock(g_idle_nodes_mutex);
    idle_nodes().push_back(std::move(node));
  }
};

std::shared_ptr<Node> idle_node() {
  const std::lock_guard<std::mutex> lock(g_idle_nodes_mutex);
  std::vector<std::shared_ptr<Node>>& nodes = idle_nodes();
  while (!nodes.empty()) {
    std::shared_ptr<Node> node = std::move(nodes.back());
    nodes.pop_back();
    if (node->usable()) return node;  // else it died while idle
  }
  return nullptr;
}

std::string numbers(const std::vector<double>& values) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i ? "," : "") + json::number(values[i]);
  return out + "]";
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

std::string too_many_nodes(int running, double available_bytes) {
  if (running < 1 || available_bytes < 0.0 || available_bytes >= 2.0 * kNodeBytes) return {};
  const int fits = running + std::max(0, static_cast<int>(available_bytes / kNodeBytes) - 1);
  return "mujoco3: " + std::to_string(running) +
         " MuJoCo 3 processes run already (Node.js, one per thread that runs MuJoCo 3, each " +
         "95-140 MB) and " + std::to_string(static_cast<long long>(available_bytes / 1e6)) +
         " MB of memory are available: run with --threads " + std::to_string(fits) + " or fewer";
}

struct Node::Answer {
  json::Value value;
};

std::shared_ptr<Node> Node::of_this_thread() {
  thread_local ThreadNode held;
  // One that died while idle (killed, out of memory) is replaced too: the
  // next call must not fail for it.
  if (held.node && held.node->usable()) return held.node;
  held.node = idle_node();
  if (!held.node) held.node.reset(new Node());
  return held.node;
}

long Node::starts() { return g_node_starts.load(); }

bool Node::usable() const { return !failed_ && process_->running(); }

Node::Node() {
  const std::string why = missing();
  if (!why.empty()) throw InputError(why);
  const std::string crowded = too_many_nodes(g_nodes.load(), available_memory());
  if (!crowded.empty()) throw InputError(crowded);
  try {
    process_ = start_node_process();
    ++g_node_starts;
  } catch (const ChildProcessError& e) {
    throw InputError("mujoco3: " + std::string(e.what()) + ": " + fix_command());
  }
  const Answer hello = request(
      "hello", R"({"op":"hello","protocol":)" + std::to_string(kProtocol) + "}", deadline());
  const auto [version, node, protocol] = checked("hello", [&] {
    return std::make_tuple(need_text(hello.value, "version"), need_text(hello.value, "node"),
                           need_integer(hello.value, "protocol"));
  });
  if (protocol != kProtocol)
    throw InputError("mujoco3: " + package_directory() + "/driver.mjs speaks protocol " +
                     std::to_string(protocol) + ", contact2d " + std::to_string(kProtocol) +
                     ": CONTACT2D_MUJOCO3_DIR names another checkout's driver");
  if (version != kVersion)
    throw InputError("mujoco3: Node loaded MuJoCo " + version + ", contact2d is pinned to " +
                     std::string(kVersion) + ": " + fix_command());
  const int node_major = static_cast<int>(std::strtol(node.c_str(), nullptr, 10));
  if (node_major < kOldestNode)
    throw InputError("mujoco3: Node " + node + " is older than " + std::to_string(kOldestNode) +
                     ", which @mujoco/mujoco needs: " + fix_command());
  counted_ = true;
  ++g_nodes;
}

Node::~Node() {
  if (counted_) --g_nodes;
}

int Node::pid() const { return static_cast<int>(process_->pid()); }

template <typename F>
auto Node::checked(const std::string& op, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const BadAnswer& e) {
    failed_ = true;
    throw EngineError("mujoco3: the Node process running MuJoCo " + std::string(kVersion) +
                      " answered " + op + " with " + e.what() + " (" + fix_command() + ")");
  }
}

void Node::lost(const std::string& why) {
  failed_ = true;
  throw EngineError("mujoco3: the Node process running MuJoCo " + std::string(kVersion) +
                    " failed: " + why + " (" + fix_command() + ")");
}

Node::Answer Node::request(const std::string& op, const std::string& line, double seconds,
                           const std::string& origin, bool verbatim) {
  // One that failed is not spoken to again (what it would answer cannot be
  // trusted): its holders (a stepper freeing its model) hear so at once.
  if (failed_)
    throw EngineError("mujoco3: the Node process running MuJoCo " + std::string(kVersion) +
                      " failed before " + op);
  Answer a;
  std::string text;
  try {
    process_->set_deadline(seconds);
    process_->write(line + "\n");
    text = process_->read_line();
    a.value = json::parse(text, "the MuJoCo 3 process's answer to " + op);
  } catch (const Cancelled&) {  // the process was killed with the wait
    failed_ = true;
    throw;
  } catch (const std::exception& e) {
    if (op == "hello" && short_of_memory(e.what())) {  // it could not start
      failed_ = true;
      throw InputError("mujoco3: Node could not start MuJoCo " + std::string(kVersion) + ": " +
                       e.what() + kMemoryHint);
    }
    lost(e.what());
  }
  if (a.value.kind != json::Value::Kind::Object) lost("its answer to " + op + " is not an object");
  if (const json::Value* said = a.value.get("messages"))
    for (const json::Value& m : said->items) messages_.push_back(m.text);
  const bool ok = checked(op, [&] { return need_flag(a.value, "ok"); });
  if (ok) return a;
  const std::string error = checked(op, [&] { return need_text(a.value, "error"); });
  if (const json::Value* fatal = a.value.get("fatal"); fatal && fatal->text == "true")
    failed_ = true;  // MuJoCo's WebAssembly aborted: the process ends
  if (op == "hello") {
    // The driver could not import the package, or speaks another protocol.
    failed_ = true;
    if (short_of_memory(error)) throw InputError("mujoco3: " + error + kMemoryHint);
    throw InputError("mujoco3: " + error + " (" + fix_command() + ")");
  }
  if (verbatim && error.rfind("diverged: ", 0) == 0) throw EngineError(error.substr(10));
  if (verbatim && !failed_) throw InputError(error);
  if (!origin.empty())
    throw InputError(origin + ": MuJoCo " + std::string(kVersion) +
                     " cannot load the model: " + error);
  failed_ = true;
  throw EngineError("mujoco3: MuJoCo " + std::string(kVersion) + " failed at " + op + ": " + error);
}

LoadedModel Node::load(const std::string& xml, const std::string& origin) {
  // Compiling: ~1 µs per byte of MJCF on a loaded machine, and ten times that.
  const Answer a = request("load", R"({"op":"load","xml":)" + json::string(xml) + "}",
                           deadline(static_cast<double>(xml.size()), 1e-5), origin);
  return checked("load", [&] {
    LoadedModel m;
    m.id = static_cast<int>(need_integer(a.value, "id", 1));
    m.nq = static_cast<int>(need_integer(a.value, "nq"));
    m.nv = static_cast<int>(need_integer(a.value, "nv"));
    m.nbody = static_cast<int>(need_integer(a.value, "nbody", 1));
    m.timestep = need_number(a.value, "timestep");
    m.body_pos = need_numbers(a.value, "body_pos", 3 * static_cast<size_t>(m.nbody));
    m.body_invweight0 = need_numbers(a.value, "body_invweight0", 2 * static_cast<size_t>(m.nbody));
    return m;
  });
}

void Node::free(int id) {
  request("free", R"({"op":"free","id":)" + std::to_string(id) + "}", deadline());
}

void Node::reset(int id, const std::vector<double>& qpos, const std::vector<double>& qvel) {
  request("reset",
          R"({"op":"reset","id":)" + std::to_string(id) + R"(,"qpos":)" + numbers(qpos) +
              R"(,"qvel":)" + numbers(qvel) + "}",
          deadline());
}

void Node::applied(int id, int body, const std::array<double, 6>& xfrc) {
  request("applied",
          R"({"op":"applied","id":)" + std::to_string(id) + R"(,"body":)" + std::to_string(body) +
              R"(,"xfrc":)" + numbers({xfrc.begin(), xfrc.end()}) + "}",
          deadline());
}

int Node::step(int id, int n, int width, std::vector<double>& out, bool& bad) {
  const Answer a = request(
      "step", R"({"op":"step","id":)" + std::to_string(id) + R"(,"n":)" + std::to_string(n) + "}",
      deadline(n, kStepSeconds));
  // Exactly the steps' qpos and qvel, checked before a byte is read.
  const auto [steps, bytes] = checked("step", [&] {
    bad = need_flag(a.value, "bad");
    const long long taken = need_integer(a.value, "steps", 0, n);
    const long long size = need_integer(a.value, "bytes", 0, 1LL << 53);
    const long long expected = taken * width * static_cast<long long>(sizeof(double));
    if (size != expected)
      throw BadAnswer("\"bytes\" " + std::to_string(size) + " where " + std::to_string(taken) +
                      " steps of nq + nv = " + std::to_string(width) + " doubles are " +
                      std::to_string(expected));
    return std::make_pair(static_cast<int>(taken), static_cast<size_t>(size));
  });
  out.resize(bytes / sizeof(double));
  try {
    process_->read_bytes(out.data(), bytes);
  } catch (const Cancelled&) {
    failed_ = true;
    throw;
  } catch (const std::exception& e) {
    lost(e.what());
  }
  return steps;
}

void Node::rewind(int id, int n) {
  request("rewind",
          R"({"op":"rewind","id":)" + std::to_string(id) + R"(,"n":)" + std::to_string(n) + "}",
          deadline(n, kStepSeconds));
}

namespace {

// A sparse row {index, value}: as many columns as values.
mujoco::SparseRow sparse_of(const json::Value& v) {
  mujoco::SparseRow row;
  row.index = need_integers(v, "index");
  row.value = need_numbers(v, "value");
  if (row.index.size() != row.value.size())
    throw BadAnswer("a sparse row has " + std::to_string(row.index.size()) + " columns and " +
                    std::to_string(row.value.size()) + " values");
  return row;
}

template <size_t N>
void fill(const json::Value& v, const char* key, std::array<double, N>& out) {
  const std::vector<double> numbers = need_numbers(v, key, N);
  std::copy(numbers.begin(), numbers.end(), out.begin());
}

// One mjContact of the driver's "read" answer, with its bodies' mj_jac and
// its mj_contactForce (mujoco/state_arrays.hpp); every key is required (a
// missing one throws BadAnswer, never reads as 0).
mujoco::ArrayContact contact_of(const json::Value& c) {
  mujoco::ArrayContact out;
  out.geom1 = static_cast<int>(need_integer(c, "geom1"));
  out.geom2 = static_cast<int>(need_integer(c, "geom2"));
  out.dim = static_cast<int>(need_integer(c, "dim", 1, 6));
  out.exclude = static_cast<int>(need_integer(c, "exclude", std::numeric_limits<int>::min()));
  out.efc_address =
      static_cast<int>(need_integer(c, "efc_address", std::numeric_limits<int>::min()));
  out.dist = need_number(c, "dist");
  out.includemargin = need_number(c, "includemargin");
  fill(c, "pos", out.pos);
  fill(c, "frame", out.frame);
  fill(c, "friction", out.friction);
  fill(c, "solref", out.solref);
  fill(c, "solreffriction", out.solreffriction);
  fill(c, "solimp", out.solimp);
  out.normal_force = need_number(c, "normal_force");
  for (const auto& [key, jac] : {std::pair{"jac1", &out.jac1}, std::pair{"jac2", &out.jac2}}) {
    const json::Value& rows = need(c, key, json::Value::Kind::Array);
    if (rows.items.size() != 3)
      throw BadAnswer(std::string("\"") + key + "\" has " + std::to_string(rows.items.size()) +
                      " rows, not 3");
    for (size_t k = 0; k < 3; ++k) (*jac)[k] = sparse_of(rows.items[k]);
  }
  return out;
}

// MuJoCo's arrays of the driver's "read" answer (mujoco/state_arrays.hpp).
mujoco::StateArrays arrays_of(const json::Value& v) {
  mujoco::StateArrays a;
  a.margin_rule = mujoco::MarginRule::Summed;  // MuJoCo 3's collision driver
  a.nv = static_cast<int>(need_integer(v, "nv"));
  a.elliptic = need_flag(v, "elliptic");
  a.body_names = need_texts(v, "body_names");
  a.geom_names = need_texts(v, "geom_names");
  a.body_weldid = need_integers(v, "body_weldid");
  a.body_parentid = need_integers(v, "body_parentid");
  a.body_mass = need_numbers(v, "body_mass");
  a.body_inertia = need_numbers(v, "body_inertia");
  a.body_invweight0 = need_numbers(v, "body_invweight0");
  a.jnt_bodyid = need_integers(v, "jnt_bodyid");
  a.jnt_type = need_integers(v, "jnt_type");
  a.geom_bodyid = need_integers(v, "geom_bodyid");
  a.geom_condim = need_integers(v, "geom_condim");
  a.geom_contype = need_integers(v, "geom_contype");
  a.geom_conaffinity = need_integers(v, "geom_conaffinity");
  a.geom_friction = need_numbers(v, "geom_friction");
  a.geom_margin = need_numbers(v, "geom_margin");
  a.geom_gap = need_numbers(v, "geom_gap");
  a.geom_priority = need_integers(v, "geom_priority");
  a.geom_solmix = need_numbers(v, "geom_solmix");
  a.geom_solref = need_numbers(v, "geom_solref");
  a.pair_geom1 = need_integers(v, "pair_geom1");
  a.pair_geom2 = need_integers(v, "pair_geom2");
  a.pair_margin = need_numbers(v, "pair_margin");
  a.pair_gap = need_numbers(v, "pair_gap");
  a.qvel = need_numbers(v, "qvel");
  a.qacc = need_numbers(v, "qacc");
  a.efc_force = need_numbers(v, "efc_force");
  for (const json::Value& c : need(v, "contacts", json::Value::Kind::Array).items)
    a.contacts.push_back(contact_of(c));
  if (const std::string misfit = mujoco::arrays_misfit(a); !misfit.empty())
    throw BadAnswer("a state whose arrays do not fit together: " + misfit);
  return a;
}

// The rows of a "solve" request: [{"index": [...], "value": [...]}, ...].
std::string rows_json(const std::vector<mujoco::SparseRow>& rows) {
  std::string out = "[";
  for (size_t r = 0; r < rows.size(); ++r) {
    out += r ? ",{\"index\":[" : "{\"index\":[";
    for (size_t k = 0; k < rows[r].index.size(); ++k)
      out += (k ? "," : "") + std::to_string(rows[r].index[k]);
    out += "],\"value\":[";
    for (size_t k = 0; k < rows[r].value.size(); ++k)
      out += (k ? "," : "") + json::number(rows[r].value[k]);
    out += "]}";
  }
  return out + "]";
}

}  // namespace

mujoco::ModelState Node::state(const mujoco::StateRequest& r) {
  const std::string path = std::filesystem::absolute(r.path).string();
  // What Node will read, checked here first: a device or a FIFO would be
  // read without end, a huge file whole (the cap scene files have).
  check_input_file(r.path, "the model");
  // Staging copies at most 256 MiB, at ~50 MB/s on a loaded machine.
  const Answer opened = request("open",
                                R"({"op":"open","path":)" + json::string(path) + R"(,"key":)" +
                                    json::string(r.key) + R"(,"settle":)" + json::number(r.settle) +
                                    R"(,"option":)" + json::string(r.option) + "}",
                                deadline(256.0, 0.02), {}, true);
  const auto [handle, steps] = checked("open", [&] {
    return std::make_pair(need_integer(opened.value, "handle", 1),
                          need_integer(opened.value, "steps", 0, 1000000));
  });
  const std::string id = std::to_string(handle);
  // Settling in slices of ~kSliceMs each (their steps grow while a slice is
  // short), a cancel looked at between them (core/cancel.hpp: a Python
  // Ctrl-C); the model is closed when one comes.
  long long done = 0, slice = 16;
  try {
    while (done < steps) {
      throw_if_cancelled();
      const long long n = std::min(slice, steps - done);
      const auto start = std::chrono::steady_clock::now();
      const Answer a = request("settle",
                               R"({"op":"settle","handle":)" + id + R"(,"n":)" + std::to_string(n) +
                                   R"(,"ms":)" + json::number(kSliceMs) + "}",
                               deadline(static_cast<double>(n), kStepSeconds), {}, true);
      const long long taken =
          checked("settle", [&] { return need_integer(a.value, "done", 1, n); });
      done += taken;
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      if (taken == n && ms < kSliceMs / 2) slice = std::min<long long>(2 * slice, 1 << 20);
    }
    throw_if_cancelled();
  } catch (const Cancelled&) {
    if (!failed_) {
      try {
        request("close", R"({"op":"close","handle":)" + id + "}", deadline(), {}, true);
      } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch)
        // Then it is gone: the next user starts another.
      }
    }
    throw;
  }
  try {
    mujoco::ModelState s = read_state(id);
    request("close", R"({"op":"close","handle":)" + id + "}", deadline(), {}, true);
    return s;
  } catch (const std::exception&) {
    if (!failed_) {
      try {
        request("close", R"({"op":"close","handle":)" + id + "}", deadline(), {}, true);
      } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch)
        // Then it is gone: the next user starts another.
      }
    }
    throw;
  }
}

mujoco::ModelState Node::read_state(const std::string& id) {
  const Answer a = request("read", R"({"op":"read","handle":)" + id + "}", deadline(), {}, true);
  mujoco::ModelState s;
  const mujoco::StateArrays arrays = checked("read", [&] {
    s.version = need_text(a.value, "version");
    s.load_warning = need_text(a.value, "load_warning");
    s.messages = need_texts(a.value, "step_warnings");
    s.timestep = need_number(a.value, "timestep");
    s.integrator = need_text(a.value, "integrator");
    s.elliptic = need_flag(a.value, "elliptic");
    s.impratio = need_number(a.value, "impratio");
    s.noslip_iterations = static_cast<int>(need_integer(a.value, "noslip_iterations"));
    const std::vector<double> g = need_numbers(a.value, "gravity", 3);
    for (size_t i = 0; i < 3; ++i) s.gravity[i] = g[i];
    s.refsafe = need_flag(a.value, "refsafe");
    s.disabled = need_text(a.value, "disabled");
    s.settled = need_number(a.value, "settled");
    mujoco::StateArrays arrays = arrays_of(a.value);
    s.bias = need_numbers(a.value, "bias", static_cast<size_t>(arrays.nv));
    return arrays;
  });
  // M⁻¹ times the rows the reader builds: MuJoCo 3's mj_solveM, one request
  // for all of them (the humanoid's 10 contacts: 30 rows).
  mujoco::read_state_arrays(
      arrays,
      [&](const std::vector<mujoco::SparseRow>& rows) {
        const Answer solved = request(
            "solve", R"({"op":"solve","handle":)" + id + R"(,"rows":)" + rows_json(rows) + "}",
            deadline(static_cast<double>(rows.size()), kStepSeconds), {}, true);
        return checked("solve", [&] {
          std::vector<mujoco::SparseRow> out;
          for (const json::Value& row : need(solved.value, "rows", json::Value::Kind::Array).items)
            out.push_back(sparse_of(row));
          if (out.size() != rows.size())
            throw BadAnswer(std::to_string(out.size()) + " rows for " +
                            std::to_string(rows.size()));
          for (const mujoco::SparseRow& row : out)
            for (size_t i = 0; i < row.index.size(); ++i)
              if (row.index[i] < 0 || row.index[i] >= arrays.nv ||
                  (i > 0 && row.index[i] <= row.index[i - 1]))
                throw BadAnswer("a solved row's columns are out of range or order");
          return out;
        });
      },
      s);
  return s;
}

mujoco::ModelState read_model_state(const mujoco::StateRequest& request) {
  // Before check_state_request, which opens it: opening a FIFO waits for a writer.
  check_input_file(request.path, "the model");
  mujoco::check_state_request(request);
  mujoco::ModelState state = Node::of_this_thread()->state(request);
  if (const std::string note = mujoco::settle_cap_note(request.settle, state.timestep);
      !note.empty())
    state.messages.push_back(note);
  return state;
}

std::vector<std::string> Node::counters(int id) {
  const Answer a =
      request("counters", R"({"op":"counters","id":)" + std::to_string(id) + "}", deadline());
  return checked("counters", [&] { return need_texts(a.value, "warnings"); });
}

std::vector<std::string> Node::take_messages() {
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

}  // namespace contact2d::mujoco3
