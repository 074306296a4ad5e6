// libFuzzer target: scene file → MJCF generator → MuJoCo. For any input,
// either parse_scene rejects it (InputError), or generate_mjcf refuses the
// scene with InputError for a reason it may have (below), or the MJCF loads in
// MuJoCo without error or warning and the model has the scene's structure:
// two bodies, its joints, geoms and keyframe, timestep == sim.dt, gravity ==
// sim.gravity, its mass, positive inertias and no non-finite number in any
// real array of the model. Anything else (a crash, a sanitizer report, another
// exception, a refusal for another reason, a model MuJoCo rejects) aborts.
//
// Reasons to refuse a valid scene: the documented ones, which must refuse
// (explicit Euler; obstacles; seed/exact with k or c = 0 or a timeconst or
// dampratio that is not a positive normal number, with a message naming
// contact.k or contact.c); a mass or hinge inertia below MuJoCo's mjMINVAL
// (MuJoCo cannot represent the body); and MuJoCo's warning about a huge qacc
// in the compiler's test step (θ = 0, v = 0) when the mapping's own contact
// spring at the initial depth can produce one, i.e. the scene starts with an
// acceleration near MuJoCo's mjMAXVAL = 1e10.
//
// Every input is tried with all three mappings (and, for a box or T, both
// geometries): they differ in what reaches MuJoCo (seed/exact: standard
// solref with refsafe; calibrated: direct solref from body_invweight0 and
// impratio), and trying all finds a scene that breaks one without the
// fuzzer having to discover a selector byte. It costs up to 14 MuJoCo loads
// per valid box or T (calibrated loads twice, and each model is reloaded
// here), and the target still runs about 1,000 inputs/s on one core.
//
// The model is not stepped. Tried: 300 steps from the keyframe, aborting on
// a non-finite qpos or a bad-number counter, only when ω·Δt < 0.1. With ω =
// √(k/m_eff) it failed within minutes on a 1e9 kg point mass hitting the
// ground at 1e6 m/s (seed's spring (k/m)/ζ² is 1e9 times k/m there); with
// the mapping's own spring in ω too, on a 1 km T spinning at 1e6 rad/s (100
// rad per step). Both pass validation and no integrator follows them;
// telling them apart from bugs needs a stability theory of MuJoCo. A finite
// qpos alone proves nothing: MuJoCo resets the state on a bad qacc.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <type_traits>

#include <mujoco/mjxmacro.h>

#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace {

using namespace contact2d;
using namespace contact2d::mujoco;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_mjcf: %s\n", what.c_str());
  std::abort();
}

bool has(const std::string& text, const char* part) { return text.find(part) != std::string::npos; }

// Generous bound on |qacc| in the compiler's test step: gravity plus, for each
// contact, the mapping's spring gain (refsafe applied) × the initial depth ×
// max(1, A/Â) × 20 (the default impedance d ≤ 0.95 amplifies by ≤ 1/(1 − d)).
// Â = body_invweight0 = 2/(3m) for slide joints at the COM; A ≤ 1/m + r²/I.
double test_step_qacc_bound(const Scene& scene, Mapping mapping, Geometry geometry) {
  const Model model = make_model(scene);
  const RigidBody& body = model.body;
  const Vec3 q0(scene.initial.q.x(), scene.initial.q.y(), 0.0);
  const double depth = max_penetration(model, q0) + kCornerRadius;
  const double a_hat = 2.0 / (3.0 * body.mass);
  const double r = body_extent(body);
  const double a = 1.0 / body.mass + (body.rotates ? r * r / body.inertia : 0.0);
  const int split = contacts_per_point(scene.shape, geometry);
  SolverSettings s = solver_settings(scene, mapping, a_hat, split);
  if (s.solref[0] > 0.0) s.solref[0] = std::max(s.solref[0], 2.0 * scene.sim.dt);
  const double gain = acceleration_gains(s.solref).stiffness;
  const double contacts = static_cast<double>(body.points.size() * split);
  return scene.sim.gravity + 20.0 * contacts * gain * depth * std::max(1.0, a / a_hat);
}

// Must generate_mjcf refuse this valid scene (documented reasons)?
bool must_refuse(const Scene& scene, Mapping mapping) {
  if (scene.sim.integrator == Integrator::ExplicitEuler) return true;
  if (mapping == Mapping::Calibrated || mapping == Mapping::Compensated) return false;
  // MuJoCo's standard solref (timeconst, dampratio), as solver_settings computes it.
  const double m = make_body(scene).mass, k = scene.contact.k, c = scene.contact.c;
  const double tc = mapping == Mapping::Seed ? std::sqrt(m / k) : 2.0 * m / c;
  const double zeta = c / (2.0 * std::sqrt(m * k));
  auto usable = [](double v) { return v > 0.0 && std::isnormal(v); };
  return !(k > 0.0 && c > 0.0 && usable(tc) && usable(zeta));
}

