// The ellipse in MuJoCo 2.2.2: one ellipsoid geom (mujoco/mjcf.cpp,
// ellipse_layout) against the ground plane.
//
// Which contacts MuJoCo makes. The plane–ellipsoid pair is
// mjCOLLISIONFUNC[PLANE][ELLIPSOID] = mjc_PlaneConvex
// (engine_collision_driver.c, 2.2.2 and every 3.x tag through 3.12):
// mjccd_support gives the ellipsoid's support point in −n (exact:
// size ⊙ normalize(size ⊙ dir)), it returns 0 contacts when its distance
// to the plane exceeds the margin (0 here), else one contact with
// dist = that distance and pos = the support point moved −dist/2 along n
// (halfway into the penetration); the extra plane–mesh vertices that follow
// are skipped for an ellipsoid ("g is an ellipsoid: no need for further
// mesh-specific processing", geom_dataid = −1). So at most one contact, and
// it is the reference's own support point (core/ellipse.hpp,
// ellipse_lowest_point): the tests check both at every step of a thrown,
// spinning, bouncing and rocking ellipse, of the real ellipse of
// validation/real/ellipse hitting the ground at 2.6 m/s, and of an ellipse
// coming to rest.
//
// Tolerance of the geometry. Both sides compute the same closed form in
// double precision: MuJoCo from its kinematics (the slide axes and the hinge
// are written in the initial pose's rotated frame, so the world axes and
// the angle come back through a quaternion product: a few ulps) and the
// support formula, the reference from h = √(a²·sin²θ + b²·cos²θ). Each is at
// most a few tens of roundings of numbers of at most 1 m (positions) and
// 0.2 m (the semi-axes): ≲ 16·ε·1 m = 3.6e-15 m. kEllipseGeometry = 1e-14 m is that
// bound with a margin of about 3 (measured: ≤ 1.7e-16 m on these runs, the
// ulp of the numbers compared). A wrong contact point is off by far more:
// the support point itself instead of MuJoCo's halfway point by d/2 (up to
// 1e-2 m here), swapped semi-axes by up to a − b = 0.1 m.
//
// When a contact exists. MuJoCo makes one exactly when the support point's
// distance to the plane is ≤ 0, the reference when its depth d > 0; within
// kEllipseGeometry of d = 0 the two roundings may decide apart, so the test
// requires a contact for d > kEllipseGeometry, none for d < −kEllipseGeometry, and at most
// one in between.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/friction_table.hpp"
#include "core/ellipse.hpp"
#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/model_state.hpp"

