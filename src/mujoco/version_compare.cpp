// `inspect --engines mujoco,mujoco3` (mujoco/version_compare.hpp).
#include "mujoco/version_compare.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "core/format.hpp"
#include "io/json.hpp"

namespace contact2d::mujoco {
namespace {

constexpr double kNoNumber = std::numeric_limits<double>::quiet_NaN();

double change(double v2, double v3) {
  if (v2 == v3) return 0.0;
  return v2 != 0.0 ? v3 / v2 - 1.0 : INFINITY;
}

// The relative change of the largest-differing principal moment (both sorted).
double inertia_change(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  double out = 0.0;
  for (size_t i = 0; i < 3; ++i) {
    const double c = change(a[i], b[i]);
    if (std::abs(c) > std::abs(out)) out = c;
  }
  return out;
}

std::string percent(double relative) {
  if (std::abs(relative) <= kVersionTolerance) return "same";
  return (relative > 0.0 ? "+" : "") + format_number(100.0 * relative, 4) + " %";
}

std::array<double, 3> principal(const ModelState& s, size_t b) {
  std::array<double, 3> out = {s.body_inertia[3 * b], s.body_inertia[3 * b + 1],
                               s.body_inertia[3 * b + 2]};
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<MeshGeom> mesh_geoms(const mjModel* m) {
  std::vector<MeshGeom> out;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_MESH || m->geom_dataid[g] < 0) continue;
    const int mesh = m->geom_dataid[g];
    const float* vert = m->mesh_vert + 3 * static_cast<std::ptrdiff_t>(m->mesh_vertadr[mesh]);
    const int* face = m->mesh_face + 3 * static_cast<std::ptrdiff_t>(m->mesh_faceadr[mesh]);
    // 2.2.2 compiles a mesh centred on its (legacy) centroid: every face's
    // pyramid to the origin, its volume taken positive, and the second
    // moments of those pyramids (a tetrahedron's, about a vertex at the origin).
    double volume = 0.0;
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (int f = 0; f < m->mesh_facenum[mesh]; ++f) {
      Eigen::Vector3d p[3];
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          p[k](j) = vert[3 * static_cast<std::ptrdiff_t>(face[3 * f + k]) + j];
      const double v = std::abs(p[0].dot(p[1].cross(p[2]))) / 6.0;
      volume += v;
      const Eigen::Vector3d sum = p[0] + p[1] + p[2];
      Eigen::Matrix3d outer = sum * sum.transpose();
      for (const auto& q : p) outer += q * q.transpose();
      second += v / 20.0 * outer;
    }
    MeshGeom mg;
    mg.geom = g;
    mg.body = m->geom_bodyid[g];
    mg.geom_name = name_of(m, mjOBJ_GEOM, g, "geom");
    mg.mesh_name = name_of(m, mjOBJ_MESH, mesh, "mesh");
    mg.mesh_volume = volume;
    // The inertia per unit density, its principal moments, and the box
    // with the same moments per unit mass: 2.2.2's volume.
    const Eigen::Matrix3d inertia = second.trace() * Eigen::Matrix3d::Identity() - second;
    const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
    if (volume > 0.0) {
      double box = 8.0;
      for (int i = 0; i < 3; ++i) {
        const double sq = 6.0 * (e.sum() - 2.0 * e(i)) / volume;
        box *= std::sqrt(std::max(0.0, sq)) / 2.0;
      }
      mg.box_volume = box;
    }
    out.push_back(mg);
  }
  return out;
}

namespace {

// The mesh cause (the header): the bodies' mass differences against their
// mesh geoms' two volumes; sets c.implied_density and its sentence. Returns
// each mesh-carrying body's Σ (V_mesh − V_box).
std::map<int, double> mesh_cause(const ModelState& v2, const ModelState& v3, VersionComparison& c) {
  // The mesh cause: the mass differences of the bodies with mesh geoms
  // against the volumes' difference.
  const size_t nbody = std::min(v2.body_mass.size(), v3.body_mass.size());
  double dm = 0.0, dv = 0.0, unexplained = 0.0;
  std::map<int, double> mesh_dv;  // body → Σ (V_mesh − V_box)
  for (const MeshGeom& mg : c.meshes) mesh_dv[mg.body] += mg.mesh_volume - mg.box_volume;
  for (size_t b = 1; b < nbody; ++b) {
    const double d = v3.body_mass[b] - v2.body_mass[b];
    if (std::abs(d) <= kVersionTolerance * std::max(v2.body_mass[b], 1e-12)) continue;
    if (auto it = mesh_dv.find(static_cast<int>(b)); it != mesh_dv.end() && it->second != 0.0) {
      dm += d;
      dv += it->second;
    } else {
      unexplained += std::abs(d);
    }
  }
  c.implied_density = dv != 0.0 ? dm / dv : kNoNumber;
  const bool found = std::isfinite(c.implied_density) && c.implied_density > 0.0;
  if (found) {
    std::string geoms;
    for (const MeshGeom& mg : c.meshes)
      if (std::abs(mg.mesh_volume - mg.box_volume) > 0.0)
        geoms += (geoms.empty() ? "" : ", ") + mg.geom_name + " (mesh " + mg.mesh_name + ", body " +
                 v2.body_names[static_cast<size_t>(mg.body)] + ": " + format_number(mg.box_volume) +
                 " m³ as 2.2.2's box, " + format_number(mg.mesh_volume) + " m³ as the mesh)";
    c.causes.push_back(
        "3.1's mesh volume: MuJoCo infers a mesh geom's mass from a volume, 2.2.2 the volume of "
        "the box with the mesh's inertia per unit mass, 3.1 and later the mesh's own (legacy) "
        "volume; measured on 2.2.2's mesh: " +
        geoms + "; the measured mass difference is that volume difference at " +
        format_number(c.implied_density) + " kg/m³" +
        (std::abs(c.implied_density / 1000.0 - 1.0) < 1e-3 ? " (MuJoCo's default density)"
                                                           : " (the geoms' density if it "
                                                             "explains them)") +
        "; the body's inertia, Â, its contacts' A, k and c and its load follow. Give the mesh "
        "geom an explicit mass (or the body an <inertial>) and both versions "
        "agree: the box has the mesh's inertia per unit mass");
  }
  if (unexplained > 0.0)
    c.causes.push_back("masses that differ on bodies with no mesh geom (" +
                       format_number(unexplained) + " kg): no version change contact2d knows");
  return mesh_dv;
}

}  // namespace

VersionComparison compare_versions(const ModelState& v2, InspectReport r2, const ModelState& v3,
                                   InspectReport r3, std::vector<MeshGeom> meshes) {
  VersionComparison c;
  c.meshes = std::move(meshes);
  const std::array<const ModelState*, 2> s = {&v2, &v3};
  const size_t nbody = std::min(v2.body_mass.size(), v3.body_mass.size());
  std::vector<size_t> root(nbody, 0);
  for (size_t b = 1; b < nbody; ++b) {
    const auto parent = static_cast<size_t>(v2.body_parent[b]);
    root[b] = parent == 0 ? b : root[parent];
  }
  // Per body.
  std::map<std::string, size_t> index;
  for (size_t b = 1; b < nbody; ++b) {
    if (v2.body_weld[root[b]] == 0) continue;
    BodyVersions row;
    row.name = v2.body_names[b];
    row.tree = v2.body_names[root[b]];
    for (size_t v = 0; v < 2; ++v) {
      row.mass[v] = s[v]->body_mass[b];
      row.inertia[v] = principal(*s[v], b);
      row.invweight[v] = s[v]->body_invweight0[2 * b];
    }
    row.mass_change = change(row.mass[0], row.mass[1]);
    row.inertia_change = inertia_change(row.inertia[0], row.inertia[1]);
    row.invweight_change = change(row.invweight[0], row.invweight[1]);
    index[row.name] = c.bodies.size();
    c.bodies.push_back(row);
  }
  for (size_t v = 0; v < 2; ++v)
    for (const BodySummary& sum : (v == 0 ? r2 : r3).bodies)
      if (auto it = index.find(sum.name); it != index.end()) {
        c.bodies[it->second].contacts[v] = sum.contacts;
        c.bodies[it->second].load[v] = sum.load;
      }
  for (BodyVersions& b : c.bodies) b.load_change = change(b.load[0], b.load[1]);
  // Per tree.
  std::map<std::string, size_t> tree_index;
  for (size_t v = 0; v < 2; ++v)
    for (const TreeLoad& t : (v == 0 ? r2 : r3).trees) {
      auto [it, fresh] = tree_index.emplace(t.root, c.trees.size());
      if (fresh) c.trees.push_back(TreeVersions{t.root, {}, {}, {}});
      TreeVersions& tv = c.trees[it->second];
      tv.weight[v] = t.weight;
      tv.support[v] = t.support;
      tv.contacts[v] = t.contacts;
    }
  const std::map<int, double> mesh_dv = mesh_cause(v2, v3, c);  // body → Σ (V_mesh − V_box)
  const bool mesh_cause_found = std::isfinite(c.implied_density) && c.implied_density > 0.0;
  // Each body's cause.
  std::map<std::string, bool> tree_changed;
  for (const BodyVersions& b : c.bodies)
    if (std::abs(b.mass_change) > kVersionTolerance ||
        std::abs(b.inertia_change) > kVersionTolerance)
      tree_changed[b.tree] = true;
  const bool both_rest = r2.at_rest && r3.at_rest;
  for (BodyVersions& b : c.bodies) {
    std::vector<std::string> why;
    const size_t id = static_cast<size_t>(
        std::find(v2.body_names.begin(), v2.body_names.end(), b.name) - v2.body_names.begin());
    const bool mass = std::abs(b.mass_change) > kVersionTolerance ||
                      std::abs(b.inertia_change) > kVersionTolerance;
    if (mass)
      why.push_back(mesh_cause_found && mesh_dv.count(static_cast<int>(id)) != 0
                        ? "mass: 3.1's mesh volume"
                        : "mass: not a known version change");
    if (std::abs(b.invweight_change) > kVersionTolerance) {
      const std::string& joints = v2.body_joints[id];
      const bool slides = !joints.empty() && joints.find("hinge") == std::string::npos &&
                          joints.find("ball") == std::string::npos &&
                          joints.find("free") == std::string::npos;
      why.push_back(tree_changed[b.tree] ? "Â: its tree's mass (" + b.tree + ")"
                    : slides             ? "Â: 3.0's slide-only invweight (1/m)"
                                         : "Â: not a known version change");
    }
    if (b.contacts[0] != b.contacts[1] ||
        std::abs(b.load_change) > std::max(kVersionTolerance, 1e-3)) {
      if (tree_changed[b.tree])
        why.push_back("load: its tree's weight");
      else if (!both_rest)
        why.push_back("load: not at rest on " + std::string(r2.at_rest ? "3.x" : "2.2.2") +
                      " (loads at an instant)");
      else
        why.push_back("load: a different resting state (contacts " + std::to_string(b.contacts[0]) +
                      " and " + std::to_string(b.contacts[1]) + ")");
    }
    for (size_t i = 0; i < why.size(); ++i) b.cause += (i ? "; " : "") + why[i];
  }
  // Margin and gap per geom pair (the first contact of each).
  std::map<std::pair<int, int>, ContactParameterChange> pairs;
  std::map<std::pair<int, int>, std::array<bool, 2>> seen;
  for (size_t v = 0; v < 2; ++v)
    for (const StateContact& con : s[v]->contacts) {
      const std::pair<int, int> key = {con.geom1, con.geom2};
      auto& flags = seen[key];
      if (flags[v]) continue;
      flags[v] = true;
      ContactParameterChange& p = pairs[key];
      p.geom1 = s[v]->geom_names[static_cast<size_t>(con.geom1)];
      p.geom2 = s[v]->geom_names[static_cast<size_t>(con.geom2)];
      p.margin[v] = con.margin;
      p.gap[v] = con.gap;
    }
  for (const auto& [key, p] : pairs)
    if (seen[key][0] && seen[key][1] && (p.margin[0] != p.margin[1] || p.gap[0] != p.gap[1]))
      c.margins.push_back(p);
  if (!c.margins.empty())
    c.causes.push_back(std::to_string(c.margins.size()) +
                       " geom pairs in contact have another margin or gap: 2.2.2 takes the larger "
                       "geom's, 3.x adds the two geoms' (a <pair> keeps its own)");
  if (!both_rest && (!r2.contacts.empty() || !r3.contacts.empty()))
    c.causes.push_back(std::string("the state is not at rest on ") +
                       (!r2.at_rest && !r3.at_rest ? "either version"
                        : r2.at_rest               ? "3.x"
                                                   : "2.2.2") +
                       ": its loads are forces at an instant, and two versions' instants differ");
  c.reports = {std::move(r2), std::move(r3)};
  return c;
}

std::string format_versions_text(const VersionComparison& c) {
  const InspectReport& a = c.reports[0];
  const InspectReport& b = c.reports[1];
  std::ostringstream o;
  o << "model " << a.path << " on MuJoCo " << a.version << " and " << b.version << ", at "
    << (a.key.empty() ? "qpos0" : "keyframe " + a.key);
  if (a.settled > 0.0 || b.settled > 0.0)
    o << " settled " << format_number(a.settled) << " s (" << a.version << ": "
      << (a.at_rest ? "at rest" : "NOT at rest") << "; " << b.version << ": "
      << (b.at_rest ? "at rest" : "NOT at rest") << ")";
  o << "\n";
  size_t same = 0;
  std::vector<const BodyVersions*> differ;
  for (const BodyVersions& row : c.bodies) {
    if (row.cause.empty())
      ++same;
    else
      differ.push_back(&row);
  }
  double largest = 0.0;
  for (const BodyVersions& row : c.bodies)
    largest = std::max({largest, std::abs(row.mass_change), std::abs(row.inertia_change),
                        std::abs(row.invweight_change)});
  o << "\nbodies: " << c.bodies.size() << " moving, " << same
    << " the same on both (mass, principal inertia and Â within "
    << format_number(kVersionTolerance)
    << " relative, contacts and loads within 1e-3; largest model difference "
    << format_number(largest) << ")";
  if (differ.empty()) {
    o << "\n";
  } else {
    o << "; " << differ.size() << " differ:\n";
    std::vector<std::vector<std::string>> rows = {{"body", "mass " + a.version, "mass " + b.version,
                                                   "inertia", "Â", "contacts", "load " + a.version,
                                                   "load " + b.version, "cause"}};
    size_t listed = 0;
    for (const BodyVersions* row : differ) {
      if (++listed > 20) continue;
      rows.push_back(
          {row->name, format_number(row->mass[0]) + " kg", format_number(row->mass[1]) + " kg",
           percent(row->inertia_change), percent(row->invweight_change),
           std::to_string(row->contacts[0]) + " / " + std::to_string(row->contacts[1]),
           format_number(row->load[0]) + " N", format_number(row->load[1]) + " N", row->cause});
    }
    // The same padding as inspect's tables.
    std::vector<size_t> widths(rows[0].size(), 0);
    auto width = [](const std::string& t) {
      size_t n = 0;
      for (const char ch : t) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80 ? 1 : 0;
      return n;
    };
    for (const auto& r : rows)
      for (size_t i = 0; i < r.size(); ++i) widths[i] = std::max(widths[i], width(r[i]));
    for (const auto& r : rows) {
      o << " ";
      for (size_t i = 0; i < r.size(); ++i)
        o << " " << r[i]
          << (i + 1 < r.size() ? std::string(widths[i] - width(r[i]) + 1, ' ') : std::string());
      o << "\n";
    }
    if (listed > 20) o << "  … and " << listed - 20 << " more (--json lists every body)\n";
  }
  o << "\ntrees (weight Σ m·|g| and what the contacts carry up, N):\n";
  for (const TreeVersions& t : c.trees) {
    if (t.contacts[0] == 0 && t.contacts[1] == 0 && t.weight[0] == t.weight[1]) continue;
    o << "  " << t.root << ": weight " << format_number(t.weight[0]) << " / "
      << format_number(t.weight[1]) << " (" << percent(change(t.weight[0], t.weight[1]))
      << "), carried " << format_number(t.support[0]) << " / " << format_number(t.support[1])
      << ", contacts " << t.contacts[0] << " / " << t.contacts[1] << "\n";
  }
  for (const ContactParameterChange& p : c.margins)
    o << "  geoms " << p.geom1 << " – " << p.geom2 << ": margin " << format_number(p.margin[0])
      << " / " << format_number(p.margin[1]) << " m, gap " << format_number(p.gap[0]) << " / "
      << format_number(p.gap[1]) << " m\n";
  o << "\ncauses:\n";
  if (c.causes.empty()) o << "  none: the versions agree on this model\n";
  for (const std::string& cause : c.causes) o << "  - " << cause << "\n";
  return o.str();
}

std::string format_versions_json(const VersionComparison& c) {
  std::ostringstream o;
  auto pair = [](double x, double y) {
    return "[" + json::number(x) + ", " + json::number(y) + "]";
  };
  o << "{\n  \"model\": " << json::string(c.reports[0].path) << ",\n  \"mujoco\": ["
    << json::string(c.reports[0].version) << ", " << json::string(c.reports[1].version) << "]"
    << ",\n  \"at_rest\": [" << (c.reports[0].at_rest ? "true" : "false") << ", "
    << (c.reports[1].at_rest ? "true" : "false") << "]"
    << ",\n  \"implied_density\": " << json::number(c.implied_density) << ",\n  \"bodies\": [";
  for (size_t i = 0; i < c.bodies.size(); ++i) {
    const BodyVersions& b = c.bodies[i];
    o << (i ? ",\n    " : "\n    ") << "{\"name\": " << json::string(b.name)
      << ", \"tree\": " << json::string(b.tree) << ", \"mass\": " << pair(b.mass[0], b.mass[1])
      << ", \"inertia\": [[" << json::number(b.inertia[0][0]) << ", "
      << json::number(b.inertia[0][1]) << ", " << json::number(b.inertia[0][2]) << "], ["
      << json::number(b.inertia[1][0]) << ", " << json::number(b.inertia[1][1]) << ", "
      << json::number(b.inertia[1][2]) << "]]"
      << ", \"invweight\": " << pair(b.invweight[0], b.invweight[1]) << ", \"contacts\": ["
      << b.contacts[0] << ", " << b.contacts[1] << "], \"load\": " << pair(b.load[0], b.load[1])
      << ", \"cause\": " << json::string(b.cause) << "}";
  }
  o << (c.bodies.empty() ? "]" : "\n  ]") << ",\n  \"trees\": [";
  for (size_t i = 0; i < c.trees.size(); ++i) {
    const TreeVersions& t = c.trees[i];
    o << (i ? ",\n    " : "\n    ") << "{\"root\": " << json::string(t.root)
      << ", \"weight\": " << pair(t.weight[0], t.weight[1])
      << ", \"support\": " << pair(t.support[0], t.support[1]) << ", \"contacts\": ["
      << t.contacts[0] << ", " << t.contacts[1] << "]}";
  }
  o << (c.trees.empty() ? "]" : "\n  ]") << ",\n  \"meshes\": [";
  for (size_t i = 0; i < c.meshes.size(); ++i) {
    const MeshGeom& m = c.meshes[i];
    o << (i ? ",\n    " : "\n    ") << "{\"geom\": " << json::string(m.geom_name)
      << ", \"mesh\": " << json::string(m.mesh_name)
      << ", \"box_volume\": " << json::number(m.box_volume)
      << ", \"mesh_volume\": " << json::number(m.mesh_volume) << "}";
  }
  o << (c.meshes.empty() ? "]" : "\n  ]") << ",\n  \"causes\": [";
  for (size_t i = 0; i < c.causes.size(); ++i)
    o << (i ? ",\n    " : "\n    ") << json::string(c.causes[i]);
  o << (c.causes.empty() ? "]" : "\n  ]") << "\n}\n";
  return o.str();
}

}  // namespace contact2d::mujoco
