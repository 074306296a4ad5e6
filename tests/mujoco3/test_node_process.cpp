// MuJoCo 3's Node process hardened (issue 49, sections 1-3): it never
// outlives, outgrows or outwaits contact2d, and its protocol cannot be
// misread. Every hang and signal here is a private process or file the test
// makes (a FIFO, a sparse file, a SIGSTOPped Node, a patched copy of the
// driver); a test that would hang without its fix has a watchdog that ends
// the process it waits on and fails instead.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/cancel.hpp"
#include "core/input_error.hpp"
#include "io/child_process.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string slurp_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// /proc/PID/stat's state letter ("" when there is no such process).
std::string state_of(int pid) {
  const std::string line = slurp_file("/proc/" + std::to_string(pid) + "/stat");
  const size_t close = line.rfind(')');
  return close == std::string::npos || close + 2 >= line.size() ? "" : line.substr(close + 2, 1);
}

// Gone: no process, or a zombie nobody reaped yet (it runs no more).
bool gone(int pid) {
  const std::string s = state_of(pid);
  return s.empty() || s == "Z" || s == "X";
}

bool wait_gone(int pid, double seconds) {
  const auto start = Clock::now();
  while (!gone(pid) && since(start) < seconds)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return gone(pid);
}

// The running children of `parent` whose command line holds `needle`.
std::vector<int> children_of(int parent, const std::string& needle) {
  std::vector<int> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = slurp_file(e.path() / "stat");
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 2));
    std::string state;
    int ppid = 0;
    rest >> state >> ppid;
    if (ppid != parent || state == "Z") continue;
    if (slurp_file(e.path() / "cmdline").find(needle) != std::string::npos)
      out.push_back(std::stoi(name));
  }
  return out;
}

// Runs `body`; if it has not returned after `seconds`, `rescue` runs (it
// must make `body` return: kill the process it waits on) and the test fails.
void within(double seconds, const std::function<void()>& body,
            const std::function<void()>& rescue) {
  std::mutex m;
  std::condition_variable cv;
  bool done = false, rescued = false;
  std::thread watchdog([&] {
    std::unique_lock<std::mutex> lock(m);
    if (!cv.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return done; })) {
      rescued = true;
      lock.unlock();
      rescue();
    }
  });
  try {
    body();
  } catch (...) {
    {
      const std::lock_guard<std::mutex> lock(m);
      done = true;
    }
    cv.notify_all();
    watchdog.join();
    throw;
  }
  {
    const std::lock_guard<std::mutex> lock(m);
    done = true;
  }
  cv.notify_all();
  watchdog.join();
  EXPECT_FALSE(rescued) << "did not return within " << seconds << " s (rescued)";
}

// A model MuJoCo takes minutes to settle for 1e300 s (1e6 steps of 40
// spheres piled in a box).
std::string slow_model() {
  std::string xml =
      "<mujoco><option timestep=\"0.002\"/><worldbody>"
      "<geom type=\"plane\" size=\"1 1 .1\"/>";
  for (int i = 0; i < 40; ++i) {
    xml += "<body pos=\"" + std::to_string(0.01 * (i % 5)) + " " + std::to_string(0.01 * (i % 3)) +
           " " + std::to_string(0.1 + 0.09 * i) +
           "\"><freejoint/><geom type=\"sphere\" size=\".04\"/></body>";
  }
  return xml + "</worldbody></mujoco>\n";
}

class NodeProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_node_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "work");
    write("work/box.toml",
          "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\nmu = 0.5\ndamping = \"kelvin_voigt\"\n"
          "[initial]\ny = 0.5\ntheta = 0.3\n[sim]\ndt = 1e-4\nduration = 0.5\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) const {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }

  struct Result {
    int status = -1;
    std::string out, err;
  };
  // contact2d ARGS in work/, `env` before it, ended after 60 s (a hang).
  Result run(const std::string& args, const std::string& env = "") const {
    const std::string out = (dir_ / "stdout").string(), err = (dir_ / "stderr").string();
    const std::string command = "cd '" + (dir_ / "work").string() + "' && timeout -s KILL 60 env " +
                                env + " '" CONTACT2D_BINARY "' " + args + " >'" + out + "' 2>'" +
                                err + "'";
    const int raw = std::system(command.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp_file(out), slurp_file(err)};
  }

  // A copy of the package folder: the driver with `patch` applied
  // (old → new, each must match) and `extra` appended, beside the real
  // node_modules; CONTACT2D_MUJOCO3_DIR=<it> points the program there.
  std::string driver(const std::vector<std::pair<std::string, std::string>>& patch,
                     const std::string& extra = "") const {
    const fs::path real = mujoco3::package_directory();
    const fs::path fake = dir_ / "mujoco3";
    fs::create_directories(fake);
    std::string text = slurp_file(real / "driver.mjs");
    for (const auto& [from, to] : patch) {
      const size_t at = text.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      if (at != std::string::npos) text.replace(at, from.size(), to);
    }
    std::ofstream(fake / "driver.mjs") << text << extra;
    if (!fs::exists(fake / "node_modules"))
      fs::create_directory_symlink(real / "node_modules", fake / "node_modules");
    return "CONTACT2D_MUJOCO3_DIR='" + fake.string() + "'";
  }

  fs::path dir_;
};

void expect_single_line(const std::string& err, const std::string& needle) {
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find(needle), std::string::npos) << err;
}

// ---- 1. Node never outlives or outgrows contact2d --------------------------

// A FIFO nobody writes and a huge (sparse) file are refused in C++ with one
// line before Node sees them (before: the FIFO blocked forever, a device
// was read at ~110 MB/s without end).
TEST_F(NodeProcess, ModelFileIsCheckedBeforeNodeSeesIt) {
  CONTACT2D_NEEDS_MUJOCO3();
  ASSERT_EQ(::mkfifo((dir_ / "work/fifo.xml").c_str(), 0600), 0);
  {
    std::ofstream big(dir_ / "work/big.xml");
    big << "<mujoco/>";
  }
  fs::resize_file(dir_ / "work/big.xml", 5u << 20);
  fs::create_directories(dir_ / "work/folder.xml");
  for (const std::string& command : {std::string("inspect fifo.xml --engine mujoco3"),
                                     std::string("solref --model fifo.xml --engine mujoco3 "
                                                 "--body b --k 1e4 --c 10")}) {
    const Result r = run(command);
    EXPECT_EQ(r.status, 2) << command << ": " << r.err;
    expect_single_line(r.err,
                       "fifo.xml: cannot read the model (a pipe or socket, not a regular file");
  }
  Result r = run("inspect big.xml --engine mujoco3");
  EXPECT_EQ(r.status, 2) << r.err;
  expect_single_line(r.err, "big.xml: cannot read the model (larger than 4 MiB");
  r = run("inspect folder.xml --engine mujoco3");
  EXPECT_EQ(r.status, 2) << r.err;
  expect_single_line(r.err, "folder.xml: cannot read the model (a directory, not a file)");
}

