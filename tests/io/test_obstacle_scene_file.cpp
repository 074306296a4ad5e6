// Obstacles in scene files (io/scene_file.hpp): boxes and segments are read
// with their keys, and every bad obstacle names its key and range.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_file.hpp"

namespace contact2d {
namespace {

// ---------------------------------------------------------------------------
// Scene files: [[obstacle]] tables and their errors.
TEST(ObstacleSceneFile, BoxesAndSegmentsAreRead) {
  const Scene scene = parse_scene(R"(
scene = "circle"
[[obstacle]]
type = "box"
x = 10.06
y = 2.5
width = 0.12
height = 0.12
[[obstacle]]
type = "segment"
x1 = 0
y1 = 1
x2 = 2
y2 = 1.5
radius = 0.05
)",
                                  "test.toml");
  ASSERT_EQ(scene.obstacles.size(), 2u);
  EXPECT_EQ(scene.obstacles[0].shape, ObstacleShape::Box);
  EXPECT_NEAR(scene.obstacles[0].a.x(), 10.0, 1e-12);
  EXPECT_NEAR(scene.obstacles[0].b.y(), 2.56, 1e-12);
  EXPECT_EQ(scene.obstacles[1].shape, ObstacleShape::Segment);
  EXPECT_EQ(scene.obstacles[1].b, Vec2(2.0, 1.5));
  EXPECT_EQ(scene.obstacles[1].radius, 0.05);
  EXPECT_EQ(make_model(scene).obstacles.size(), 2u);
}

// An obstacle's own contact keys replace the scene's, key by key; the keys
// it leaves out follow the scene's [contact], also when that changes later
// (a --set or a sweep), and the reference applies each obstacle's law.
TEST(ObstacleSceneFile, AnObstacleHasItsOwnContactLawKeyByKey) {
  Scene scene = parse_scene(R"(
scene = "circle"
[contact]
k = 1e5
c = 60
mu = 0.4
[[obstacle]]
type = "box"
x = 0
y = 2
width = 1
height = 0.1
[[obstacle]]
type = "box"
x = 3
y = 2
width = 1
height = 0.1
k = 2000
c = 150
damping = "kelvin_voigt"
)",
                            "test.toml");
  EXPECT_FALSE(scene.obstacles[0].contact.any());
  scene.contact.mu = 0.7;  // a later change of the scene's law
  const Model model = make_model(scene);
  ASSERT_EQ(model.obstacle_laws.size(), 2u);
  EXPECT_EQ(model.obstacle_laws[0].k, 1e5);
  EXPECT_EQ(model.obstacle_laws[1].k, 2000.0);
  EXPECT_EQ(model.obstacle_laws[1].c, 150.0);
  EXPECT_EQ(model.obstacle_laws[1].damping, DampingLaw::KelvinVoigt);
  EXPECT_EQ(model.obstacle_laws[1].mu, 0.7) << "unset: follows the scene's";
  // The force: a disc resting 1 mm deep on each top face, at rest, feels
  // k·d of its obstacle's own k (Kelvin–Voigt at v = 0 is k·d too).
  for (size_t i = 0; i < 2; ++i) {
    const double x = i == 0 ? 0.0 : 3.0;
    const Vec3 q(x, 2.05 + scene.radius - 1e-3, 0.0);
    const Vec3 a = acceleration(model, q, Vec3::Zero());
    const double fn = (a.y() + model.gravity) * scene.mass;
    EXPECT_NEAR(fn, model.obstacle_laws[i].k * 1e-3, 1e-9 * model.obstacle_laws[i].k) << i;
  }
}

struct BadObstacle {
  const char* toml;
  const char* expected;  // part of the one-line message
};

class ObstacleSceneFileErrors : public ::testing::TestWithParam<BadObstacle> {};

TEST_P(ObstacleSceneFileErrors, NameTheKeyAndTheRange) {
  const std::string text = std::string("scene = \"circle\"\n") + GetParam().toml;
  try {
    parse_scene(text, "bad.toml");
    FAIL() << "accepted: " << GetParam().toml;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ObstacleSceneFileErrors,
    ::testing::Values(
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = -1\nheight = 1\n",
                    "obstacle[0].width = -1 is out of range: must be in (0, 1e6] m"},
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = inf\nheight = 1\n",
                    "obstacle[0].width = inf is out of range"},
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = nan\ny = 0\nwidth = 1\nheight = 1\n",
                    "obstacle[0].x = nan is out of range: must be finite"},
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = 1\n",
                    "obstacle[0].height is required"},
        BadObstacle{
            "[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = 1\nheight = 1\nradius = 2\n",
            "unknown key 'obstacle[0].radius' (allowed here: type, x, y, width, height, k, c, mu, "
            "alpha, mu_roll, mu_torsion, damping)"},
        BadObstacle{"[[obstacle]]\nx = 0\n", "obstacle[0].type is required"},
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = 1\nheight = 1\nk = -5\n",
                    "obstacle[0].k = -5 is out of range: must be in [0, 1e12] N/m"},
        BadObstacle{
            "[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = 1\nheight = 1\nalpha = 0\n",
            "obstacle[0].alpha = 0 is out of range: must be in (0, 1e9] s/m"},
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = 1\nheight = 1\n"
                    "damping = \"soft\"\n",
                    "obstacle[0].damping = \"soft\" is not a damping law"},
        BadObstacle{"[[obstacle]]\ntype = \"circle\"\n",
                    "obstacle[0].type = \"circle\" is not an obstacle type"},
        BadObstacle{
            "[[obstacle]]\ntype = \"segment\"\nx1 = 0\ny1 = 0\nx2 = 1\ny2 = 1\nradius = -0.1\n",
            "obstacle[0].radius = -0.1 is out of range: must be in [0, 1e3] m"},
        BadObstacle{
            "[[obstacle]]\ntype = \"segment\"\nx1 = 1\ny1 = 1\nx2 = 1\ny2 = 1\n",
            "obstacle[0].radius = 0 is out of range: must be > 0 when the two ends coincide"},
        BadObstacle{"[[obstacle]]\ntype = \"segment\"\nx1 = \"a\"\n",
                    "obstacle[0].x1 must be a number"},
        BadObstacle{"obstacle = 3\n", "obstacle must be an array of tables"},
        BadObstacle{"[[obstacle]]\ntype = \"box\"\nx = 0\ny = 0\nwidth = 1\nheight = 1\n"
                    "[[obstacle]]\ntype = \"box\"\nx = 0\ny = 2e6\nwidth = 1\nheight = 1\n",
                    "obstacle[1].y = 2e+06 is out of range: must be finite, |y| <= 1e6 m"}));

}  // namespace
}  // namespace contact2d
