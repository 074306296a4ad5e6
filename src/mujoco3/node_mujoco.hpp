// MuJoCo 3 as this program reaches it: the official WebAssembly package
// @mujoco/mujoco, pinned to kVersion by package-lock.json (its integrity
// hash), run by Node.js through driver.mjs (the protocol is described
// there). One Node process per thread, started on first use and kept for
// every model that thread loads (Node and the module take ~1 s to start),
// ended with the thread. Every request carries a batch: a run is a few
// requests of up to thousands of steps each, never one round trip per step.
//
// Errors are one line. What is missing to start (Node, the package, the
// pinned version, a driver of another protocol) is an InputError naming the
// command that fixes it, before any work; MuJoCo 3 refusing a model is an
// InputError with its message (and what MuJoCo printed); a Node process
// that dies, breaks the protocol (a key missing or of the wrong kind, a
// step's bytes not steps·(nq+nv)·8) or fails mid-run is an EngineError
// (core/input_error.hpp).
//
// The process never outlives, outgrows or outwaits the program: it dies
// with it (io/child_process.hpp: PR_SET_PDEATHSIG, the interrupt handler,
// and the driver watching its parent); every answer has a deadline scaled
// to the work asked ($CONTACT2D_MUJOCO3_TIMEOUT seconds, 60 by default,
// plus 0.5 ms a step), past which Node is killed and the run fails; a user's
// model settles in slices of ~50 ms with a cancel looked at between them,
// and a cancel while waiting kills Node (core/cancel.hpp); another Node is
// not started when the memory left would not hold it (too_many_nodes).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mujoco/model_state.hpp"

namespace contact2d {
class ChildProcess;
}

namespace contact2d::mujoco3 {

// The version of @mujoco/mujoco this build is pinned to.
inline constexpr std::string_view kVersion = "3.14.0";
// The version of the protocol spoken with driver.mjs (its PROTOCOL): hello
// carries it both ways and either side refuses another.
inline constexpr int kProtocol = 6;

// Why another Node process should not start when `running` run already
// and `available_bytes` of memory are available (negative: unknown), as
// one line saying what --threads fits; empty when it may.
std::string too_many_nodes(int running, double available_bytes);

// The folder of driver.mjs, package.json, package-lock.json and
// node_modules/: $CONTACT2D_MUJOCO3_DIR, else the source tree's src/mujoco3.
std::string package_directory();

// Why MuJoCo 3 cannot run here, as one line ending in the command that
// fixes it; empty when Node and the pinned package are installed. Looks at
// files only (no process is started).
std::string missing();

// A model loaded in the Node process.
struct LoadedModel {
  int id = 0;
  int nq = 0, nv = 0, nbody = 0;
  double timestep = 0.0;
  std::vector<double> body_pos;         // 3 per body
  std::vector<double> body_invweight0;  // 2 per body: translational, rotational
};

class Node {
 public:
  // This thread's process: on first use an idle one of the process's (one
  // whose thread ended: a worker of an earlier analysis::parallel_for), else
  // started, and again after the last one failed (InputError when
  // missing()). Processes are started from one thread that lives as long as
  // the program (PR_SET_PDEATHSIG kills a child when the thread that
  // started it ends), so a process pays Node's start (about 1 s) once per
  // worker, not once per parallel_for.
  static std::shared_ptr<Node> of_this_thread();
  // Node processes started by this program so far.
  static long starts();
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  // Compiles MJCF text in MuJoCo 3; InputError "<origin>: MuJoCo 3.14.0
  // cannot load the model: ..." on its refusal.
  LoadedModel load(const std::string& xml, const std::string& origin);
  void free(int id);
  // mj_resetData, then this qpos and qvel.
  void reset(int id, const std::vector<double>& qpos, const std::vector<double>& qvel);
  // xfrc_applied of `body`.
  void applied(int id, int body, const std::array<double, 6>& xfrc);
  // Up to n mj_step; after each, qpos (nq) then qvel (nv), `width` = nq +
  // nv doubles, appended to `out` (cleared first). Stops after a step that
  // raised a bad-number counter (bad = true). Returns the steps taken.
  int step(int id, int n, int width, std::vector<double>& out, bool& bad);
  // Back to the state before the last step() and n steps again.
  void rewind(int id, int n);
  // A user's model file at one state (mujoco/model_state.hpp), as 3.14
  // loads, settles and reads it; InputError with the driver's one line
  // (MuJoCo 3 refusing the model, an unknown keyframe).
  mujoco::ModelState state(const mujoco::StateRequest& request);
  // MuJoCo's non-zero warning counters ("... (N times)").
  std::vector<std::string> counters(int id);
  // MuJoCo's printed messages since the last call.
  std::vector<std::string> take_messages();
  // The process's id (tests kill it).
  int pid() const;
  // Neither failed nor ended: another request may be sent.
  bool usable() const;

 private:
  Node();
  struct Answer;
  // The answer to `line` (the request `op`) within `seconds`. origin
  // non-empty: an error is MuJoCo refusing that model; `verbatim`: an
  // error is the driver's own line, an InputError.
  Answer request(const std::string& op, const std::string& line, double seconds,
                 const std::string& origin = {}, bool verbatim = false);
  // read() of an answer to `op`; a missing or mistyped key is an EngineError.
  template <typename F>
  auto checked(const std::string& op, F&& read) -> decltype(read());
  [[noreturn]] void lost(const std::string& why);  // failed: an EngineError
  // state()'s read of an opened model (the handle `id`), its rows solved.
  mujoco::ModelState read_state(const std::string& id);

  std::unique_ptr<ChildProcess> process_;
  std::vector<std::string> messages_;
  bool failed_ = false;   // it died or broke the protocol: the next user starts another
  bool counted_ = false;  // started and answered hello: one of g_nodes
};

// mujoco/model_state.hpp's read_model_state, in MuJoCo 3.14 (this
// thread's Node process).
mujoco::ModelState read_model_state(const mujoco::StateRequest& request);

}  // namespace contact2d::mujoco3