// May generate_mjcf refuse this valid scene with this message?
bool refusal_allowed(const Scene& scene, Mapping mapping, Geometry geometry,
                     const std::string& message) {
  if (must_refuse(scene, mapping)) {
    const bool contact_key = message.rfind("contact.", 0) == 0;
    return scene.sim.integrator == Integrator::ExplicitEuler || contact_key;
  }
  const RigidBody body = make_body(scene);
  if (has(message, "must be larger than mjMINVAL"))
    return body.mass < mjMINVAL || (body.rotates && body.inertia < mjMINVAL);
  if (has(message, "warns while loading") && has(message, "huge value in QACC"))
    return !(test_step_qacc_bound(scene, mapping, geometry) < mjMAXVAL);
  return false;
}

// Every real array of the model (mjxmacro.h lists them all) is finite.
bool all_finite(const mjModel* m) {
  MJMODEL_POINTERS_PREAMBLE(m)
#define X(type, name, nr, nc)                                            \
  if constexpr (std::is_floating_point_v<type>) {                        \
    for (long i = 0; i < static_cast<long>(m->nr) * (nc); ++i) {         \
      if (!std::isfinite(static_cast<double>(m->name[i]))) return false; \
    }                                                                    \
  }
  MJMODEL_POINTERS
#undef X
  return true;
}

void check_model(const Scene& scene, Mapping mapping, Geometry geometry, const mjModel* m) {
  const RigidBody body = make_body(scene);
  // compensated moves the contact geoms onto a massless body ("contacts") at
  // a lever, turned by the body's hinge; the point mass gets one ("spin").
  const bool compensated = mapping == Mapping::Compensated;
  const bool hinge = scene.shape != Shape::PointMass || compensated;
  const int points = static_cast<int>(body.points.size());
  // Ground + contact geoms (+ the parts drawn when corner spheres carry the contacts).
  int geoms = 1 + 1;
  // The point mass's contact sphere of kCornerRadius at (0, −h), and a
  // visual sphere of radius h when h is larger (mujoco/mjcf.hpp).
  if (scene.shape == Shape::PointMass && scene.half_height > kCornerRadius) geoms += 1;
  if (scene.shape == Shape::Box || scene.shape == Shape::TShape)
    geoms = 1 + points / 4 + (geometry == Geometry::CornerSpheres ? points : 0);
  // One static geom per obstacle, touched through one explicit pair per
  // (contact geom of the body, obstacle).
  const int obstacles = static_cast<int>(scene.obstacles.size());
  geoms += obstacles;
  const int contact_geoms = (scene.shape == Shape::Box || scene.shape == Shape::TShape)
                                ? (geometry == Geometry::CornerSpheres ? points : points / 4)
                                : 1;
  if (m->nbody != (compensated ? 3 : 2) || m->njnt != (hinge ? 3 : 2) || m->nq != m->njnt ||
      m->nv != m->njnt || m->ngeom != geoms || m->nkey != 1 ||
      m->npair != obstacles * contact_geoms)
    fail("unexpected model structure");
  if (!(m->opt.timestep == scene.sim.dt)) fail("timestep differs from sim.dt");
  if (!(m->opt.gravity[2] == -scene.sim.gravity)) fail("gravity differs from sim.gravity");
  if (!(std::abs(m->body_mass[1] - body.mass) <= 1e-12 * body.mass))
    fail("body mass differs from the scene's");
  for (int i = 3; i < 6; ++i)
    if (!(m->body_inertia[i] >= mjMINVAL)) fail("inertia below mjMINVAL");
  if (!all_finite(m)) fail("non-finite number in the model");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  try {
    scene = parse_scene(text, "fuzz.toml");
  } catch (const InputError&) {
    return 0;
  }
  const bool boxes = scene.shape == Shape::Box || scene.shape == Shape::TShape;
  for (Mapping mapping : kAllMappings) {
    for (Geometry geometry : {Geometry::CornerSpheres, Geometry::BoxGeoms}) {
      if (geometry == Geometry::BoxGeoms && !boxes) continue;
      MjcfOptions options;
      options.mapping = mapping;
      options.geometry = geometry;
      options.source = "fuzz.toml";
      GeneratedModel generated;
      try {
        generated = generate_mjcf(scene, options);
      } catch (const InputError& e) {
        if (refusal_allowed(scene, mapping, geometry, e.what())) continue;
        fail(std::string("valid scene refused: ") + e.what());
      } catch (const std::exception& e) {
        fail(std::string("unexpected exception: ") + e.what());
      }
      if (must_refuse(scene, mapping)) fail("generate_mjcf accepted a scene it must refuse");
      try {
        const ModelPtr model = load_model(generated.xml, "fuzz.toml");
        check_model(scene, mapping, geometry, model.get());
      } catch (const std::exception& e) {
        fail(std::string("generated MJCF does not reload: ") + e.what());
      }
    }
  }
  return 0;
}
