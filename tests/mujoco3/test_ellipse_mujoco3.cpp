// The ellipse in MuJoCo 3.14 (the engine mujoco3): its contacts with the
// ground, read where the engine can read them, and its trajectory against
// MuJoCo 2.2.2.
//
// The engine's stepper returns qpos and qvel only (driver.mjs "step"), not
// MuJoCo's contacts; the driver's "state" op (mujoco3::read_model_state,
// what `contact2d inspect --engine mujoco3` reads) returns every contact of
// a model at a keyframe. So 3.14 is stepped through the driver, states of
// its own trajectory are written as keyframes of the same model, and each is
// read back: the contacts MuJoCo 3.14 makes at that configuration.
//
// Expected: one contact at most, at the reference's support point, as on
// 2.2.2 (tests/mujoco/test_ellipse_mujoco.cpp says why and derives the
// bound kEllipseGeometry). The plane–ellipsoid pair is mjc_PlaneConvex on every
// 3.x tag of MuJoCo's repository (3.0.0–3.12.0 and main at 3.12.1): an
// ellipsoid gets its support point and no more. 3.10 turned multiccd on by
// default (mjDSBL_MULTICCD is now a disable bit), but that is mjc_Convex's,
// which a plane does not use (and mjc_Convex skips it for ellipsoids); this
// test is what says 3.14 still makes one.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/ellipse.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;

constexpr double kEllipseGeometry = 1e-14;  // m: test_ellipse_mujoco.cpp's kEllipseGeometry

// The thrown ellipse of tests/mujoco (test::drop_scene(Shape::Ellipse, 20,
// 0.5)) for 1 s: it lands at 0.306 s, spins up, bounces and lands again.
Scene thrown_ellipse() {
  return parse_scene(
      "scene = \"ellipse\"\n[body]\nmass = 1.0\na = 0.2\nb = 0.1\n"
      "[contact]\nk = 1e4\nc = 20\nmu = 0.5\nalpha = 100\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.6\ntheta = 0.3\nvx = 0.5\nomega = 1.0\n"
      "[sim]\ndt = 1e-4\nduration = 1.0\n",
      "thrown ellipse");
}

