// The MuJoCo stepper (mujoco/stepper.hpp): state read-back conventions (docs/physics.md), sample
// times, runtime warnings and divergence.
#include <cmath>
#include <string>

#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d {
namespace {

// Far above the ground nothing but gravity acts, so MuJoCo's Euler and the
// reference's semi-implicit Euler make the same updates: v' = v + a·Δt,
// q' = q + v'·Δt with a = (0, −g, 0). A slip in the read-back of x, y, θ or
// the velocities (order, sign, the body's initial offset) would show at
// once; the states agree to rounding (1e-12 over 5000 steps of numbers ~ 10).
TEST(MujocoStepper, FreeFlightReadsBackTheReferenceState) {
  const Scene scene = test::scene_from(
      "scene = \"tshape\"\n[initial]\nx = -1.5\ny = 10\ntheta = 0.7\nvx = 0.8\nvy = 2.5\nomega = "
      "-3.1\n"
      "[sim]\ndt = 1e-4\nduration = 0.5\n");
  const test::BothRuns runs = test::run_both(scene);
  EXPECT_LT(runs.errors.max_pos, 1e-12);
  EXPECT_LT(runs.errors.max_angle, 1e-12);
  EXPECT_LT(runs.errors.max_vel, 1e-12);
  EXPECT_LT(runs.errors.max_omega, 1e-12);
  const State& end = runs.mj.trajectory.samples.back().state;
  EXPECT_NEAR(end.q.z(), 0.7 - 3.1 * 0.5, 1e-12);  // ω < 0 turns clockwise: θ falls
}

// docs/physics.md: a body-fixed point c_loc is at p + R(θ)·c_loc with θ counter-
// clockwise. MuJoCo's forward kinematics of the generated model put every
// corner sphere there (MuJoCo z = 2D y), for any (x, y, θ).
TEST(MujocoStepper, CornerSpheresSitWhereTheTwoDimensionalRotationPutsThem) {
  const Scene scene = default_scene(Shape::TShape);
  const mujoco::ModelPtr model = mujoco::load_model(mujoco::generate_mjcf(scene, {}).xml, "T");
  const mujoco::DataPtr data = mujoco::make_data(model.get());
  const RigidBody body = make_body(scene);
  const Vec3 q(0.4, 1.3, 2.2);  // x, y, θ
  data->qpos[0] = q.x() - model->body_pos[3];
  data->qpos[1] = q.y() - model->body_pos[5];
  data->qpos[2] = q.z();
  mj_kinematics(model.get(), data.get());
  const double c = std::cos(q.z()), s = std::sin(q.z());
  for (size_t i = 0; i < body.points.size(); ++i) {
    const int g = mj_name2id(model.get(), mjOBJ_GEOM, ("corner" + std::to_string(i)).c_str());
    ASSERT_GE(g, 0);
    const Vec2& r = body.points[i];
    EXPECT_NEAR(data->geom_xpos[3 * g + 0], q.x() + c * r.x() - s * r.y(), 1e-12) << i;
    EXPECT_NEAR(data->geom_xpos[3 * g + 1], 0.0, 1e-12) << i;
    EXPECT_NEAR(data->geom_xpos[3 * g + 2], q.y() + s * r.x() + c * r.y(), 1e-12) << i;
  }
}

// A point mass has no hinge: θ and ω read back as exactly 0.
TEST(MujocoStepper, PointMassHasNoAngle) {
  const test::BothRuns runs = test::run_both(test::drop_scene(Shape::PointMass, 200.0, 0.5));
  for (const Sample& s : runs.mj.trajectory.samples) {
    ASSERT_EQ(s.state.q.z(), 0.0);
    ASSERT_EQ(s.state.v.z(), 0.0);
  }
}

// Samples at t = 0, every output_dt, and the last step when the duration is
// not a multiple of output_dt (0.0105 s = 105 steps, stride 10).
TEST(MujocoStepper, SamplesAtTheReferencesTimes) {
  Scene scene = test::drop_scene(Shape::Box, 200.0, 0.5);
  scene.sim.duration = 0.0105;
  const test::BothRuns runs = test::run_both(scene);
  ASSERT_EQ(runs.mj.trajectory.samples.size(), 12u);
  for (size_t i = 0; i < runs.ref.samples.size(); ++i) {
    EXPECT_EQ(runs.mj.trajectory.samples[i].t, runs.ref.samples[i].t) << i;
  }
  EXPECT_EQ(runs.mj.trajectory.samples.back().t, 105 * 1e-4);
}

// A model whose contact buffer holds one contact, for a box landing flat on
// two corners: MuJoCo drops the second contact and warns; the run reports
// both the text warning and the counter.
TEST(MujocoStepper, RuntimeWarningsAreSurfaced) {
  const Scene scene = test::scene_from(
      "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\ndamping = \"kelvin_voigt\"\n[initial]\ny = "
      "0.2\n"
      "[sim]\ndt = 1e-4\nduration = 0.3\n");
  std::string xml = mujoco::generate_mjcf(scene, {}).xml;
  const std::string size = "nconmax=\"48\"";
  ASSERT_NE(xml.find(size), std::string::npos);
  xml.replace(xml.find(size), size.size(), "nconmax=\"1\"");
  const test::MujocoRun run = test::run_mujoco_xml(scene, xml, "one contact");
  ASSERT_EQ(run.warnings.size(), 2u);
  EXPECT_NE(run.warnings[0].find("contact"), std::string::npos) << run.warnings[0];
  EXPECT_NE(run.warnings[1].find("mjData.warning: too many contacts (nconmax)"), std::string::npos)
      << run.warnings[1];
}

// k = 1e8 N/m on 1 kg at Δt = 1e-3 (ω·Δt = 10): MuJoCo's explicit contact
// force blows up. The run stops at the first bad step with a divergence and
// keeps only finite samples before it.
TEST(MujocoStepper, DivergenceStopsTheRunWithoutNonFiniteSamples) {
  const Scene scene = test::scene_from(
      "scene = \"point_mass\"\n[contact]\nk = 1e8\nc = 0\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.06\n[sim]\ndt = 1e-3\nduration = 1\n");
  const test::MujocoRun run = test::run_mujoco(scene, {});
  ASSERT_TRUE(run.trajectory.divergence.has_value());
  EXPECT_LT(run.trajectory.divergence->time, 0.1);
  for (const Sample& s : run.trajectory.samples) {
    EXPECT_TRUE(s.state.q.allFinite() && s.state.v.allFinite()) << "t = " << s.t;
    EXPECT_LT(s.t, run.trajectory.divergence->time);
  }
}

// set_applied reaches MuJoCo as xfrc_applied at the COM in the reference's
// convention: +Fx along x, +Fy up (MuJoCo z), +τ turning θ positive (the
// hinge axis is −y). In flight, with F_y = m·g cancelling gravity, a
// constant (Fx, τ) gives vx = Fx/m·t and ω = τ/I·t; MuJoCo's Euler adds the
// same acceleration every step, so only rounding over 1000 steps differs
// (tolerance 1e-9 relative). vy stays at its initial value to rounding.
TEST(MujocoStepper, AppliedForceAndTorqueFollowTheReferenceConvention) {
  const Scene scene = test::scene_from(
      "scene = \"box\"\n[body]\nmass = 2.0\nwidth = 0.4\nheight = 0.2\n"
      "[initial]\ny = 5\n[sim]\ndt = 1e-3\nduration = 1\n");
  mujoco::MujocoStepper stepper(scene, mujoco::MjcfOptions{});
  const double fx = 3.0, tau = 0.5;
  const double m = scene.mass, inertia = make_body(scene).inertia;
  stepper.set_applied(Vec3(fx, m * scene.sim.gravity, tau));
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(stepper.step(), StepStatus::Ok);
  const double t = 1.0;
  EXPECT_NEAR(stepper.state().v.x(), fx / m * t, 1e-9 * fx / m * t);
  EXPECT_NEAR(stepper.state().v.z(), tau / inertia * t, 1e-9 * tau / inertia * t);
  EXPECT_NEAR(stepper.state().v.y(), 0.0, 1e-12);
  EXPECT_TRUE(stepper.contacts().empty()) << "in flight";
}

// reset() puts MuJoCo in the given planar state (read back exactly).
TEST(MujocoStepper, ResetSetsThePlanarState) {
  const Scene scene = test::scene_from("scene = \"box\"\n[initial]\ny = 1\n");
  mujoco::MujocoStepper stepper(scene, mujoco::MjcfOptions{});
  State s;
  s.q = Vec3(0.25, 0.08, 0.3);
  s.v = Vec3(-1.0, 0.5, 2.0);
  stepper.reset(s);
  EXPECT_NEAR((stepper.state().q - s.q).norm(), 0.0, 1e-15);
  EXPECT_EQ(stepper.state().v, s.v);
  EXPECT_FALSE(stepper.contacts().empty()) << "a corner of the tilted box is below the ground";
}

}  // namespace
}  // namespace contact2d