namespace contact2d {
namespace {

constexpr double kEllipseGeometry = 1e-14;  // m, see above

// What a run of MuJoCo 2.2.2 on an ellipse scene showed, step by step,
// against the reference's support point at the same configuration.
struct EllipseContactLog {
  long long steps = 0;
  long long contact_steps = 0;  // steps with a MuJoCo contact
  int max_ncon = 0;
  long long wrong_count = 0;    // steps whose ncon the reference's depth contradicts
  std::string first_wrong;      // the first of them, described
  long long wrong_pair = 0;     // contacts not between "ground" and "ellipse"
  double depth_error = 0.0;     // max |dist − (−d)|, m
  double position_error = 0.0;  // max |pos − (support point + (0, d/2))|, m
  double normal_error = 0.0;    // max |normal − (0, 0, 1)|
  double max_depth = 0.0;       // largest d of a contact, m
  double end_speed = 0.0;       // largest |qvel| at the end
};

// MuJoCo 2.2.2 on the scene's calibrated model, from its keyframe, for the
// scene's duration. After mj_step, d->contact holds the contacts of the
// configuration the step started from (mj_step runs mj_forward, collision
// included, then integrates qpos): that configuration is compared.
EllipseContactLog ellipse_contacts_222(const Scene& scene) {
  const std::string xml = mujoco::generate_mjcf(scene, {}).xml;
  const mujoco::ModelPtr model = mujoco::load_model(xml, "ellipse scene");
  const mujoco::DataPtr data = mujoco::make_data(model.get());
  const mjModel* m = model.get();
  mjData* d = data.get();
  mj_resetDataKeyframe(m, d, 0);
  const int ground = mj_name2id(m, mjOBJ_GEOM, "ground");
  const int ellipse = mj_name2id(m, mjOBJ_GEOM, "ellipse");
  EXPECT_GE(ground, 0);
  EXPECT_GE(ellipse, 0);
  const double x0 = m->body_pos[3], y0 = m->body_pos[5];
  EllipseContactLog log;
  log.steps = step_count(scene.sim);
  for (long long i = 0; i < log.steps; ++i) {
    const double x = x0 + d->qpos[0], y = y0 + d->qpos[1], theta = d->qpos[2];
    const Vec2 r = ellipse_lowest_point(scene.a, scene.b, theta);
    const double depth = -(y + r.y());
    mj_step(m, d);
    const int ncon = d->ncon;
    log.max_ncon = std::max(log.max_ncon, ncon);
    if (ncon > 0) ++log.contact_steps;
    const bool wrong = ncon > 1 || (depth > kEllipseGeometry && ncon != 1) ||
                       (depth < -kEllipseGeometry && ncon != 0);
    if (wrong && log.wrong_count++ == 0) {
      char text[160];
      std::snprintf(text, sizeof text, "step %lld: ncon %d at depth %.17g m (theta %.17g)", i, ncon,
                    depth, theta);
      log.first_wrong = text;
    }
    for (int k = 0; k < ncon; ++k) {
      const mjContact& c = d->contact[k];
      if (!((c.geom1 == ground && c.geom2 == ellipse) || (c.geom1 == ellipse && c.geom2 == ground)))
        ++log.wrong_pair;
      log.depth_error = std::max(log.depth_error, std::abs(c.dist + depth));
      log.position_error = std::max({log.position_error, std::abs(c.pos[0] - (x + r.x())),
                                     std::abs(c.pos[1]), std::abs(c.pos[2] + 0.5 * depth)});
      log.normal_error = std::max({log.normal_error, std::abs(c.frame[0]), std::abs(c.frame[1]),
                                   std::abs(c.frame[2] - 1.0)});
      log.max_depth = std::max(log.max_depth, depth);
    }
  }
  for (int j = 0; j < m->nv; ++j) log.end_speed = std::max(log.end_speed, std::abs(d->qvel[j]));
  std::printf(
      "  %lld steps, %lld with a contact, max ncon %d, max depth %.3g m; |dist - ref| %.2g m, "
      "|pos - ref| %.2g m, |normal - z| %.2g\n",
      log.steps, log.contact_steps, log.max_ncon, log.max_depth, log.depth_error,
      log.position_error, log.normal_error);
  return log;
}

// Every step: at most one contact, present exactly when the reference's
// support point is below the ground, at its depth and halfway point.
void expect_one_contact_at_the_support_point(const EllipseContactLog& log) {
  EXPECT_EQ(log.max_ncon, 1);
  EXPECT_EQ(log.wrong_count, 0) << log.first_wrong;
  EXPECT_EQ(log.wrong_pair, 0);
  EXPECT_LE(log.depth_error, kEllipseGeometry);
  EXPECT_LE(log.position_error, kEllipseGeometry);
  EXPECT_LE(log.normal_error, kEllipseGeometry);
}

// The throw: a = 0.2, b = 0.1, tilted 0.3 rad, vx = 0.5 m/s,
// ω = 1 rad/s from 0.6 m (test::drop_scene), c = 20 N·s/m so that it
// bounces, μ = 0.5: it lands at 0.306 s, spins up to ~10 rad/s, bounces and
// rocks (measured: 6128 of 20000 steps in contact, depth up to 2.1 cm).
TEST(EllipseMujoco, ThrownEllipseHasOneContactAtTheSupportPoint) {
  const Scene scene = test::drop_scene(Shape::Ellipse, 20.0, 0.5);
  const EllipseContactLog log = ellipse_contacts_222(scene);
  expect_one_contact_at_the_support_point(log);
  EXPECT_GT(log.contact_steps, 1000);  // it does land, bounce and rock
}

// The real ellipse of validation/real/ellipse (a = 35 mm, b = 25 mm,
// m = 36.4 g, the plate's inertia) hitting the ground at 2.6 m/s, tilted
// 0.7 rad, spinning at 15 rad/s, with the fitted stiffness and damping
// (docs/real-impacts.md: k = 2.15e7 N/m, c = 409 N·s/m) and rolling
// resistance (condim 6), Δt = 4e-7 s (ω·Δt ≈ 0.01): 310 steps in contact,
// 70 µm deep at most.
TEST(EllipseMujoco, RealEllipseImpactHasOneContactAtTheSupportPoint) {
  const Scene scene = test::scene_from(
      "scene = \"ellipse\"\n[body]\nmass = 0.0364\na = 0.035\nb = 0.025\ninertia = 1.6835e-5\n"
      "[contact]\nk = 2.15e7\nc = 409\nmu = 0.3\nmu_roll = 0.003\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.036\ntheta = 0.7\nvx = 0.8\nvy = -2.6\nomega = 15\n"
      "[sim]\ndt = 4e-7\nduration = 0.005\n");
  const EllipseContactLog log = ellipse_contacts_222(scene);
  expect_one_contact_at_the_support_point(log);
  EXPECT_GT(log.contact_steps, 100);
}

// At rest: an ellipse set down on its flat side tilted 0.05 rad rocks and
// settles (rolling resistance 5 mm takes the rocking out; without it the
// rocking decays over tens of seconds): one contact at every step, and at
// the end it is at rest by model_state.hpp's criterion (measured
// |qvel| ≤ 1e-7 at 3 s).
TEST(EllipseMujoco, RestingEllipseHasOneContactAtTheSupportPoint) {
  const Scene scene = test::scene_from(
      "scene = \"ellipse\"\n[body]\nmass = 1\na = 0.2\nb = 0.1\n"
      "[contact]\nk = 1e4\nc = 200\nmu = 0.5\nmu_roll = 0.005\n"
      "[initial]\ny = 0.1\ntheta = 0.05\n[sim]\ndt = 1e-4\nduration = 3\n");
  const EllipseContactLog log = ellipse_contacts_222(scene);
  expect_one_contact_at_the_support_point(log);
  EXPECT_EQ(log.contact_steps, log.steps);
  EXPECT_LE(log.end_speed, mujoco::kRestSpeed);
}

// The two engines on the thrown ellipse, with MuJoCo's friction taken
// apart (test_soft_cone.cpp's conformance: the compensated mapping, whose
// force is the Kelvin–Voigt law up to 1e-6·d·A/Â). Without friction the
// reference's own law and MuJoCo apply the same normal force at the same
// support point (moving it along the normal, as MuJoCo's halfway point
// does, changes no torque); with friction the reference runs MuJoCo's soft
// cone at the model's impratio, applied halfway into the penetration.
// Measured: 9.1e-9 m and 1.1e-7 rad without friction (a chaotic run: the
// scene magnifies a 1e-8 m change of the start 373-fold, `contact2d
// compare`), 3.4e-11 m and 2.5e-10 rad under the soft cone (1.4-fold).
// Bound 1e-6 m, test_soft_cone.cpp's kConformance, 110 times the larger, on
// the position and on the rim's displacement a·Δθ (2.2e-8 m measured).
// What it catches (measured by changing the reference's scene): the solid
// ellipsoid's inertia m(a² + b²)/5 instead of the plate's, 0.14 m and
// 0.20 m; b off by 1e-7 m, 4.2e-3 m and 3.2e-5 m; with friction, twice the
// cone ratio, 6.7e-3 m, and the cone without its push (viscous_cone),
// 0.105 m. The calibrated mapping is 1.8e-4 m (soft cone) and 0.10 m
// (without friction: the runs graze apart at 0.84 s) away: its O(d) term.
TEST(EllipseMujoco, FollowsTheReferenceWithoutFrictionAndUnderTheSoftCone) {
  constexpr double kConformance = 1e-6;  // m, see above
  mujoco::MjcfOptions options;
  options.mapping = mujoco::Mapping::Compensated;
  for (double mu : {0.0, 0.5}) {
    const Scene scene = test::drop_scene(Shape::Ellipse, 20.0, mu);
    const test::MujocoRun mj = test::run_mujoco(scene, options);
    const Trajectory ref =
        simulate(mu > 0.0 ? analysis::conformance_scene(scene, FrictionLaw::SoftCone) : scene);
    ASSERT_FALSE(ref.divergence.has_value());
    ASSERT_FALSE(mj.trajectory.divergence.has_value());
    EXPECT_TRUE(mj.warnings.empty());
    const analysis::TrajectoryError e = analysis::error_between(ref, mj.trajectory);
    std::printf("  mu %.1f: ref%s vs MuJoCo 2.2.2 (compensated) %.3g m, %.3g rad\n", mu,
                mu > 0.0 ? " (soft cone)" : "", e.max_pos, e.max_angle);
    EXPECT_LT(e.max_pos, kConformance) << "mu " << mu;
    EXPECT_LT(scene.a * e.max_angle, kConformance) << "mu " << mu;
  }
}

}  // namespace
}  // namespace contact2d
