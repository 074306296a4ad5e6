// The files MuJoCo 2.2.2 opens for a model (mujoco/model_files.hpp).
#include "mujoco/model_files.hpp"

#include <strings.h>
#include <sys/stat.h>
#include <tinyxml2.h>

#include "io/read_file.hpp"

namespace contact2d::mujoco {
namespace {

bool named(const tinyxml2::XMLElement* e, const char* name) {
  return ::strcasecmp(e->Value(), name) == 0;
}

std::string attribute(const tinyxml2::XMLElement* e, const char* name) {
  const char* value = e->Attribute(name);
  return value ? value : "";
}

// mjuu_getfiledir: the path up to and with its last '/' or '\', "" for none.
std::string file_dir(const std::string& path) {
  const size_t last = path.find_last_of("/\\");
  return last == std::string::npos ? "" : path.substr(0, last + 1);
}

// mjuu_isabspath.
bool absolute_2_2_2(const std::string& path) {
  if (path.empty()) return false;
  if (path[0] == '/' || path[0] == '\\') return true;
  return path.find(":/") != std::string::npos || path.find(":\\") != std::string::npos;
}

// mjuu_makefullname, with the '/' mjCModel::Compile appends to the folder.
std::string full_name(const std::string& dir, std::string folder, std::string file,
                      bool strip_path) {
  if (strip_path) {
    const size_t last = file.find_last_of("/\\");
    if (last != std::string::npos) file = file.substr(last + 1);
  }
  if (!folder.empty() && folder.back() != '/' && folder.back() != '\\') folder += '/';
  if (absolute_2_2_2(file)) return file;
  if (absolute_2_2_2(folder)) return folder + file;
  return dir + folder + file;
}

bool exists(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}

// A file an asset element names, before meshdir/texturedir are known.
struct Named {
  std::string file, what;
  bool texture = false;
};

struct Walk {
  std::string dir;                    // the model's folder, as 2.2.2 prefixes it
  std::vector<std::string> included;  // the model and each include, as 2.2.2 compares them
  std::string meshdir, texturedir;
  bool strip_path = false;
  std::vector<ModelFile> includes;
  std::vector<Named> assets;
};

void read_compiler(const tinyxml2::XMLElement* c, Walk& w) {
  if (c->Attribute("meshdir")) w.meshdir = attribute(c, "meshdir");
  if (c->Attribute("texturedir")) w.texturedir = attribute(c, "texturedir");
  if (c->Attribute("strippath")) w.strip_path = attribute(c, "strippath") == "true";
}

void note_asset(const tinyxml2::XMLElement* e, Walk& w) {
  const std::string name = e->Value();
  const char* what = name == "mesh"      ? "the mesh file the model names"
                     : name == "skin"    ? "the skin file the model names"
                     : name == "hfield"  ? "the height field file the model names"
                     : name == "texture" ? "the texture file the model names"
                                         : nullptr;
  if (!what) return;
  const bool texture = name == "texture";
  for (const char* a :
       {"file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback"}) {
    if (!texture && std::string(a) != "file") break;
    if (const char* value = e->Attribute(a); value && *value)
      w.assets.push_back({value, what, texture});
  }
}

bool walk_list(const tinyxml2::XMLElement* first, bool at_root, Walk& w);

// mjIncludeXML: the include's file read and its root's children walked in
// its place; false where 2.2.2 stops with an error of its own.
bool walk_include(const tinyxml2::XMLElement* e, bool at_root, Walk& w) {
  if (!e->NoChildren() || !e->Attribute("file")) return false;
  const std::string path = w.dir + attribute(e, "file");
  for (const std::string& seen : w.included)
    if (::strcasecmp(seen.c_str(), path.c_str()) == 0) return false;
  if (!exists(path)) return false;
  const char* what = "an <include> of the model";
  check_input_file(path, what);
  w.includes.push_back({path, what});
  w.included.push_back(path);
  const std::string text = read_input_file(path, what);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement() ||
      !doc.RootElement()->FirstChildElement())
    return false;
  return walk_list(doc.RootElement()->FirstChildElement(), at_root, w);
}

// A list of sibling elements (the root's children when at_root).
bool walk_list(const tinyxml2::XMLElement* first, bool at_root, Walk& w) {
  for (const tinyxml2::XMLElement* e = first; e; e = e->NextSiblingElement()) {
    if (named(e, "include")) {
      if (!walk_include(e, at_root, w)) return false;
      continue;
    }
    if (at_root && std::string(e->Value()) == "compiler") read_compiler(e, w);
    note_asset(e, w);
    if (!walk_list(e->FirstChildElement(), false, w)) return false;
  }
  return true;
}

// A URDF model's meshes (mjXURDF::Parse): <mesh filename>, strippath true
// unless the <mujoco><compiler> sets it.
void walk_urdf(const tinyxml2::XMLElement* root, Walk& w) {
  w.strip_path = true;
  if (const tinyxml2::XMLElement* mjc = root->FirstChildElement("mujoco"))
    if (const tinyxml2::XMLElement* c = mjc->FirstChildElement("compiler")) read_compiler(c, w);
  std::vector<const tinyxml2::XMLElement*> stack{root};
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    if (std::string(e->Value()) == "mesh" && e->Attribute("filename"))
      w.assets.push_back({attribute(e, "filename"), "the mesh file the model names", false});
    for (const tinyxml2::XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement())
      stack.push_back(c);
  }
}

}  // namespace

std::vector<ModelFile> files_read_by_2_2_2(const std::string& model_path) {
  Walk w;
  w.dir = file_dir(model_path);
  w.included.push_back(model_path);
  const std::string text = read_input_file(model_path, "the MJCF file");
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement())
    return {};
  const tinyxml2::XMLElement* root = doc.RootElement();
  bool complete = true;
  if (named(root, "mujoco"))
    complete = walk_list(root->FirstChildElement(), true, w);
  else if (named(root, "robot"))
    walk_urdf(root, w);
  std::vector<ModelFile> out = std::move(w.includes);
  if (!complete) return out;  // MuJoCo stops at that include, before any asset
  for (const Named& a : w.assets)
    out.push_back(
        {full_name(w.dir, a.texture ? w.texturedir : w.meshdir, a.file, w.strip_path), a.what});
  return out;
}

void check_files_read_by_2_2_2(const std::string& model_path) {
  for (const ModelFile& f : files_read_by_2_2_2(model_path))
    if (exists(f.path))
      check_input_file(f.path, f.what, kMaxModelAssetBytes,
                       "larger than " + std::to_string(kMaxModelAssetBytes >> 20) +
                           " MiB, the most MuJoCo 3 reads of a whole model");
}

}  // namespace contact2d::mujoco
