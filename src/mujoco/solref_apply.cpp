// solref --apply (mujoco/solref_apply.hpp).
#include "mujoco/solref_apply.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d::mujoco {
namespace {

namespace fs = std::filesystem;

std::string numbers(std::initializer_list<double> values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + format_exact(v);
  return out;
}

tinyxml2::XMLElement* find_body(tinyxml2::XMLElement* parent, const std::string& name) {
  for (tinyxml2::XMLElement* e = parent->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const char* n = e->Attribute("name");
    if (std::string(e->Name()) == "body" && n && name == n) return e;
    if (tinyxml2::XMLElement* found = find_body(e, name)) return found;
  }
  return nullptr;
}

}  // namespace

Applied apply_solref(const SolrefReport& report, const MappingOutcome& o, const std::string& model,
                     const std::string& body, const std::string& out, const StateRequest& settle,
                     const StateReader& read) {
  const fs::path model_dir = fs::absolute(model).parent_path().lexically_normal();
  const fs::path out_path = fs::absolute(out).lexically_normal();
  if (out_path.parent_path() != model_dir)
    throw InputError("--apply " + out + ": write it in the model's folder " + model_dir.string() +
                     " (the model's includes, meshes and textures resolve from there)");
  std::error_code same_error;
  if (out_path == fs::absolute(model).lexically_normal() ||
      fs::equivalent(out_path, fs::absolute(model), same_error))
    throw InputError("--apply " + out + ": is the model itself; name a new file");
  check_output_file("--apply", out);

  tinyxml2::XMLDocument doc;
  const std::string text = read_input_file(model, "--model");
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
    throw InputError("--model " + model + ": not XML (" + std::string(doc.ErrorStr()) + ")");
  tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "mujoco")
    throw InputError("--model " + model + ": its root element is not <mujoco>");
  tinyxml2::XMLElement* b = find_body(root, body);
  if (!b)
    throw InputError("--apply " + out + ": body '" + body + "' is not in " + model +
                     " itself (an <include>d file?): apply the snippet by hand");
  const SolverSettings& s = o.settings;
  const SolrefInput& in = report.input;
  if (s.elliptic || (o.condim > 1 && s.impratio != 1.0)) {
    tinyxml2::XMLElement* option = root->FirstChildElement("option");
    if (!option) {
      option = doc.NewElement("option");
      root->InsertFirstChild(option);
    }
    if (s.elliptic) option->SetAttribute("cone", "elliptic");
    if (o.condim > 1 && s.impratio != 1.0)
      option->SetAttribute("impratio", format_exact(s.impratio).c_str());
  }
  for (tinyxml2::XMLElement* g = b->FirstChildElement("geom"); g;
       g = g->NextSiblingElement("geom")) {
    g->SetAttribute("solref", numbers({s.solref[0], s.solref[1]}).c_str());
    g->SetAttribute(
        "solimp",
        numbers({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]}).c_str());
    g->SetAttribute("priority", "1");
    if (o.condim > 0) g->SetAttribute("condim", o.condim);
    if (o.condim > 1) g->SetAttribute("friction", numbers({in.mu, 0.0, in.mu_roll}).c_str());
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  {
    AtomicFile file(out);
    std::fputs(printer.CStr(), file.get());
    file.commit();
  }

  StateRequest request = settle;
  request.path = out;
  request.option = "--apply";
  const ModelBody applied_body = read_model_body(read(request), out, body);
  Applied applied;
  applied.path = out;
  applied.mapping = std::string(mapping_name(o.mapping));
  applied.settled = applied_body.settle_seconds;
  applied.at_rest = applied_body.at_rest;
  for (const SettledContact& c : applied_body.contacts) {
    AppliedContact a;
    static_cast<SettledContact&>(a) = c;
    // The contact's Â (both bodies'), with the cone's φ as the report has it.
    a.predicted = static_penetration(s.solimp, o.K,
                                     c.inv_weight * o.normal_weight / report.inv_weight, a.load);
    applied.contacts.push_back(a);
  }
  return applied;
}

}  // namespace contact2d::mujoco
