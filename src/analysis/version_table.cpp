#include "analysis/version_table.hpp"

#include <regex>
#include <stdexcept>

#include "analysis/engine.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/run.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3/stepper.hpp"

namespace contact2d::analysis {
namespace {

VersionRow version_row(const NamedScene& s, mujoco::Mapping mapping, bool friction) {
  Scene scene = s.scene;
  if (!friction) scene.contact.mu = scene.contact.mu_roll = 0.0;
  VersionRow row;
  row.scene = s.name;
  row.mapping = std::string(mujoco::mapping_name(mapping));
  row.friction = friction;
  mujoco::MjcfOptions options;
  options.mapping = mapping;
  options.source = s.name;
  const mujoco::GeneratedModel two = mujoco::generate_mjcf(scene, options);
  options.version = mujoco::Version::V3;
  const mujoco::GeneratedModel three = mujoco::generate_mjcf(scene, options);
  mujoco::MujocoStepper native(scene, two.xml, s.name);
  const Trajectory base = simulate(native, scene.sim);
  const Trajectory reference = simulate(scene);
  auto on_v3 = [&](const std::string& xml) {
    mujoco3::Mujoco3Stepper wasm(scene, xml, s.name, three.settings);
    return simulate(wasm, scene.sim);
  };
  const Trajectory v3 = on_v3(three.xml);
  row.for_v3 = error_between(base, v3).max_pos;
  // Each change left in by editing the model for 3.x. An edit that finds
  // nothing would measure nothing: the tolerance is on every model for 3.x,
  // the start margin on compensated's corner spheres (mjcf.cpp's set_start).
  auto edited = [&](const std::string& pattern, const std::string& with, bool must) {
    std::string xml = std::regex_replace(three.xml, std::regex(pattern), with);
    if (must && xml == three.xml)
      throw std::logic_error("version table: " + s.name + ": the model for 3.x has no " + pattern +
                             " to edit (mjcf.cpp changed what it writes?)");
    return xml;
  };
  row.tolerance = error_between(base, on_v3(edited(" tolerance=\"[^\"]*\"", "", true))).max_pos;
  const bool starts =
      mapping == mujoco::Mapping::Compensated && shape_features(scene.shape).corners;
  row.gap =
      error_between(base, on_v3(edited("margin=\"-1e-09\"", "gap=\"1e-09\"", starts))).max_pos;
  row.v2_model = error_between(base, on_v3(two.xml)).max_pos;
  row.ref_v2 = error_between(reference, base).max_pos;
  row.ref_v3 = error_between(reference, v3).max_pos;
  if (friction && mapping == mujoco::Mapping::Compensated && scene.contact.mu > 0.0) {
    options.friction_damper = true;
    mujoco3::Mujoco3Stepper damper(scene, options);
    row.ref_v3_damper = error_between(reference, simulate(damper, scene.sim)).max_pos;
  }
  return row;
}

}  // namespace

VersionTable version_table(const std::vector<NamedScene>& scenes, unsigned threads) {
  VersionTable table;
  table.not_run = mujoco3::missing();
  if (!table.not_run.empty()) return table;
  const mujoco::Mapping mappings[] = {mujoco::Mapping::Calibrated, mujoco::Mapping::Compensated};
  table.rows.resize(scenes.size() * 4);
  parallel_for(table.rows.size(), threads, [&](size_t i) {
    table.rows[i] = version_row(scenes[i / 4], mappings[i % 2], (i / 2) % 2 == 0);
  });
  return table;
}

}  // namespace contact2d::analysis
