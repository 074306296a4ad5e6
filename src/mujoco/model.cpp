#include "mujoco/model.hpp"

#include <cstring>
#include <mutex>

#include "core/format.hpp"
#include "core/input_error.hpp"

namespace contact2d::mujoco {
namespace {

thread_local std::vector<std::string>* t_sink = nullptr;

std::string trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (char& ch : text) {
    if (ch == '\n') ch = ' ';
  }
  return text;
}

void on_warning(const char* message) {
  if (t_sink) {
    t_sink->push_back(trim(message));
  } else {
    std::fprintf(stderr, "contact2d: MuJoCo warning: %s\n", trim(message).c_str());
  }
}

[[noreturn]] void on_error(const char* message) { throw MujocoError(trim(message)); }

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = on_warning;
    mju_user_error = on_error;
  });
}

const char* warning_name(int i) {
  switch (i) {
    case mjWARN_INERTIA: return "(near) singular inertia matrix";
    case mjWARN_CONTACTFULL: return "too many contacts (nconmax)";
    case mjWARN_CNSTRFULL: return "too many constraints (njmax)";
    case mjWARN_VGEOMFULL: return "too many visual geoms";
    case mjWARN_BADQPOS: return "bad number in qpos";
    case mjWARN_BADQVEL: return "bad number in qvel";
    case mjWARN_BADQACC: return "bad number in qacc";
    case mjWARN_BADCTRL: return "bad number in ctrl";
    default: return "unknown warning";
  }
}

}  // namespace

ModelPtr load_model(const std::string& xml, const std::string& origin) {
  install_handlers();
  static constexpr char kName[] = "contact2d_model.xml";
  auto vfs = std::make_unique<mjVFS>();  // ~2 MB: never on the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0) {
    throw InputError(origin + ": MuJoCo cannot load the model: virtual file system refused it");
  }
  const int index = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML(kName, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!model) throw InputError(origin + ": MuJoCo cannot load the model: " + trim(error));
  ModelPtr owned(model);
  if (error[0] != '\0')
    throw InputError(origin + ": MuJoCo warns while loading the model: " + trim(error));
  return owned;
}

DataPtr make_data(const mjModel* model) {
  mjData* data = mj_makeData(model);
  if (!data) throw MujocoError("mj_makeData failed");
  return DataPtr(data);
}

WarningCapture::WarningCapture(std::vector<std::string>& messages) : previous_(t_sink) {
  install_handlers();
  t_sink = &messages;
}

WarningCapture::~WarningCapture() { t_sink = previous_; }

std::vector<std::string> warning_counters(const mjData* data) {
  std::vector<std::string> out;
  for (int i = 0; i < mjNWARNING; ++i) {
    const int n = data->warning[i].number;
    if (n > 0) out.push_back(std::string(warning_name(i)) + " (" + std::to_string(n) + " times)");
  }
  return out;
}

std::string printable_name(const std::string& name) {
  std::string out;
  for (const char ch : name) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte < 0x20 || byte == 0x7f) {
      out += format_text("\\x%02x", byte);
    } else {
      if (ch == '\\') out += '\\';
      out += ch;
    }
  }
  return out;
}

std::string name_of(const mjModel* m, int type, int id, const char* what) {
  const char* name = mj_id2name(m, type, id);
  if (name && name[0]) return printable_name(name);
  if (type == mjOBJ_BODY && id == 0) return "world";
  return std::string(what) + " #" + std::to_string(id);
}

std::vector<double> normal_jacobian(const mjModel* m, const mjData* d, int body1, int body2,
                                    const std::array<double, 3>& pos,
                                    const std::array<double, 3>& normal) {
  const size_t nv = static_cast<size_t>(m->nv);
  std::vector<double> j1(3 * nv), j2(3 * nv), jr(3 * nv), row(nv, 0.0);
  mj_jac(m, d, j1.data(), jr.data(), pos.data(), body1);
  mj_jac(m, d, j2.data(), jr.data(), pos.data(), body2);
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < nv; ++i) row[i] += normal[k] * (j2[k * nv + i] - j1[k * nv + i]);
  return row;
}

double inverse_mass(const mjModel* m, mjData* d, const std::vector<double>& row) {
  std::vector<double> x(row.size());
  mj_solveM(m, d, x.data(), row.data(), 1);
  double a = 0.0;
  for (size_t i = 0; i < row.size(); ++i) a += row[i] * x[i];
  return a;
}

}  // namespace contact2d::mujoco
