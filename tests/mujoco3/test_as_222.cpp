// MuJoCo 3 read and reported as MuJoCo 2.2.2 is (issue 49, section 4): the
// same steps found bad, the same contacts listed, one Node per worker, and
// only the steps taken reported.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <string>

#include "analysis/engine.hpp"
#include "core/stepper.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3/stepper.hpp"
#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

// The first step that is NonFinite (0: none in `limit`).
template <typename S>
long long first_bad_step(S& stepper, long long limit) {
  for (long long i = 1; i <= limit; ++i) {
    if (stepper.step() == StepStatus::NonFinite) return i;
  }
  return 0;
}

Scene pushed_point_mass() {
  return parse_scene(
      "scene = \"point_mass\"\n[body]\nmass = 1\nhalf_height = 0.02\n"
      "[contact]\nk = 3e4\nc = 40\nalpha = 150\nmu = 0.5\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.4\n[sim]\ndt = 2e-4\nduration = 1\n",
      "test scene");
}

// A force of 1e11 N on 1 kg: |qacc| = 1e11 > mjMAXVAL at once, while qvel
// grows by 2e7 m/s a step and stays below 1e10 for 500 steps. 2.2.2 finds
// the first step bad (mjWARN_BADQACC); MuJoCo 3 found step 500 (|qvel| only).
TEST(As222, BadAccelerationIsTheSameStep) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Scene scene = pushed_point_mass();
  const Vec3 push(1e11, 0.0, 0.0);
  mujoco::MujocoStepper v2(scene, mujoco::MjcfOptions{});
  v2.set_applied(push);
  mujoco3::Mujoco3Stepper v3(scene, mujoco::MjcfOptions{});
  v3.set_applied(push);
  v3.plan(2000);
  EXPECT_EQ(first_bad_step(v2, 2000), 1);
  EXPECT_EQ(first_bad_step(v3, 2000), 1);
}

// A bad position or speed is MuJoCo's mj_checkPos/mj_checkVel at the start
// of the next step on both versions: the same step, under Euler and RK4
// (whose qacc after the step is not the one MuJoCo tested).
TEST(As222, BadSpeedIsTheSameStep) {
  CONTACT2D_NEEDS_MUJOCO3();
  for (const Integrator integrator : {Integrator::SemiImplicitEuler, Integrator::RK4}) {
    Scene scene = pushed_point_mass();
    scene.sim.integrator = integrator;
    // Upwards, clear of the ground: qacc 2e9, |qpos| = 40·n² passes 1e10 after
    // step 15,811 (qvel at 25,000); mj_checkPos finds it in the next (RK4's
    // stages one step later).
    const Vec3 push(0.0, 2e9, 0.0);
    mujoco::MujocoStepper v2(scene, mujoco::MjcfOptions{});
    v2.set_applied(push);
    mujoco3::Mujoco3Stepper v3(scene, mujoco::MjcfOptions{});
    v3.set_applied(push);
    v3.plan(30000);
    const long long a = first_bad_step(v2, 30000);
    EXPECT_GE(a, 15812) << integrator_name(integrator);
    EXPECT_LE(a, 15813) << integrator_name(integrator);
    EXPECT_EQ(first_bad_step(v3, 30000), a) << integrator_name(integrator);
  }
}

// What agrees between the versions' lists of one model's contacts: the
// count, each contact's geoms, condim, friction, solref and solimp exactly,
// dist within `dist_tol` m and, where the model's masses agree, A and the
// normal force within relative 1e-6 and 1e-5. `masses`: false for the mug,
// whose mass differs by design (docs/mujoco.md, "One model on both
// versions": the mesh volume); its depths then differ too (4e-8 m).
// `path3`: the file 3.14 reads, when not `path`.
void expect_same_contacts(const std::string& path, double settle, double dist_tol, bool masses,
                          const std::string& path3 = {}) {
  mujoco::StateRequest request;
  request.path = path;
  request.settle = settle;
  const mujoco::ModelState a = mujoco::read_model_state(request);
  if (!path3.empty()) request.path = path3;
  const mujoco::ModelState b = mujoco3::read_model_state(request);
  ASSERT_EQ(a.contacts.size(), b.contacts.size()) << path;
  for (size_t i = 0; i < a.contacts.size(); ++i) {
    const mujoco::StateContact& x = a.contacts[i];
    const mujoco::StateContact& y = b.contacts[i];
    const std::string at = path + " contact " + std::to_string(i);
    EXPECT_EQ(x.geom1, y.geom1) << at;
    EXPECT_EQ(x.geom2, y.geom2) << at;
    EXPECT_EQ(x.condim, y.condim) << at;
    for (size_t k = 0; k < 5; ++k) EXPECT_EQ(x.friction[k], y.friction[k]) << at;
    for (size_t k = 0; k < 2; ++k) EXPECT_EQ(x.solref[k], y.solref[k]) << at;
    for (size_t k = 0; k < 5; ++k) EXPECT_EQ(x.solimp[k], y.solimp[k]) << at;
    EXPECT_NEAR(x.dist, y.dist, dist_tol) << at;
    if (!masses) continue;
    EXPECT_NEAR(x.A, y.A, 1e-6 * std::abs(x.A)) << at;
    EXPECT_NEAR(x.force, y.force, 1e-5 * std::abs(x.force) + 1e-9) << at;
  }
}