// The folder copy checks sizes before it reads: a 300 MiB (sparse) sibling
// the model does not name is left out (the model loads, as on 2.2.2), one
// it names is refused in one line, and Node's memory never holds either
// (before: read whole first, 408 MB peak here; Node reached 2.0 GB on a
// larger folder).
TEST_F(NodeProcess, FolderCopyChecksSizesBeforeReading) {
  CONTACT2D_NEEDS_MUJOCO3();
  const std::string ball =
      "<worldbody><body><freejoint/><geom size=\".1\"/></body></worldbody></mujoco>\n";
  write("m/model.xml", "<mujoco><include file=\"part.xml\"/>" + ball);
  write("m/part.xml", "<mujoco><option timestep=\"0.001\"/></mujoco>\n");
  write("m/data.bin", "x");
  fs::resize_file(dir_ / "m/data.bin", 300u << 20);
  write("n/model.xml", "<mujoco><include file=\"big.xml\"/>" + ball);
  write("n/big.xml", "<mujoco/>");
  fs::resize_file(dir_ / "n/big.xml", 300u << 20);
  std::thread([&] {  // a Node of its own
    auto node = mujoco3::Node::of_this_thread();
    const int pid = node->pid();
    mujoco::StateRequest request;
    request.path = (dir_ / "m/model.xml").string();
    EXPECT_NO_THROW(mujoco3::read_model_state(request));
    request.path = (dir_ / "n/model.xml").string();
    try {
      mujoco3::read_model_state(request);
      ADD_FAILURE() << "loaded an include of 300 MiB";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("big.xml"), std::string::npos) << what;
      EXPECT_NE(what.find("more than 256 MiB"), std::string::npos) << what;
    }
    // Its peak resident memory: Node and MuJoCo (~100-140 MB), never a file.
    const std::string status = slurp_file("/proc/" + std::to_string(pid) + "/status");
    const size_t at = status.find("VmHWM:");
    ASSERT_NE(at, std::string::npos);
    const double peak_mb = std::stod(status.substr(at + 6)) / 1024.0;
    std::printf("Node's peak resident memory: %.0f MB\n", peak_mb);
    EXPECT_LT(peak_mb, 290.0);
  })
      .join();
}

// Models that MuJoCo 2.2.2 loads from the disk load on 3.14 too: a sibling
// whose name is not UTF-8, a file name with a backslash, an include outside
// the folder (../ and an absolute path), a symlinked asset.
TEST_F(NodeProcess, ModelsLoadAsOnMujoco222) {
  CONTACT2D_NEEDS_MUJOCO3();
  const std::string tet =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string body =
      "<worldbody><geom type=\"plane\" size=\"1 1 .1\"/><body pos=\"0 0 1\"><freejoint/>"
      "<geom type=\"mesh\" mesh=\"m\"/></body></worldbody></mujoco>\n";
  write("a/tet.obj", tet);
  write("a/\xff\xfe.bin", "not UTF-8");
  write("a/model.xml", "<mujoco><asset><mesh name=\"m\" file=\"tet.obj\"/></asset>" + body);
  write("b/x\\y.obj", tet);
  write("b/model.xml", "<mujoco><asset><mesh name=\"m\" file=\"x\\y.obj\"/></asset>" + body);
  write("c/shared/inc.xml", "<mujoco><asset><mesh name=\"m\" file=\"" +
                                (dir_ / "c/meshes/tet.obj").string() + "\"/></asset></mujoco>\n");
  write("c/meshes/tet.obj", tet);
  write("c/model/model.xml", "<mujoco><include file=\"../shared/inc.xml\"/>" + body);
  write("d/real/tet.obj", tet);
  fs::create_symlink(dir_ / "d/real/tet.obj", dir_ / "d/link.obj");
  write("d/model.xml", "<mujoco><asset><mesh name=\"m\" file=\"link.obj\"/></asset>" + body);
  for (const char* model : {"a/model.xml", "b/model.xml", "c/model/model.xml", "d/model.xml"}) {
    mujoco::StateRequest request;
    request.path = (dir_ / model).string();
    const mujoco::ModelState two = mujoco::read_model_state(request);
    try {
      const mujoco::ModelState three = mujoco3::read_model_state(request);
      EXPECT_EQ(three.body_names.size(), two.body_names.size()) << model;
      EXPECT_EQ(three.geom_names.size(), two.geom_names.size()) << model;
    } catch (const std::exception& e) {
      ADD_FAILURE() << model << ": " << e.what();
    }
  }
  // What 2.2.2 cannot load either is one line naming the file.
  write("e/model.xml", "<mujoco><include file=\"../nowhere/inc.xml\"/>" + body);
  mujoco::StateRequest request;
  request.path = (dir_ / "e/model.xml").string();
  try {
    mujoco3::read_model_state(request);
    ADD_FAILURE() << "loaded a model whose include is missing";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find("nowhere/inc.xml"), std::string::npos) << what;
  }
}

