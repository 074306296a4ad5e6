// solref --apply (mujoco/solref_apply.hpp).
#include "mujoco/solref_apply.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <initializer_list>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d::mujoco {
namespace {

namespace fs = std::filesystem;

std::string apply_numbers(std::initializer_list<double> values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + format_exact(v);
  return out;
}

bool is_named(const tinyxml2::XMLElement* e, const char* element, const std::string& name) {
  const char* n = e->Attribute("name");
  return std::string(e->Name()) == element && n && name == n;
}

tinyxml2::XMLElement* find_named(tinyxml2::XMLElement* parent, const char* element,
                                 const std::string& name) {
  for (tinyxml2::XMLElement* e = parent->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (is_named(e, element, name)) return e;
    if (tinyxml2::XMLElement* found = find_named(e, element, name)) return found;
  }
  return nullptr;
}

// Every element named `element` below `parent`, in document order.
void collect(tinyxml2::XMLElement* parent, const char* element,
             std::vector<tinyxml2::XMLElement*>& out) {
  for (tinyxml2::XMLElement* e = parent->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (std::string(e->Name()) == element) out.push_back(e);
    collect(e, element, out);
  }
}

// The unnamed geom `g` in the model's own file: the index_in_body-th <geom>
// child of its body (MuJoCo numbers a body's geoms in the order they are
// written), or null when the body's geoms are not all written there.
tinyxml2::XMLElement* find_geom(tinyxml2::XMLElement* root, const GeomRef& g) {
  tinyxml2::XMLElement* body =
      g.body == "world" ? root->FirstChildElement("worldbody") : find_named(root, "body", g.body);
  if (!body) return nullptr;
  int index = 0;
  for (tinyxml2::XMLElement* e = body->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string name = e->Name();
    if (name == "include" || name == "frame" || name == "replicate") return nullptr;
    if (name == "geom" && index++ == g.index_in_body) return e;
  }
  return nullptr;
}

// The model's <pair> of these two geoms, written in its own file.
tinyxml2::XMLElement* find_pair(tinyxml2::XMLElement* root, const std::string& a,
                                const std::string& b) {
  std::vector<tinyxml2::XMLElement*> pairs;
  collect(root, "pair", pairs);
  for (tinyxml2::XMLElement* p : pairs) {
    const char* g1 = p->Attribute("geom1");
    const char* g2 = p->Attribute("geom2");
    if (g1 && g2 && ((a == g1 && b == g2) || (a == g2 && b == g1))) return p;
  }
  return nullptr;
}

const char* const kFileAttributes[] = {"file",     "fileright", "fileleft", "fileup",
                                       "filedown", "filefront", "fileback"};

// A file the model names relative to its folder, resolved there.
bool relative(const char* path) { return path && *path && !fs::path(path).is_absolute(); }

// The model written to another folder than its own: its relative file
// references made absolute, so that it loads there as it did. MuJoCo
// resolves <include file> against the model's folder; a mesh's, skin's or
// height field's file against <compiler meshdir>, a texture's against
// texturedir (assetdir, 3.x: both), each itself relative to the model's
// folder, or against the folder when unset. A folder set is made absolute and
// the files under it stay as they are. An <include>d file that names files
// relative to the model's folder cannot be rewritten here: InputError.
void rebase(tinyxml2::XMLElement* root, const fs::path& model_dir, const std::string& out) {
  std::vector<tinyxml2::XMLElement*> compilers, includes;
  collect(root, "compiler", compilers);
  bool meshdir = false, texturedir = false;
  for (tinyxml2::XMLElement* c : compilers) {
    for (const char* dir : {"meshdir", "texturedir", "assetdir"}) {
      const char* value = c->Attribute(dir);
      if (!value) continue;
      if (std::string(dir) != "texturedir") meshdir = true;
      if (std::string(dir) != "meshdir") texturedir = true;
      if (relative(value)) c->SetAttribute(dir, (model_dir / value).lexically_normal().c_str());
    }
  }
  std::vector<tinyxml2::XMLElement*> all;
  collect(root, "include", includes);
  for (const char* element : {"mesh", "skin", "hfield", "texture", "include", "model"})
    collect(root, element, all);
  for (tinyxml2::XMLElement* e : all) {
    const std::string name = e->Name();
    const bool under_dir = name == "texture" ? texturedir : name == "include" ? false : meshdir;
    if (under_dir) continue;
    for (const char* attribute : kFileAttributes) {
      const char* value = e->Attribute(attribute);
      if (relative(value))
        e->SetAttribute(attribute, (model_dir / value).lexically_normal().c_str());
    }
  }
  // An included file's own references resolve against the model's folder too.
  for (tinyxml2::XMLElement* include : includes) {
    const std::string file = include->Attribute("file") ? include->Attribute("file") : "";
    tinyxml2::XMLDocument doc;
    const std::string text = read_input_file(file, "--model's <include>");
    if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement())
      continue;  // MuJoCo says what is wrong with it when it loads the model
    std::vector<tinyxml2::XMLElement*> inner;
    for (const char* element :
         {"compiler", "mesh", "skin", "hfield", "texture", "include", "model"})
      collect(doc.RootElement(), element, inner);
    for (tinyxml2::XMLElement* e : inner)
      for (const char* attribute : {"file", "fileright", "fileleft", "fileup", "filedown",
                                    "filefront", "fileback", "meshdir", "texturedir", "assetdir"})
        if (relative(e->Attribute(attribute)))
          throw InputError("--apply " + out + ": " + file + " (an <include> of the model) names " +
                           e->Attribute(attribute) +
                           " relative to the model's folder: write the output in " +
                           model_dir.string());
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> geom_classes_in_file(
    const std::string& model, const std::vector<GeomRef>& geoms) {
  std::vector<std::pair<std::string, std::string>> out(geoms.size());
  tinyxml2::XMLDocument doc;
  const std::string text = read_input_file(model, "--model");
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement() ||
      std::string(doc.RootElement()->Name()) != "mujoco")
    return out;
  for (size_t i = 0; i < geoms.size(); ++i) {
    const GeomRef& g = geoms[i];
    const tinyxml2::XMLElement* e =
        g.named ? find_named(doc.RootElement(), "geom", g.name) : find_geom(doc.RootElement(), g);
    if (!e) continue;
    if (const char* own = e->Attribute("class")) {
      out[i] = {own, ""};
      continue;
    }
    for (const tinyxml2::XMLNode* up = e->Parent(); up && up->ToElement(); up = up->Parent()) {
      const tinyxml2::XMLElement* a = up->ToElement();
      if (const char* child = a->Attribute("childclass")) {
        const char* name = a->Attribute("name");
        out[i] = {child, "the childclass of " + std::string(a->Name()) +
                             (name ? " '" + std::string(name) + "'" : std::string())};
        break;
      }
    }
  }
  return out;
}

namespace {

// <option>: the mapping's cone and impratio; a model that ignores <pair>s
// (collision="dynamic") is refused.
void write_options(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* root, const MappingOutcome& o,
                   const std::string& out) {
  const SolverSettings& s = o.settings;
  for (tinyxml2::XMLElement* option = root->FirstChildElement("option"); option;
       option = option->NextSiblingElement("option")) {
    const char* collision = option->Attribute("collision");
    if (collision && std::string(collision) == "dynamic")
      throw InputError("--apply " + out +
                       ": the model's <option collision=\"dynamic\"> ignores "
                       "<pair>s; apply the default class snippet by hand");
  }
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
}

void write_pairs(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* root,
                 const std::vector<RestPair>& pairs, const MappingOutcome& o,
                 const std::string& model, const std::string& out) {
  const SolverSettings& s = o.settings;
  // One <pair> per geom pair the body rests on (solref_tool.hpp's
  // RestPair): only those contacts change, and only in solref and solimp
  // (with --mu also condim and friction). A pair the model has already is
  // edited in place (a second one would double its contacts).
  tinyxml2::XMLElement* contact = nullptr;
  for (const RestPair& p : pairs) {
    const std::string a = pair_name(p.geom1), b = pair_name(p.geom2);
    if (p.explicit_pair) {
      tinyxml2::XMLElement* existing = find_pair(root, a, b);
      if (!existing)
        throw InputError("--apply " + out + ": the <pair> of " + a + " and " + b + " is not in " +
                         model + " itself (an <include>d file?): apply the pair snippet by hand");
      existing->SetAttribute("solref", apply_numbers({s.solref[0], s.solref[1]}).c_str());
      existing->SetAttribute(
          "solimp",
          apply_numbers({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]}).c_str());
      if (o.condim > 0) {
        existing->SetAttribute("condim", p.condim);
        existing->SetAttribute(
            "friction", apply_numbers({p.friction[0], p.friction[1], p.friction[2], p.friction[3],
                                       p.friction[4]})
                            .c_str());
      }
      continue;
    }
    for (const GeomRef* g : {&p.geom1, &p.geom2}) {
      if (g->named) continue;
      tinyxml2::XMLElement* element = find_geom(root, *g);
      if (!element)
        throw InputError("--apply " + out + ": " + g->name + " (geom " +
                         std::to_string(g->index_in_body + 1) + " of body '" + g->body +
                         "') has no name and is not written in " + model +
                         " itself: name it, then apply again");
      element->SetAttribute("name", pair_name(*g).c_str());
    }
    if (!contact) {
      contact = doc.NewElement("contact");
      root->InsertEndChild(contact);
      contact->InsertNewComment(
          " contact2d solref --apply: the body's contacts at rest, condim, friction, margin and "
          "gap as MuJoCo mixed them ");
    }
    // The pair's attributes, parsed from the one text the snippet prints.
    tinyxml2::XMLDocument element_doc;
    const std::string pair_text =
        "<pair geom1=\"" + a + "\" geom2=\"" + b + "\"" + pair_attributes(p, s) + "/>";
    element_doc.Parse(pair_text.c_str());
    contact->InsertEndChild(element_doc.RootElement()->DeepClone(&doc));
  }
}

}  // namespace

