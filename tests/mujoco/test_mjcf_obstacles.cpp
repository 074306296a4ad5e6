// Obstacles in the MJCF (issue 14): the game's pitch loads in MuJoCo without
// a warning (load_model throws on any), with one world geom per obstacle,
// each touched through one explicit pair carrying the obstacle's own law.
#include <gtest/gtest.h>

#include <tinyxml2.h>

#include <string>

#include "game/pitch.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d {
namespace {

TEST(MjcfObstacles, ThePitchLoadsWithOneGeomAndOnePairPerObstacle) {
  const game::Pitch pitch = game::default_pitch();
  const Scene& scene = pitch.scene;
  const mujoco::GeneratedModel generated =
      mujoco::generate_mjcf(scene, mujoco::mjcf_options("", "", pitch.path));
  const mujoco::ModelPtr model = mujoco::load_model(generated.xml, "pitch");
  const mjModel* m = model.get();
  ASSERT_EQ(scene.obstacles.size(), 3u);
  // Geoms: the ground, the obstacles, the ball's disc.
  EXPECT_EQ(m->ngeom, 1 + static_cast<int>(scene.obstacles.size()) + 1);
  EXPECT_EQ(m->npair, static_cast<int>(scene.obstacles.size())) << "one pair per obstacle";
  const double a_hat = m->body_invweight0[2];
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const std::string name = "obstacle" + std::to_string(i);
    const int g = mj_name2id(m, mjOBJ_GEOM, name.c_str());
    ASSERT_GE(g, 0) << name;
    EXPECT_EQ(m->geom_bodyid[g], 0) << "static: in the world body";
    EXPECT_EQ(m->geom_type[g], mjGEOM_BOX);
    EXPECT_EQ(m->geom_contype[g], 0) << "touched through its pair only";
    const Obstacle& o = scene.obstacles[i];
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g + 0], 0.5 * (o.b.x() - o.a.x()));
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g + 2], 0.5 * (o.b.y() - o.a.y()));
    EXPECT_DOUBLE_EQ(m->geom_pos[3 * g + 0], 0.5 * (o.a.x() + o.b.x()));
    EXPECT_DOUBLE_EQ(m->geom_pos[3 * g + 2], 0.5 * (o.a.y() + o.b.y()));
    // The pair: solref = (−k·Â, −c·Â) of the obstacle's own law (n = 1 for
    // the disc), to the 17 digits written.
    int pair = -1;
    for (int p = 0; p < m->npair; ++p) {
      if (m->pair_geom1[p] == g || m->pair_geom2[p] == g) pair = p;
    }
    ASSERT_GE(pair, 0) << name;
    const ContactParams law = o.contact.apply(scene.contact);
    EXPECT_NEAR(m->pair_solref[2 * pair + 0], -law.k * a_hat, 1e-15 * law.k * a_hat) << name;
    EXPECT_NEAR(m->pair_solref[2 * pair + 1], -law.c * a_hat, 1e-15 * law.c * a_hat) << name;
    EXPECT_EQ(m->pair_friction[5 * pair + 0], law.mu) << name;
    EXPECT_EQ(m->pair_dim[pair], mujoco::contact_condim(law)) << name;
  }
  // The crossbar keeps the scene's law, the net (roof, back) has its own.
  EXPECT_FALSE(scene.obstacles[0].contact.any());
  EXPECT_TRUE(scene.obstacles[2].contact.any());
  EXPECT_NE(generated.xml.find("obstacle2 (box, own law): k 2000 N/m"), std::string::npos)
      << "the header states each obstacle's law";
}

TEST(MjcfObstacles, ASegmentIsACapsuleAndAPostASphere) {
  Scene scene = default_scene(Shape::Circle);
  scene.obstacles = {make_segment_obstacle(Vec2(1.0, 0.5), Vec2(2.0, 0.8), 0.05),
                     make_segment_obstacle(Vec2(3.0, 0.5), Vec2(3.0, 0.5), 0.05)};
  const mujoco::GeneratedModel generated =
      mujoco::generate_mjcf(scene, mujoco::mjcf_options("", "", ""));
  const mujoco::ModelPtr model = mujoco::load_model(generated.xml, "segments");
  const mjModel* m = model.get();
  EXPECT_EQ(m->geom_type[mj_name2id(m, mjOBJ_GEOM, "obstacle0")], mjGEOM_CAPSULE);
  EXPECT_EQ(m->geom_type[mj_name2id(m, mjOBJ_GEOM, "obstacle1")], mjGEOM_SPHERE);
  EXPECT_EQ(m->npair, 2);
}

}  // namespace
}  // namespace contact2d
