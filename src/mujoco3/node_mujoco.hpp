// MuJoCo 3 as this program reaches it: the official WebAssembly package
// @mujoco/mujoco, pinned to kVersion by package-lock.json (its integrity
// hash), run by Node.js through driver.mjs (the protocol is described
// there). One Node process per thread, started on first use and kept for
// every model that thread loads (Node and the module take ~1 s to start),
// ended with the thread. Every request carries a batch: a run is a few
// requests of up to thousands of steps each, never one round trip per step.
//
// Errors are one line. What is missing to start (Node, the package, the
// pinned version) is an InputError naming the command that fixes it, before
// any work; MuJoCo 3 refusing a model is an InputError with its message; a
// Node process that dies or breaks the protocol mid-run is an EngineError
// (core/input_error.hpp).
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
  // This thread's process: started on first use, and again after the last
  // one failed (InputError when missing()).
  static std::shared_ptr<Node> of_this_thread();
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
  // Up to n mj_step; after each, qpos (nq) then qvel (nv) appended to `out`
  // (cleared first). Stops after a step that raised a bad-number counter
  // (bad = true). Returns the steps taken.
  int step(int id, int n, std::vector<double>& out, bool& bad);
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

 private:
  Node();
  struct Answer;
  // origin non-empty: an error is MuJoCo refusing that model; `verbatim`:
  // an error is the driver's own line, an InputError.
  Answer request(const std::string& line, const std::string& origin = {}, bool verbatim = false);

  std::unique_ptr<ChildProcess> process_;
  std::vector<std::string> messages_;
  bool failed_ = false;  // it died or broke the protocol: the next user starts another
};

// mujoco/model_state.hpp's read_model_state, in MuJoCo 3.14 (this
// thread's Node process).
mujoco::ModelState read_model_state(const mujoco::StateRequest& request);

}  // namespace contact2d::mujoco3
