// `inspect --engines mujoco,mujoco3`: one model read by MuJoCo 2.2.2 and by
// 3.14, compared body by body — mass, principal inertia, Â
// (body_invweight0), contacts and loads — and tree by tree (weight and the
// load its contacts carry), each difference with the cause it measures:
//
//   mass and inertia: a mesh geom whose mass MuJoCo infers from the mesh.
//   2.2.2 weighs it by the volume of its equivalent inertia box (the box
//   with the mesh's inertia per unit mass, 8·bx·by·bz; user_objects.cc's
//   GetVolume without exactmeshinertia), 3.1 and later by the mesh's own
//   volume (its default inertia="legacy": Σ|c·n|·a/3 over the faces about
//   the mesh's centroid). Both volumes are measured here on 2.2.2's compiled
//   mesh (mesh_vert is centred on that centroid), so the difference they
//   predict, ρ·Σ(V_mesh − V_box), is checked against the measured one: the
//   density ρ it implies is printed (MuJoCo's default is 1000 kg/m³), and
//   the cause is named only when a mesh geom can carry it. An explicit
//   geom mass (or an <inertial>) gives both versions the same mass and
//   inertia: the box and the mesh have the same inertia per unit mass.
//   Â: follows from the mass and inertia of the body's tree, or 3.0's
//   slide-only invweight (a body on slide joints only: 1/m in 3.x);
//   contacts: their margin and gap (2.2.2 takes the larger geom's, 3.x adds
//   the two), their loads: the tree's weight, or a state not at rest.
// Differences below kVersionTolerance (relative) count as agreement.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mujoco/inspect.hpp"
#include "mujoco/model.hpp"
#include "mujoco/model_state.hpp"

namespace contact2d::mujoco {

inline constexpr double kVersionTolerance = 1e-4;

// A mesh geom of 2.2.2's compiled model and the two volumes it may be
// weighed by (m³): 2.2.2's equivalent inertia box and 3.x's legacy volume.
struct MeshGeom {
  int geom = -1, body = -1;
  std::string geom_name, mesh_name;
  double box_volume = 0.0, mesh_volume = 0.0;
};

std::vector<MeshGeom> mesh_geoms(const mjModel* m);

struct BodyVersions {
  std::string name, tree;
  std::array<double, 2> mass{};
  std::array<std::array<double, 3>, 2> inertia{};  // principal, sorted
  std::array<double, 2> invweight{};               // translational
  std::array<int, 2> contacts{};
  std::array<double, 2> load{};  // its contacts' loads summed, N
  double mass_change = 0.0, inertia_change = 0.0,
         invweight_change = 0.0;  // relative, 3.x/2.2.2 − 1
  double load_change = 0.0;
  std::string cause;  // what explains its differences (empty: it agrees)
};

struct TreeVersions {
  std::string root;
  std::array<double, 2> weight{}, support{};
  std::array<int, 2> contacts{};
};

struct ContactParameterChange {  // a geom pair whose margin or gap differs
  std::string geom1, geom2;
  std::array<double, 2> margin{}, gap{};
};

struct VersionComparison {
  std::array<InspectReport, 2> reports;  // 2.2.2's, 3.x's
  std::vector<BodyVersions> bodies;      // every moving body
  std::vector<TreeVersions> trees;
  std::vector<ContactParameterChange> margins;
  std::vector<MeshGeom> meshes;
  // The mesh cause, when it explains the masses: the density the measured
  // mass differences imply for the mesh geoms (kg/m³; NaN: no mesh cause).
  double implied_density = 0.0;
  std::vector<std::string> causes;  // one sentence per cause found
};

// Both states must be of the same model (same bodies and geoms).
VersionComparison compare_versions(const ModelState& v2, InspectReport r2, const ModelState& v3,
                                   InspectReport r3, std::vector<MeshGeom> meshes);

std::string format_versions_text(const VersionComparison& c);
std::string format_versions_json(const VersionComparison& c);

}  // namespace contact2d::mujoco
