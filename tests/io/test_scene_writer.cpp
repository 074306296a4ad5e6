// scene_to_toml (io/scene_writer.hpp): what it writes reads back as the same
// scene, field for field and bit for bit, for every built-in scene and for
// scenes whose numbers have no short decimal form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/scene_file.hpp"
#include "io/scene_writer.hpp"

namespace contact2d {
namespace {

void expect_same(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.shape, b.shape);
  const Model ma = make_model(a), mb = make_model(b);
  EXPECT_EQ(ma.body.mass, mb.body.mass);
  EXPECT_EQ(ma.body.inertia, mb.body.inertia);
  ASSERT_EQ(ma.body.points.size(), mb.body.points.size());
  for (size_t i = 0; i < ma.body.points.size(); ++i)
    EXPECT_EQ(ma.body.points[i], mb.body.points[i]);
  EXPECT_EQ(a.contact.k, b.contact.k);
  EXPECT_EQ(a.contact.c, b.contact.c);
  EXPECT_EQ(a.contact.mu, b.contact.mu);
  EXPECT_EQ(a.contact.alpha, b.contact.alpha);
  EXPECT_EQ(a.contact.mu_roll, b.contact.mu_roll);
  EXPECT_EQ(a.contact.mu_torsion, b.contact.mu_torsion);
  EXPECT_EQ(a.contact.damping, b.contact.damping);
  EXPECT_EQ(a.initial.q, b.initial.q);
  EXPECT_EQ(a.initial.v, b.initial.v);
  EXPECT_EQ(a.sim.dt, b.sim.dt);
  EXPECT_EQ(a.sim.duration, b.sim.duration);
  EXPECT_EQ(a.sim.output_dt, b.sim.output_dt);
  EXPECT_EQ(a.sim.integrator, b.sim.integrator);
  EXPECT_EQ(a.sim.gravity, b.sim.gravity);
  EXPECT_EQ(a.obstacles.size(), b.obstacles.size());
}

TEST(SceneWriter, BuiltInScenesReadBackUnchanged) {
  for (const char* name : {"point_mass", "box", "tshape", "circle"}) {
    SCOPED_TRACE(name);
    const Scene scene =
        load_scene(std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes/" + name + ".toml");
    expect_same(scene, parse_scene(scene_to_toml(scene), "written"));
  }
}

// Numbers with no short decimal form (1/3, π/7, …) and a T of three
// parts, Kelvin–Voigt, RK4: every field must survive, which needs 17
// significant digits where the shortest form is that long.
TEST(SceneWriter, AwkwardNumbersAndEveryShapeRoundTripBitForBit) {
  for (Shape shape : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
    SCOPED_TRACE(shape_name(shape));
    Scene s = default_scene(shape);
    if (shape != Shape::TShape) s.mass = 1.0 / 3.0;
    s.width = M_PI / 7.0;
    s.height = std::sqrt(2.0) / 10.0;
    s.radius = std::exp(-1.0);
    s.half_height = 0.1 / 3.0;
    if (shape == Shape::TShape)
      s.parts = {{0.3, 0.1 / 3.0, -0.1, 0.05, 0.2},  // width, height, x, y, mass
                 {0.1, 0.4, 0.0, 0.0, 1.0 / 7.0},
                 {0.05, 0.05, 0.2 / 3.0, -0.3, 0.01}};
    s.contact.k = 12345.678901234567;
    s.contact.c = 1.0 / 3.0 * 100.0;
    s.contact.mu = 0.1 * 3.0;
    s.contact.mu_roll = shape == Shape::Circle ? 0.01 / 3.0 : 0.0;
    s.contact.damping = DampingLaw::KelvinVoigt;
    s.initial.q = Vec3(0.1 + 0.2, 1.0 / 3.0, shape == Shape::PointMass ? 0.0 : -M_PI / 9.0);
    s.initial.v = Vec3(-2.0 / 3.0, 1e-7 / 3.0, shape == Shape::PointMass ? 0.0 : 3.0 / 7.0);
    s.sim.dt = 1e-4;
    s.sim.duration = 1.5;
    s.sim.integrator = Integrator::RK4;
    s.sim.gravity = 9.80665;
    expect_same(s, parse_scene(scene_to_toml(s, "two\nlines"), "written"));
  }
}

TEST(SceneWriter, CommentLinesComeFirstBehindHashes) {
  const std::string text = scene_to_toml(default_scene(Shape::Box), "random scene s05\nseed 7");
  EXPECT_EQ(text.rfind("# random scene s05\n# seed 7\nscene = \"box\"\n", 0), 0u) << text;
}

}  // namespace
}  // namespace contact2d
