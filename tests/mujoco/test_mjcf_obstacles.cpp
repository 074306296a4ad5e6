// Obstacles in the MJCF: the game's pitch loads in MuJoCo without
// a warning (load_model throws on any), with one geom per obstacle (in the
// world body, or for the moving keeper at the origin of its mocap body),
// each touched through one explicit pair carrying the obstacle's own law.
#include <gtest/gtest.h>

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/compare_run.hpp"
#include "core/format.hpp"
#include "game/pitch.hpp"
#include "mj_test_util.hpp"
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
  ASSERT_EQ(scene.obstacles.size(), 4u);
  EXPECT_EQ(m->nmocap, 1) << "the keeper";
  EXPECT_EQ(m->body_mocapid[1], -1) << "the ball stays body 1";
  // Geoms: the ground, the obstacles, the ball's disc.
  EXPECT_EQ(m->ngeom, 1 + static_cast<int>(scene.obstacles.size()) + 1);
  EXPECT_EQ(m->npair, static_cast<int>(scene.obstacles.size())) << "one pair per obstacle";
  const double a_hat = m->body_invweight0[2];
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const std::string name = "obstacle" + std::to_string(i);
    const int g = mj_name2id(m, mjOBJ_GEOM, name.c_str());
    ASSERT_GE(g, 0) << name;
    const Obstacle& o = scene.obstacles[i];
    const int body = m->geom_bodyid[g];
    // Where the obstacle's centre is: the geom's own position in the world
    // body, or its mocap body's (the geom at its origin).
    const mjtNum* centre = m->geom_pos + 3 * g;
    if (o.moves) {
      EXPECT_GE(m->body_mocapid[body], 0) << name << ": moving: a mocap body";
      EXPECT_EQ(m->body_parentid[body], 0) << name;
      EXPECT_EQ(m->geom_pos[3 * g + 0], 0.0) << name;
      EXPECT_EQ(m->geom_pos[3 * g + 2], 0.0) << name;
      centre = m->body_pos + 3 * body;
    } else {
      EXPECT_EQ(body, 0) << name << ": static: in the world body";
    }
    EXPECT_EQ(m->geom_type[g], mjGEOM_BOX);
    EXPECT_EQ(m->geom_contype[g], 0) << "touched through its pair only";
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g + 0], 0.5 * (o.b.x() - o.a.x()));
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g + 2], 0.5 * (o.b.y() - o.a.y()));
    EXPECT_DOUBLE_EQ(centre[0], 0.5 * (o.a.x() + o.b.x()));
    EXPECT_DOUBLE_EQ(centre[2], 0.5 * (o.a.y() + o.b.y()));
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
  // The crossbar and the keeper keep the scene's law, the net (roof, back)
  // has its own.
  EXPECT_FALSE(scene.obstacles[0].contact.any());
  EXPECT_FALSE(scene.obstacles[3].contact.any());
  EXPECT_TRUE(scene.obstacles[2].contact.any());
  EXPECT_NE(generated.xml.find("obstacle2 (box, own law): k 2000 N/m"), std::string::npos)
      << "the header states each obstacle's law";
}

// The value printed after `label` in the header.
double value_after(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  EXPECT_NE(at, std::string::npos) << label;
  return at == std::string::npos ? NAN : std::stod(text.substr(at + label.size()));
}