// Two spheres on a plane, both detected by their pairs, one within its gap
// (dist 0.05 m, active only within 0.02 m): that one is no contact of the
// constraint problem (exclude 1), and neither version lists it. The
// versions read margin and gap differently (docs/mujoco.md, "One model on
// both versions"): 2.2.2 detects within the margin (0.1) and makes active
// within margin − gap; 3.x detects within margin + gap and makes active
// within the margin (0.02).
std::string gap_model(double margin, double gap) {
  const std::string pair =
      "margin=\"" + std::to_string(margin) + "\" gap=\"" + std::to_string(gap) + "\"/>\n";
  return "<mujoco>\n  <worldbody>\n"
         "    <geom name=\"floor\" type=\"plane\" size=\"5 5 0.1\"/>\n"
         "    <body pos=\"0 0 0.11\"><freejoint/><geom name=\"a\" type=\"sphere\" "
         "size=\"0.1\"/></body>\n"
         "    <body pos=\"1 0 0.15\"><freejoint/><geom name=\"b\" type=\"sphere\" "
         "size=\"0.1\"/></body>\n"
         "  </worldbody>\n  <contact>\n"
         "    <pair geom1=\"floor\" geom2=\"a\" " +
         pair + "    <pair geom1=\"floor\" geom2=\"b\" " + pair + "  </contact>\n</mujoco>\n";
}

TEST(As222, ContactsInAGapAreListedByNeither) {
  CONTACT2D_NEEDS_MUJOCO3();
  namespace fs = std::filesystem;
  const std::string stem = "contact2d_as222_gap_" + std::to_string(getpid());
  const fs::path v2 = fs::temp_directory_path() / (stem + "_v2.xml");
  const fs::path v3 = fs::temp_directory_path() / (stem + "_v3.xml");
  std::ofstream(v2) << gap_model(0.1, 0.08);
  std::ofstream(v3) << gap_model(0.02, 0.08);
  mujoco::StateRequest request;
  request.path = v2.string();
  EXPECT_EQ(mujoco::read_model_state(request).contacts.size(), 1U);
  request.path = v3.string();
  EXPECT_EQ(mujoco3::read_model_state(request).contacts.size(), 1U);
  expect_same_contacts(v2.string(), 0.0, 1e-12, true, v3.string());
  fs::remove(v2);
  fs::remove(v3);
}

TEST(As222, DebianSamplesListTheSameContacts) {
  CONTACT2D_NEEDS_MUJOCO3();
  const std::string humanoid = "/usr/share/mujoco/model/humanoid/humanoid.xml";
  const std::string mug = "/usr/share/mujoco/model/mug/mug.xml";
  if (!std::filesystem::exists(humanoid) || !std::filesystem::exists(mug))
    FAIL() << "Debian's MuJoCo samples are missing (libmujoco-samples): scripts/setup";
  // At qpos0 neither version has a contact in the problem (2.2.2's reader
  // listed 3 contacts left out of it for one of the two before).
  expect_same_contacts(humanoid, 0.0, 1e-12, true);
  expect_same_contacts(mug, 0.0, 1e-12, false);
  // Settled 1 s: the humanoid's 6 foot contacts (dist within 6.4e-11 m, A
  // 2.3e-8 and the force 1.7e-7 relative, measured), the mug's 3.
  expect_same_contacts(humanoid, 1.0, 1e-9, true);
  expect_same_contacts(mug, 1.0, 1e-7, false);
  mujoco::StateRequest request;
  request.path = humanoid;
  request.settle = 1.0;
  EXPECT_EQ(mujoco::read_model_state(request).contacts.size(), 6U);
}

// The Node processes of the threads that ran `tasks` tasks in parallel_for
// (each loads a model and steps it).
std::set<int> nodes_of_parallel_for(size_t tasks) {
  const Scene scene = pushed_point_mass();
  std::mutex mutex;
  std::set<int> pids;
  analysis::parallel_for(tasks, 2, [&](size_t) {
    mujoco3::Mujoco3Stepper stepper(scene, mujoco::MjcfOptions{});
    stepper.step();
    const int pid = mujoco3::Node::of_this_thread()->pid();
    const std::lock_guard<std::mutex> lock(mutex);
    pids.insert(pid);
  });
  return pids;
}