// Node dies with contact2d on SIGINT, SIGTERM and SIGKILL, in the middle of
// a settle of minutes (before: it settled on under PID 1 for ~17 min). The
// three programs run side by side.
TEST_F(NodeProcess, NodeDiesWithTheProgramOnEverySignal) {
  CONTACT2D_NEEDS_MUJOCO3();
  write("work/slow.xml", slow_model());
  const std::vector<int> signals = {SIGINT, SIGTERM, SIGKILL};
  std::vector<pid_t> programs;
  for (size_t i = 0; i < signals.size(); ++i) {
    const pid_t program = ::fork();
    ASSERT_GE(program, 0);
    if (program == 0) {
      ::chdir((dir_ / "work").c_str());
      for (int s : {SIGINT, SIGTERM}) ::signal(s, SIG_DFL);  // ctest may start us with them ignored
      const int null =
          ::open((dir_ / ("out" + std::to_string(i))).c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
      ::execl(CONTACT2D_BINARY, CONTACT2D_BINARY, "inspect", "slow.xml", "--engine", "mujoco3",
              "--settle", "1e300", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    programs.push_back(program);
  }
  // Their Nodes, then settling for a while.
  std::vector<int> nodes(programs.size(), 0);
  const auto start = Clock::now();
  for (size_t i = 0; i < programs.size(); ++i) {
    while (nodes[i] == 0 && since(start) < 30) {
      const std::vector<int> found = children_of(programs[i], "driver.mjs");
      if (!found.empty()) nodes[i] = found[0];
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  for (size_t i = 0; i < programs.size(); ++i) {
    const char* name = strsignal(signals[i]);
    if (nodes[i] == 0 || gone(nodes[i])) {
      ADD_FAILURE() << name << ": no Node settling before the signal";
      ::kill(programs[i], SIGKILL);
      ::waitpid(programs[i], nullptr, 0);
      continue;
    }
    ::kill(programs[i], signals[i]);
    ::waitpid(programs[i], nullptr, 0);
    const auto sent = Clock::now();
    const bool ended = wait_gone(nodes[i], 10.0);
    std::printf("%s: Node %s %.3f s after the signal\n", name, ended ? "gone" : "still running",
                since(sent));
    EXPECT_TRUE(ended) << name;
    if (!ended) ::kill(nodes[i], SIGKILL);
  }
}

// A settle is cancellable: a cancel (Python's Ctrl-C) ends it in a slice,
// and the thread's Node serves the next request.
TEST_F(NodeProcess, SettleIsCancellable) {
  CONTACT2D_NEEDS_MUJOCO3();
  write("slow.xml", slow_model());
  std::thread([&] {
    auto node = mujoco3::Node::of_this_thread();
    const int pid = node->pid();
    std::thread canceller([] {
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      request_cancel();
    });
    mujoco::StateRequest request;
    request.path = (dir_ / "slow.xml").string();
    request.settle = 1e300;
    Clock::time_point cancelled;
    within(
        20.0,
        [&] {
          try {
            mujoco3::read_model_state(request);
            ADD_FAILURE() << "settled 1e6 steps";
          } catch (const Cancelled&) {
            cancelled = Clock::now();
          }
        },
        [&] { ::kill(pid, SIGKILL); });
    canceller.join();
    clear_cancel();
    // The settle stopped (Node is not left stepping), and the next request runs.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const std::string stat = slurp_file("/proc/" + std::to_string(pid) + "/stat");
    EXPECT_TRUE(gone(pid) || stat.find(") S ") != std::string::npos) << stat;
    request.settle = 0.01;
    EXPECT_NO_THROW(mujoco3::read_model_state(request));
  }).join();
}

// --threads is capped by memory: another Node is not started when the
// memory left would not hold it, and the message says what fits.
TEST(NodeMemory, ThreadsAreCappedByMemory) {
  EXPECT_EQ(mujoco3::too_many_nodes(0, 50e6), "");  // the first always starts
  EXPECT_EQ(mujoco3::too_many_nodes(10, 20e9), "");
  EXPECT_EQ(mujoco3::too_many_nodes(10, -1.0), "");  // unknown
  const std::string said = mujoco3::too_many_nodes(12, 250e6);
  EXPECT_NE(said.find("12 MuJoCo 3 processes run already"), std::string::npos) << said;
  EXPECT_NE(said.find("95-140 MB"), std::string::npos) << said;
  EXPECT_NE(said.find("--threads 12 or fewer"), std::string::npos) << said;
}

// ---- 2. No wait without a deadline -------------------------------------------

// A stopped Node (SIGSTOP) is a one-line engine error once the answer's
// deadline passes ($CONTACT2D_MUJOCO3_TIMEOUT = 2 s here), and it is
// killed (before: a read blocked forever).
TEST_F(NodeProcess, AStoppedNodeFailsAtTheDeadline) {
  CONTACT2D_NEEDS_MUJOCO3();
  std::thread([&] {
    ::setenv("CONTACT2D_MUJOCO3_TIMEOUT", "2", 1);
    auto node = mujoco3::Node::of_this_thread();
    const int pid = node->pid();
    mujoco3::LoadedModel m = node->load(
        "<mujoco><worldbody><body><freejoint/><geom size=\".1\"/></body></worldbody></mujoco>",
        "test");
    ::kill(pid, SIGSTOP);
    std::vector<double> out;
    bool bad = false;
    const auto start = Clock::now();
    within(
        20.0,
        [&] {
          try {
            node->step(m.id, 100, m.nq + m.nv, out, bad);
            ADD_FAILURE() << "a stopped Node answered";
          } catch (const EngineError& e) {
            EXPECT_NE(std::string(e.what()).find("did not answer within 2.05 s (it was stopped)"),
                      std::string::npos)
                << e.what();
          }
        },
        [&] { ::kill(pid, SIGKILL); });
    ::unsetenv("CONTACT2D_MUJOCO3_TIMEOUT");
    std::printf("stopped Node: failed after %.2f s\n", since(start));
    EXPECT_TRUE(wait_gone(pid, 5.0));
    EXPECT_NE(mujoco3::Node::of_this_thread()->pid(), pid);  // the next user starts another
  }).join();
}

// A child that writes much to its standard error never blocks this side:
// it is drained while waiting (before: a chatty child filled the pipe and
// both waited for ever).
TEST(ChildProcessStderr, AChattyChildDoesNotDeadlock) {
  ChildProcess child({"sh", "-c",
                      "i=0; while [ $i -lt 2000 ]; do echo 'a line of chatter on stderr, forty "
                      "bytes or so' >&2; i=$((i+1)); done; echo answered"});
  child.set_deadline(20.0);
  std::string line;
  const pid_t pid = child.pid();
  within(
      25.0, [&] { line = child.read_line(); }, [&] { ::kill(pid, SIGKILL); });
  EXPECT_EQ(line, "answered");
}

// Node itself with NODE_OPTIONS=--trace-sync-io (a stack trace on stderr
// for every synchronous file read): repeated inspects run through.
TEST_F(NodeProcess, AChattyNodeDoesNotDeadlock) {
  CONTACT2D_NEEDS_MUJOCO3();
  for (int i = 0; i < 20; ++i)
    write("m/part" + std::to_string(i) + ".xml", "<mujoco><compiler angle=\"radian\"/></mujoco>\n");
  std::string includes;
  for (int i = 0; i < 20; ++i) includes += "<include file=\"part" + std::to_string(i) + ".xml\"/>";
  write("m/model.xml", "<mujoco>" + includes +
                           "<worldbody><body><freejoint/><geom size=\".1\"/></body></worldbody>"
                           "</mujoco>\n");
  std::thread([&] {
    ::setenv("NODE_OPTIONS", "--trace-sync-io", 1);
    auto node = mujoco3::Node::of_this_thread();
    ::unsetenv("NODE_OPTIONS");
    const int pid = node->pid();
    mujoco::StateRequest request;
    request.path = (dir_ / "m/model.xml").string();
    within(
        30.0,
        [&] {
          for (int i = 0; i < 10; ++i) {
            try {
              mujoco3::read_model_state(request);
            } catch (const std::exception& e) {
              ADD_FAILURE() << e.what();
              return;
            }
          }
        },
        [&] { ::kill(pid, SIGKILL); });
  }).join();
}

// ---- 3. A protocol that cannot be misread ------------------------------------

// hello carries the protocol's version; a driver of another (another
// checkout's, through CONTACT2D_MUJOCO3_DIR) is refused in one line.
TEST_F(NodeProcess, HelloCarriesTheProtocolVersion) {
  CONTACT2D_NEEDS_MUJOCO3();
  const std::string ours = "const PROTOCOL = " + std::to_string(mujoco3::kProtocol) + ";";
  Result r = run("simulate box.toml --engine mujoco3", driver({{ours, "const PROTOCOL = 1;"}}));
  EXPECT_EQ(r.status, 2) << r.err;
  expect_single_line(
      r.err, "driver.mjs speaks protocol 1, contact2d " + std::to_string(mujoco3::kProtocol));
  // A driver that says nothing of a protocol (one from before it).
  r = run("simulate box.toml --engine mujoco3",
          driver({{"if (r.protocol !== PROTOCOL) {", "if (false) {"},
                  {"      protocol: PROTOCOL\n", "\n"}}));
  EXPECT_EQ(r.status, 3) << r.err;
  expect_single_line(r.err, "answered hello with no \"protocol\"");
}

// A missing key is an engine error (exit 3, one line), never 0 and never a
// null dereference; a step's bytes are checked before anything is read.
TEST_F(NodeProcess, AnswersAreReadStrictly) {
  CONTACT2D_NEEDS_MUJOCO3();
  const auto patched = [&](const std::string& op, const std::string& change) {
    return driver({}, "\n{ const original = ops." + op + "; ops." + op +
                          " = (r) => { const a = original(r); " + change + " return a; }; }\n");
  };
  struct Case {
    std::string op, change, command, said;
  };
  write("work/ball.xml",
        "<mujoco><worldbody><geom type=\"plane\" size=\"1 1 .1\"/><body pos=\"0 0 .1\">"
        "<freejoint/><geom size=\".1\"/></body></worldbody></mujoco>\n");
  const std::vector<Case> cases = {
      {"load", "delete a.nbody;", "simulate box.toml --engine mujoco3",
       "answered load with no \"nbody\""},
      {"step", "a.bytes += 3;", "simulate box.toml --engine mujoco3",
       "answered step with \"bytes\" "},
      {"step", "a.bytes = 'many';", "simulate box.toml --engine mujoco3",
       "answered step with \"bytes\" is a string, not a number"},
      {"counters", "delete a.warnings;", "simulate box.toml --engine mujoco3",
       "answered counters with no \"warnings\""},
      {"read", "delete a.efc_force;", "inspect ball.xml --engine mujoco3",
       "answered read with no \"efc_force\""},
      {"read", "a.contacts[0].jac2[0] = {index: [99], value: [1]};",
       "inspect ball.xml --engine mujoco3",
       "answered read with a state whose arrays do not fit together: a Jacobian row's columns"},
      {"solve", "a.rows.pop();", "inspect ball.xml --engine mujoco3 --settle 0.5",
       "answered solve with 2 rows for 3"},
  };
  for (const Case& c : cases) {
    const Result r = run(c.command, patched(c.op, c.change));
    EXPECT_EQ(r.status, 3) << c.op << " " << c.change << ": " << r.err;
    expect_single_line(r.err, c.said);
  }
}

// Errors say what happened: an op's error is that op's, not "could not
// import the package"; MuJoCo's own text is kept; a package that cannot
// start MuJoCo is bad input (exit 2), not an engine failure.
TEST_F(NodeProcess, ErrorsSayWhatHappened) {
  CONTACT2D_NEEDS_MUJOCO3();
  Result r = run("simulate box.toml --engine mujoco3",
                 driver({}, "\nops.reset = () => { throw new Error('reset refused'); };\n"));
  EXPECT_EQ(r.status, 3) << r.err;
  expect_single_line(r.err, "mujoco3: MuJoCo 3.14.0 failed at reset: reset refused");
  EXPECT_EQ(r.err.find("import"), std::string::npos) << r.err;

  // Past WebAssembly's 2 GiB: MuJoCo's "Cannot enlarge memory" is kept.
  write("work/huge.xml",
        "<mujoco><asset><hfield name=\"h\" nrow=\"16000\" ncol=\"16000\" size=\"1 1 .1 .1\"/>"
        "</asset><worldbody><geom type=\"hfield\" hfield=\"h\"/></worldbody></mujoco>\n");
  r = run("inspect huge.xml --engine mujoco3");
  EXPECT_EQ(r.status, 2) << r.err;
  expect_single_line(r.err, "Cannot enlarge memory");

  // loadMujoco() failing (a broken package) is in the try: exit 2.
  const std::string env = driver({{"mj = await loadMujoco(",
                                   "mj = await Promise.reject(new "
                                   "Error('instantiation broke'));("}});
  r = run("simulate box.toml --engine mujoco3", env);
  EXPECT_EQ(r.status, 2) << r.err;
  expect_single_line(r.err, "cannot import @mujoco/mujoco: instantiation broke");
}

// A start failure says why: Node's own error, not its version banner.
TEST_F(NodeProcess, AStartFailureSaysWhy) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Result r = run("simulate box.toml --engine mujoco3",
                       driver({{"const PROTOCOL = ",
                                "throw new RangeError('no room to start'); const PROTOCOL = "}}));
  EXPECT_EQ(r.status, 3) << r.err;
  expect_single_line(r.err, "RangeError: no room to start");
  EXPECT_EQ(r.err.find("Node.js v"), std::string::npos) << r.err;
  // Under a limit of virtual memory WebAssembly cannot reserve its memory
  // (before: "exited with status 1: Node.js v20..."). Not under
  // AddressSanitizer, which reserves terabytes of address space itself.
  if (kAddressSanitizer) return;
  for (const char* limit : {"1500000", "600000"}) {
    const Result limited =
        run("simulate box.toml --engine mujoco3",
            std::string("sh -c 'ulimit -v ") + limit + " && exec \"$0\" \"$@\"'");
    EXPECT_EQ(limited.status, 2) << limit << ": " << limited.err;
    expect_single_line(limited.err, "is virtual memory limited (ulimit -v)?");
  }
}

// A relative PATH entry finds node as the shell does, from the working
// folder, although Node runs in the package's folder.
TEST_F(NodeProcess, RelativePathEntriesFindNode) {
  CONTACT2D_NEEDS_MUJOCO3();
  std::string node;
  std::istringstream path(std::getenv("PATH") ? std::getenv("PATH") : "");
  for (std::string dir; std::getline(path, dir, ':');)
    if (node.empty() && ::access((dir + "/node").c_str(), X_OK) == 0) node = dir + "/node";
  ASSERT_FALSE(node.empty());
  fs::create_directories(dir_ / "work/tools");
  fs::create_symlink(fs::canonical(node), dir_ / "work/tools/node");
  const Result r = run("simulate box.toml --engine mujoco3", "PATH=tools");
  EXPECT_EQ(r.status, 0) << r.err;
}

// A thread's Node that died while idle does not fail the next call.
TEST_F(NodeProcess, ANodeThatDiedIdleIsReplaced) {
  CONTACT2D_NEEDS_MUJOCO3();
  write("ball.xml",
        "<mujoco><worldbody><body><freejoint/><geom size=\".1\"/></body></worldbody></mujoco>\n");
  std::thread([&] {
    mujoco::StateRequest request;
    request.path = (dir_ / "ball.xml").string();
    mujoco3::read_model_state(request);
    const int pid = mujoco3::Node::of_this_thread()->pid();
    ::kill(pid, SIGKILL);
    // Until it can be reaped (all its threads ended), without reaping it.
    siginfo_t info{};
    const auto start = Clock::now();
    while (since(start) < 5.0) {
      info.si_pid = 0;
      if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
          info.si_pid == pid)
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_EQ(info.si_pid, pid);
    EXPECT_NO_THROW(mujoco3::read_model_state(request)) << "killed " << pid;
  }).join();
}

}  // namespace
}  // namespace contact2d
