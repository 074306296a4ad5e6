// Loading MuJoCo 2.2 models from memory, and MuJoCo's messages.
//
// 2.2.2 has no load-from-string: the XML goes into a virtual file system
// (mjVFS, ~2 MB, so it is allocated on the heap). mj_loadXML returns NULL on
// error and may leave a warning in its error buffer on success (the compiler
// takes one test step); both become InputError. At run time MuJoCo reports
// through mju_warning (text) and mjData.warning (counters); the first is
// collected by a WarningCapture, the second read by the adapter.
#pragma once

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace contact2d::mujoco {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// Compiles MJCF text; `origin` names it in messages. Throws InputError
// ("<origin>: MuJoCo cannot load the model: ..." or "...: MuJoCo warns
// while loading the model: ...").
ModelPtr load_model(const std::string& xml, const std::string& origin);

DataPtr make_data(const mjModel* model);

// While alive, MuJoCo's text warnings on this thread are appended to
// `messages` instead of being printed (and written to MUJOCO_LOG.TXT).
// mju_error, which MuJoCo would end the process on, throws MujocoError.
class WarningCapture {
 public:
  explicit WarningCapture(std::vector<std::string>& messages);
  ~WarningCapture();
  WarningCapture(const WarningCapture&) = delete;
  WarningCapture& operator=(const WarningCapture&) = delete;

 private:
  std::vector<std::string>* previous_;
};

struct MujocoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Text of mjData.warning counters that are non-zero ("bad number in qacc
// (3 times)"), empty when there are none.
std::vector<std::string> warning_counters(const mjData* data);

// A model object's name; "world" for body 0; "<what> #id" when unnamed.
std::string name_of(const mjModel* m, int type, int id, const char* what);

// A model's name as the tool prints and stores it: a control character
// (ESC, a newline: a model is anybody's) as \xNN, and a backslash as \\, so
// that a name can neither move the terminal's cursor nor break a line.
// name_of gives names so, the state reader makes both versions' so
// (state_arrays.cpp), and an option naming a body is compared after the
// same escaping.
std::string printable_name(const std::string& name);

// A contact's normal row of the Jacobian, n·(J_p(body2) − J_p(body1)) at pos.
std::vector<double> normal_jacobian(const mjModel* m, const mjData* d, int body1, int body2,
                                    const std::array<double, 3>& pos,
                                    const std::array<double, 3>& normal);

// A = J·M⁻¹·Jᵀ for one row (mj_solveM on the factor mj_forward left).
double inverse_mass(const mjModel* m, mjData* d, const std::vector<double>& row);

}  // namespace contact2d::mujoco