// parallel_for starts threads on every call; their Nodes outlive them, so
// a second and third call start none (before: one per worker and call).
TEST(As222, NodeStartsOncePerWorker) {
  CONTACT2D_NEEDS_MUJOCO3();
  const std::set<int> first = nodes_of_parallel_for(8);
  const long starts = mujoco3::Node::starts();
  for (int call = 0; call < 2; ++call) {
    for (const int pid : nodes_of_parallel_for(8)) EXPECT_EQ(first.count(pid), 1U) << pid;
  }
  EXPECT_EQ(mujoco3::Node::starts(), starts);
}

// A planned run fetches its steps ahead in batches; what it reports is of
// the steps read. Pushed up at 2e9 m/s², qpos is bad after step 15,811:
// a run stopped at step 100 has no bad-number warning (before: the batch's
// 15,812 steps had raised mjWARN_BADQPOS), and goes on as one that never
// asked (the same state, bit for bit, at step 200).
TEST(As222, WarningsAreOfTheStepsTaken) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Scene scene = pushed_point_mass();
  const Vec3 push(0.0, 2e9, 0.0);
  mujoco3::Mujoco3Stepper ahead(scene, mujoco::MjcfOptions{});
  ahead.set_applied(push);
  ahead.plan(20000);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(ahead.step(), StepStatus::Ok);
  EXPECT_TRUE(ahead.warnings().empty()) << ahead.warnings().front();
  mujoco3::Mujoco3Stepper plain(scene, mujoco::MjcfOptions{});
  plain.set_applied(push);
  for (int i = 0; i < 200; ++i) plain.step();
  for (int i = 0; i < 100; ++i) ahead.step();
  EXPECT_EQ(ahead.state().q, plain.state().q);
  EXPECT_EQ(ahead.state().v, plain.state().v);
  // The rest of the plan still runs to the bad step, and reports it there.
  EXPECT_EQ(first_bad_step(ahead, 20000), 15812 - 200);
  EXPECT_FALSE(ahead.warnings().empty());
}

// Batched steps are the steps one at a time, bit for bit, across the
// rewinds a changed applied force makes (docs/mujoco3.md): one stepper
// planned 3000 steps ahead, the force changed at steps 700 and 1900 (each
// time a rewind to the step read), against one fetching a single step per
// request; a box dropped on its corners, contacts on and off.
TEST(As222, BatchedStepsAreTheSingleStepsBitForBit) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Scene scene = parse_scene(
      "scene = \"box\"\n[body]\nmass = 0.7\nwidth = 0.3\nheight = 0.12\n"
      "[contact]\nk = 3e4\nc = 40\nalpha = 150\nmu = 0.5\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.25\ntheta = -0.5\nvx = 0.8\nomega = -3\n[sim]\ndt = 2e-4\n"
      "duration = 1\n",
      "test scene");
  mujoco3::Mujoco3Stepper batched(scene, mujoco::MjcfOptions{});
  mujoco3::Mujoco3Stepper single(scene, mujoco::MjcfOptions{});
  batched.plan(3000);
  for (int i = 1; i <= 3000; ++i) {
    if (i == 700 || i == 1900) {
      const Vec3 push(i == 700 ? 3.0 : -1.0, 2.0, 0.1);
      batched.set_applied(push);
      single.set_applied(push);
      batched.plan(3000 - i + 1);
    }
    single.plan(1);
    ASSERT_EQ(batched.step(), StepStatus::Ok) << i;
    ASSERT_EQ(single.step(), StepStatus::Ok) << i;
    ASSERT_EQ(batched.state().q, single.state().q) << "step " << i;
    ASSERT_EQ(batched.state().v, single.state().v) << "step " << i;
  }
}

// A stepper's warnings are its own, though every stepper on a thread shares
// its Node: one run pushed to a bad acceleration at step 1 beside a quiet
// one, stepped in turn. (MuJoCo 3's WebAssembly build counts the warning
// but prints nothing while stepping, measured: what each request printed
// goes to the stepper that asked, stepper.cpp's collect_messages.)
TEST(As222, WarningsArePerStepper) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Scene scene = pushed_point_mass();
  mujoco3::Mujoco3Stepper loud(scene, mujoco::MjcfOptions{});
  loud.set_applied(Vec3(1e11, 0.0, 0.0));
  mujoco3::Mujoco3Stepper quiet(scene, mujoco::MjcfOptions{});
  loud.plan(50);
  quiet.plan(50);
  for (int i = 0; i < 50; ++i) {
    loud.step();
    quiet.step();
  }
  const std::vector<std::string> said = loud.warnings();
  EXPECT_TRUE(std::any_of(said.begin(), said.end(), [](const std::string& w) {
    return w.find("QACC") != std::string::npos;
  })) << (said.empty() ? "no warnings" : said.front());
  const std::vector<std::string> none = quiet.warnings();
  EXPECT_TRUE(none.empty()) << none.front();
}

}  // namespace
}  // namespace contact2d