std::string keyframe_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// 3.14 and 2.2.2 step the thrown ellipse side by side (the same MJCF but
// for the version's header, mujoco/mjcf.hpp); at states of 3.14's run,
// 3.14's own contacts (read through the driver's "state" op) are checked
// against the reference's support point, and their number against 2.2.2's
// at the same step. The runs are held to test_versions.cpp's floor,
// 1e-9 m: over this 1 s the scene magnifies a 1e-8 m change of its start
// only 1.36-fold (`contact2d compare`), far from the millimetres some
// scenes amplify rounding to; measured 1.2e-14 m at every step. Run time
// 1.4–1.7 s on a loaded 2-core machine (Node's start, 10⁴ steps on each
// version, ~70 states read at ~9 ms each).
TEST(Mujoco3Ellipse, OneGroundContactAtTheSupportPointAsOnMujoco222) {
  CONTACT2D_NEEDS_MUJOCO3();
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = thrown_ellipse();
  const long long steps = step_count(scene.sim);

  // 2.2.2: every step's qpos and contact count (of the configuration the
  // step starts from: mj_step collides, then integrates).
  const mujoco::ModelPtr m2 = mujoco::load_model(mujoco::generate_mjcf(scene, {}).xml, "2.2.2");
  const mujoco::DataPtr d2 = mujoco::make_data(m2.get());
  mj_resetDataKeyframe(m2.get(), d2.get(), 0);
  const int nq = m2->nq;
  ASSERT_EQ(nq, 3);
  std::vector<double> qpos2;  // before each step
  std::vector<int> ncon2;
  for (long long i = 0; i < steps; ++i) {
    qpos2.insert(qpos2.end(), d2->qpos, d2->qpos + nq);
    mj_step(m2.get(), d2.get());
    ncon2.push_back(d2->ncon);
  }

  // 3.14 through the driver: the qpos before each step (the initial state,
  // then the states after steps 1 … n − 1).
  mujoco::MjcfOptions options;
  options.version = mujoco::Version::V3;
  const std::string xml3 = mujoco::generate_mjcf(scene, options).xml;
  const auto node = mujoco3::Node::of_this_thread();
  const mujoco3::LoadedModel loaded = node->load(xml3, "3.14");
  ASSERT_EQ(loaded.nq, nq);
  std::vector<double> qpos_init(qpos2.begin(), qpos2.begin() + nq);
  const Vec3& v = scene.initial.v;
  node->reset(loaded.id, qpos_init, {v.x(), v.y(), v.z()});
  std::vector<double> batch;
  bool bad = false;
  ASSERT_EQ(node->step(loaded.id, static_cast<int>(steps - 1), loaded.nq + loaded.nv, batch, bad),
            steps - 1);
  node->free(loaded.id);
  ASSERT_FALSE(bad);
  const size_t width = 2 * static_cast<size_t>(nq);
  auto qpos3 = [&](long long i) {
    return i == 0 ? qpos_init.data() : batch.data() + width * static_cast<size_t>(i - 1);
  };

  double version_gap = 0.0;
  for (long long i = 0; i < steps; ++i) {
    const double* a = qpos3(i);
    const double* b = qpos2.data() + nq * i;
    version_gap =
        std::max({version_gap, std::hypot(a[0] - b[0], a[1] - b[1]), std::abs(a[2] - b[2])});
  }

  // The states read back: the last step before and the first after each
  // change of 2.2.2's contact count (touch-down and lift-off, where a second
  // contact or a missing one would show first), every 20th step in contact
  // and every 500th in flight: 3 impacts of ~280 steps in contact each.
  std::vector<long long> picked;
  for (long long i = 0; i < steps; ++i) {
    const bool change =
        (i > 0 && ncon2[i] != ncon2[i - 1]) || (i + 1 < steps && ncon2[i] != ncon2[i + 1]);
    if (change || i % (ncon2[i] > 0 ? 20 : 500) == 0) picked.push_back(i);
  }
  const double stepped =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::string keys;
  for (long long i : picked) {
    const double* q = qpos3(i);
    keys += "<key name=\"s" + std::to_string(i) + "\" qpos=\"" + keyframe_number(q[0]) + " " +
            keyframe_number(q[1]) + " " + keyframe_number(q[2]) + "\"/>\n";
  }
  std::string with_keys = xml3;
  const size_t end_keys = with_keys.find("</keyframe>");
  ASSERT_NE(end_keys, std::string::npos);
  with_keys.insert(end_keys, keys);
  const fs::path path =
      fs::temp_directory_path() / ("contact2d_ellipse3_" + std::to_string(::getpid()) + ".xml");
  {
    std::ofstream out(path);
    out << with_keys;
  }

  const double x0 = m2->body_pos[3], y0 = m2->body_pos[5];
  int max_ncon = 0, contact_states = 0, wrong = 0, differs_from_222 = 0;
  double depth_error = 0.0, position_error = 0.0, normal_error = 0.0;
  std::string version;
  for (long long i : picked) {
    mujoco::StateRequest request;
    request.path = path.string();
    request.key = "s" + std::to_string(i);
    const mujoco::ModelState state = mujoco3::read_model_state(request);
    version = state.version;
    const double* q = qpos3(i);
    const Vec2 r = ellipse_lowest_point(scene.a, scene.b, q[2]);
    const double depth = -(y0 + q[1] + r.y());
    const int ncon = static_cast<int>(state.contacts.size());
    max_ncon = std::max(max_ncon, ncon);
    if (ncon > 0) ++contact_states;
    if (ncon > 1 || (depth > kEllipseGeometry && ncon != 1) ||
        (depth < -kEllipseGeometry && ncon != 0)) {
      if (wrong++ == 0)
        ADD_FAILURE() << "step " << i << ": " << ncon << " contacts at depth " << depth << " m";
    }
    if (ncon != ncon2[static_cast<size_t>(i)]) ++differs_from_222;
    for (const mujoco::StateContact& c : state.contacts) {
      EXPECT_EQ(state.geom_names.at(static_cast<size_t>(c.geom1)), "ground");
      EXPECT_EQ(state.geom_names.at(static_cast<size_t>(c.geom2)), "ellipse");
      depth_error = std::max(depth_error, std::abs(c.dist + depth));
      position_error = std::max({position_error, std::abs(c.pos[0] - (x0 + q[0] + r.x())),
                                 std::abs(c.pos[1]), std::abs(c.pos[2] + 0.5 * depth)});
      normal_error = std::max({normal_error, std::abs(c.normal[0]), std::abs(c.normal[1]),
                               std::abs(c.normal[2] - 1.0)});
    }
  }
  fs::remove(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "  MuJoCo %s: %zu states read, %d with a contact, max ncon %d; |dist - ref| %.2g m, "
      "|pos - ref| %.2g m, |normal - z| %.2g; 2.2.2 <-> 3.14 %.3g m over %lld steps (%.2f s, "
      "of which stepping %.2f s)\n",
      version.c_str(), picked.size(), contact_states, max_ncon, depth_error, position_error,
      normal_error, version_gap, steps, seconds, stepped);
  EXPECT_EQ(max_ncon, 1);
  EXPECT_GT(contact_states, 40);  // it does land, bounce and land again
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(differs_from_222, 0);
  EXPECT_LE(depth_error, kEllipseGeometry);
  EXPECT_LE(position_error, kEllipseGeometry);
  EXPECT_LE(normal_error, kEllipseGeometry);
  EXPECT_LE(version_gap, 1e-9);
}

}  // namespace
}  // namespace contact2d
