// The files MuJoCo 2.2.2's mj_loadXML opens besides the model itself, found
// before it opens them. 2.2.2 reads a model's <include>s, meshes, skins,
// height fields and textures from the disk itself, with fopen and
// ifstream: a FIFO among them blocks the load for ever, a device reads
// without end. (MuJoCo 3.14 reads copies that src/mujoco3/driver.mjs stages
// after the same check.)
//
// Resolved as 2.2.2 resolves them (src/xml/xml.cc, src/user/user_util.cc
// mjuu_makefullname, src/user/user_mesh.cc and user_objects.cc at tag
// 2.2.2), with D the model's folder as its path names it (the text up to
// the last '/' or '\', "" for none):
// - <include file=F>: D + F, always — an included file's own includes too,
//   and an absolute F as well (2.2.2 prefixes it); the included file's
//   root's children take the <include>'s place;
// - <mesh>, <skin>, <hfield> file=F: mjuu_makefullname(D, meshdir, F), a
//   <texture>'s file and its six cube faces (fileright … fileback) the
//   same with texturedir: F when F is absolute (starts with '/' or '\', or
//   holds ":/" or ":\"), meshdir + F when meshdir is, else D + meshdir + F;
//   meshdir and texturedir are the last <compiler>'s among the root's
//   children (after the includes) that sets them, with a '/' appended when
//   they do not end in one; <compiler strippath="true"> first cuts F to its
//   name after the last '/' or '\';
// - a URDF model (root <robot>): each <mesh filename=F> the same, with
//   strippath true unless its <mujoco><compiler> says otherwise.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace contact2d::mujoco {

// The most a model's file other than the MJCF is read at (a mesh, a
// texture): what MuJoCo 3's staging copies of a whole model
// (src/mujoco3/driver.mjs, kStageBytes).
constexpr std::size_t kMaxModelAssetBytes = 256u << 20;  // 256 MiB

// One file the model names, resolved as 2.2.2 opens it.
struct ModelFile {
  std::string path;  // as 2.2.2 passes it to fopen (relative to the working folder)
  std::string what;  // "an <include> of the model", "the mesh file the model names", …
};

// Every file 2.2.2 would open for the model at `model_path`, in the order it
// opens them (includes first). It stops at the first include it cannot
// follow (missing, unreadable XML, included twice): MuJoCo's own error
// comes there. Throws InputError when an include is not a regular file
// within the cap (check_input_file): it cannot be read to go on.
std::vector<ModelFile> files_read_by_2_2_2(const std::string& model_path);

// Each of those files that exists passed to check_input_file: an InputError
// "PATH: cannot read WHAT (a pipe or socket, …)" for a FIFO, a device, a
// folder or one past the cap (kMaxInputBytes for an include, which is MJCF,
// kMaxModelAssetBytes for the others). A missing file is left to MuJoCo's
// own message.
void check_files_read_by_2_2_2(const std::string& model_path);

}  // namespace contact2d::mujoco