Applied apply_solref(const SolrefReport& report, const MappingOutcome& o, const std::string& model,
                     const std::string& body, const std::string& out, const StateRequest& settle,
                     const StateReader& read) {
  const fs::path model_dir = fs::absolute(model).parent_path().lexically_normal();
  const fs::path out_path = fs::absolute(out).lexically_normal();
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
  const SolverSettings& s = o.settings;
  const SolrefInput& in = report.input;
  const std::vector<RestPair> pairs = rest_pairs(in, o);
  if (pairs.empty())
    throw InputError("--apply " + out + ": body '" + body + "' touches nothing after settling " +
                     format_number(settle.settle) +
                     " s, so there is no contact to apply the mapping to (a longer --settle, or "
                     "--key a keyframe where it rests)");
  write_options(doc, root, o, out);
  write_pairs(doc, root, pairs, o, model, out);
  // MuJoCo settles the written model from its temporary file, before it
  // takes the output's name: a model it refuses leaves no file. That file
  // sits beside the output (or in $TMPDIR for a FIFO or device): in another
  // folder than the model's, its references are rebased.
  AtomicFile file(out);
  if (fs::absolute(file.temp_path()).parent_path().lexically_normal() != model_dir)
    rebase(root, model_dir, out);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  std::fputs(printer.CStr(), file.get());
  if (std::fflush(file.get()) != 0)
    throw InputError("--apply " + out + ": cannot write " + file.temp_path());
  StateRequest request = settle;
  request.path = file.temp_path();
  request.option = "--apply";
  const ModelBody applied_body = read_model_body(read(request), out, body);
  file.commit();
  Applied applied;
  applied.path = out;
  applied.mapping = std::string(mapping_name(o.mapping));
  applied.settled = applied_body.settle_seconds;
  applied.at_rest = applied_body.at_rest;
  applied.pairs = static_cast<int>(pairs.size());
  for (const SettledContact& c : applied_body.contacts) {
    AppliedContact a;
    static_cast<SettledContact&>(a) = c;
    const std::string g1 = c.ref1.named ? c.ref1.name : pair_name(c.ref1);
    const std::string g2 = c.ref2.named ? c.ref2.name : pair_name(c.ref2);
    a.mapped = std::any_of(pairs.begin(), pairs.end(), [&](const RestPair& p) {
      const std::string p1 = pair_name(p.geom1), p2 = pair_name(p.geom2);
      return (p1 == g1 && p2 == g2) || (p1 == g2 && p2 == g1);
    });
    // The contact's Â (both bodies'), with the cone's φ as the report has it.
    a.predicted = static_penetration(s.solimp, o.K,
                                     c.inv_weight * o.normal_weight / report.inv_weight, a.load);
    applied.contacts.push_back(a);
  }
  return applied;
}

}  // namespace contact2d::mujoco