// The header's per-obstacle lines and the values that obstacles change,
// recomputed from their formulas (as tests/mujoco/test_mjcf_header.cpp does
// for the built-in scenes): each obstacle's law and solref = (−k·Â/n,
// −c·Â/n), impratio from the largest c (the net's 150 N·s/m, not the
// ground's 60), N and nconmax = 2·P·(1 + N) + 40.
TEST(MjcfObstacles, TheHeaderStatesEachObstaclesValues) {
  const game::Pitch pitch = game::default_pitch();
  const Scene& scene = pitch.scene;
  const std::string xml =
      mujoco::generate_mjcf(scene, mujoco::mjcf_options("", "", pitch.path)).xml;
  const std::string h = xml.substr(0, xml.find("-->"));
  const mujoco::ModelPtr model = mujoco::load_model(xml, "pitch");
  const double a_hat = model->body_invweight0[2];
  EXPECT_EQ(value_after(h, "A = body_invweight0 = "), a_hat);
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const Obstacle& o = scene.obstacles[i];
    const ContactParams law = o.contact.apply(scene.contact);
    const std::string line = h.substr(h.find("    obstacle" + std::to_string(i) + " ("));
    EXPECT_EQ(value_after(line, "k "), law.k) << i;
    EXPECT_EQ(value_after(line, "c "), law.c) << i;
    EXPECT_EQ(line.find(law.damping == DampingLaw::KelvinVoigt ? "damping kelvin_voigt"
                                                               : "damping compression"),
              line.find("damping "))
        << i;
    const double k_printed = value_after(line, "solref = (");
    const double c_printed =
        value_after(line, "solref = (" + mujoco::format_exact(k_printed) + ", ");
    EXPECT_NEAR(k_printed, -law.k * a_hat, 1e-15 * law.k * a_hat) << i;
    EXPECT_NEAR(c_printed, -law.c * a_hat, 1e-15 * law.c * a_hat) << i;
  }
  const double c_max = 150.0;  // the net's (pitch.toml), above the ground's 60
  EXPECT_NE(h.find("with c = 150 N s/m, the largest"), std::string::npos);
  const double m = scene.mass, r = scene.radius, inertia = 0.5 * m * r * r;
  const double dt = scene.sim.dt, a_t = 1.0 / m + r * r / inertia;
  const double mu = scene.contact.mu, mu_roll = scene.contact.mu_roll;
  const double impratio =
      std::min(1.0 / (c_max * dt * a_t), inertia * (mu / mu_roll) * (mu / mu_roll) / (c_max * dt));
  EXPECT_NEAR(value_after(h, "mu_roll)^2/(c Δt)) = "), impratio, 1e-12 * impratio);
  EXPECT_EQ(value_after(h, "N = "), 4.0);
  EXPECT_EQ(value_after(h, "nconmax = 2 P (1 + N) + 40 = "), 2 * 1 * (1 + 4) + 40);
  EXPECT_EQ(model->nconmax, 2 * 1 * (1 + 4) + 40);
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

namespace contact2d {
namespace {

// A point mass (half_height 5 cm) slides without friction down a 30° slope
// made of a segment obstacle, the ground far below. Its 2D contact is the
// point (0, −h). The MJCF's point mass was a sphere of radius h about the
// COM: the same lowest point on flat ground, but on the slope it touched at
// the sphere's side, started 6.7 mm (h − h·cos 30°) inside the slope, was
// thrown up and ended 0.064 m from the reference. Now a sphere of ε = 1e-9 m
// at (0, ε − h): the engines agree to 8.7e-9 m (measured here), the order
// of ε and of the calibrated mapping's residual on a smooth slide; the
// bound, 1e-6 m, is 1e-5 of the old difference.
TEST(MjcfObstacles, APointMassTouchesASlopeAtItsContactPointInBothEngines) {
  const double s30 = 0.5, c30 = std::sqrt(3.0) / 2.0, h = 0.05;
  // The slope: a capsule of radius 0.05 m through (−1, 2) at −30°; the body
  // starts with its contact point on the capsule's surface at x = −0.5.
  const double x1 = -1.0, y1 = 2.0, x2 = x1 + 4.0 * c30, y2 = y1 - 4.0 * s30, r = 0.05;
  const double px = -0.5, surface = y1 - (px - x1) * s30 / c30 + r / c30;
  const std::string text =
      "scene = \"point_mass\"\n[body]\nmass = 1.0\nhalf_height = 0.05\n"
      "[contact]\nk = 1e5\nc = 400\nmu = 0.0\ndamping = \"kelvin_voigt\"\n"
      "[initial]\nx = " +
      format_shortest(px) + "\ny = " + format_shortest(surface + h) +
      "\n[sim]\ndt = 1e-4\nduration = 1.0\n"
      "[[obstacle]]\ntype = \"segment\"\nx1 = " +
      format_shortest(x1) + "\ny1 = " + format_shortest(y1) + "\nx2 = " + format_shortest(x2) +
      "\ny2 = " + format_shortest(y2) + "\nradius = " + format_shortest(r) + "\n";
  analysis::Comparison c = analysis::prepare_comparison(
      test::scene_from(text),
      analysis::comparison_engines({}, {}, 0.0, "slope.toml",
                                   [](std::string_view n) { return "--" + std::string(n); }));
  analysis::run_engines(c);
  analysis::measure(c, 1e-10, false);
  ASSERT_EQ(c.runs.size(), 2u);
  // It slid: g·sin 30° = 4.9 m/s² for 1 s is metres, so a body held still
  // or thrown off would not pass for a slide.
  const State& end = c.runs[0].run.trajectory.samples.back().state;
  EXPECT_GT(end.q.x() - px, 1.0);
  EXPECT_LT(c.runs[1].vs_first.max_pos, 1e-6);
}

}  // namespace
}  // namespace contact2d
