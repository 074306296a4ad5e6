// MuJoCo's descriptor for the engine registry (mujoco/engine.hpp).
#include "mujoco/engine.hpp"

#include "mujoco/mapping.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"

namespace contact2d::mujoco {
namespace {

std::unique_ptr<Stepper> make_mujoco(const engines::EngineSpec& spec, const Scene& scene) {
  MjcfOptions options = mjcf_options(spec.option("mapping"), spec.option("geometry"), spec.source);
  options.model_dt = spec.model_dt;
  return std::make_unique<MujocoStepper>(scene, options);
}

bool offers(Integrator integrator) { return integrator != Integrator::ExplicitEuler; }

// MuJoCo's implicit integrates joint damping and actuators implicitly but
// contact forces explicitly: for a contact it is semi-implicit Euler.
Integrator contact_integrator(Integrator integrator) {
  return integrator == Integrator::ImplicitEuler ? Integrator::SemiImplicitEuler : integrator;
}

std::vector<std::string_view> mapping_values() {
  std::vector<std::string_view> values;
  for (Mapping m : kAllMappings) values.push_back(mapping_name(m));
  return values;
}

}  // namespace

std::string_view integrator_title(Integrator integrator) {
  switch (integrator) {
    case Integrator::SemiImplicitEuler: return "Euler";
    case Integrator::ImplicitEuler: return "implicit";
    case Integrator::RK4: return "RK4";
    case Integrator::ExplicitEuler: break;
  }
  return {};
}

const engines::EngineInfo& engine_info() {
  // mujoco[:MAPPING[:GEOMETRY]], named as mapping.hpp names them.
  static const engines::EngineInfo info{
      "mujoco",
      "MuJoCo",
      make_mujoco,
      offers,
      [](const Scene& scene) { mujoco_integrator(scene.sim.integrator); },
      integrator_title,
      contact_integrator,
      {{"mapping", "solref/solimp mapping", mapping_values(), mapping_name(kDefaultMapping)},
       {"geometry",
        "MuJoCo geoms of a box or T (corners: a small sphere per 2D contact point; boxes: a box "
        "geom per part)",
        {geometry_name(Geometry::CornerSpheres), geometry_name(Geometry::BoxGeoms)},
        geometry_name(kDefaultGeometry)}},
      "Compute MuJoCo's Δt-dependent values (the calibrated impratio) for this Δt instead of the "
      "timestep: holds the model fixed while --dt changes",
      true};
  return info;
}

}  // namespace contact2d::mujoco
