// `contact2d inspect` against MuJoCo itself, on three models written here by
// hand (not by contact2d's generator): a box on a plane with MuJoCo's
// defaults, a sphere whose contact comes from a default class and a <pair>
// override, and a two-body arm on hinges touching a wall. Each printed number
// is checked against a measurement in MuJoCo: the depth a settled body rests
// at, the speed a body rebounds with, the speed a body creeps at under a
// tilted gravity, the acceleration a known force gives the contact point.
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "benchmarks/impact.hpp"
#include "mujoco/inspect.hpp"
#include "mujoco/model.hpp"
#include "mujoco/solref_tool.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;
namespace mj = contact2d::mujoco;

constexpr double kPiInspect = 3.14159265358979323846;

// MuJoCo's defaults everywhere: solref 0.02 1, solimp 0.9 0.95 0.001 0.5 2,
// friction 1, condim 3, pyramidal cone, timestep 0.002, Euler. The box
// starts 0.1 mm into the plane so that its four bottom corners touch.
const char* kBoxModel = R"(<mujoco model="box on a plane">
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="box" pos="0 0 0.0999">
      <freejoint/>
      <geom name="box" type="box" size="0.1 0.1 0.1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
)";

// The ball's class sets solref, solimp, friction and priority; the <pair>
// with the floor overrides them (direct solref, flat solimp, condim 1), so
// the floor contact has k = 1e4 N/m and c = 20 N·s/m for m = 1 kg. The wall
// collides by default: the class's values win there (priority 1).
const char* kBallModel = R"(<mujoco model="ball with a class and a pair">
  <option timestep="0.0001"/>
  <default>
    <default class="ball">
      <geom solref="0.01 0.5" solimp="0.8 0.9 0.01" friction="0.7" priority="1" condim="4"/>
    </default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <geom name="wall" type="box" pos="1 0 0.5" size="0.05 2 0.5" solref="0.05 1" friction="0.2"/>
    <body name="ball" pos="0 0 0.0999">
      <freejoint/>
      <geom name="ball" class="ball" type="sphere" size="0.1" mass="1"/>
    </body>
  </worldbody>
  <contact>
    <pair geom1="ball" geom2="floor" condim="1" solref="-10000 -20" solimp="0.99 0.99 0.001"/>
  </contact>
  <keyframe>
    <key name="at_wall" qpos="0.8501 0 0.0999 1 0 0 0"/>
  </keyframe>
</mujoco>
)";

// Two links on hinges about z, straight along x; the fingertip (a sphere at
// x = 0.5) moves along y, toward the wall at y = 0.031 when the shoulder
// turns positive. Frictionless, flat impedance 0.5 (so that A ≠ Â shows in
// ω and ζ), standard solref 0.01 0.2.
const char* kArmModel = R"(<mujoco model="two-link arm and a wall">
  <option timestep="0.0001" gravity="0 0 0"/>
  <worldbody>
    <geom name="wall" type="plane" pos="0.25 0.031 0" zaxis="0 -1 0" size="1 1 0.1"
          condim="1" solref="0.01 0.2" solimp="0.5 0.5 0.001"/>
    <body name="upper">
      <joint name="shoulder" type="hinge" axis="0 0 1"/>
      <geom name="upper" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="1"
            condim="1" solref="0.01 0.2" solimp="0.5 0.5 0.001"/>
      <body name="fore" pos="0.3 0 0">
        <joint name="elbow" type="hinge" axis="0 0 1"/>
        <geom name="fore" type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="0.5"
              condim="1" solref="0.01 0.2" solimp="0.5 0.5 0.001"/>
        <geom name="tip" type="sphere" pos="0.2 0 0" size="0.03" mass="0.2"
              condim="1" solref="0.01 0.2" solimp="0.5 0.5 0.001"/>
      </body>
    </body>
  </worldbody>
  <keyframe>
    <key name="touch" qpos="0.0022 0"/>
  </keyframe>
</mujoco>
)";

class Inspect : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_inspect_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }

  mj::InspectReport report(const std::string& xml, const std::string& key = "",
                           std::optional<double> slope = std::nullopt, bool pairs = false,
                           double settle = 0.0, bool estimate = false) const {
    mj::InspectOptions o;
    o.path = write("model.xml", xml);
    o.key = key;
    o.slope = slope;
    o.pairs = pairs;
    o.settle = settle;
    o.estimate_loads = estimate;
    return mj::inspect(o);
  }

  struct Run {
    int status = -1;
    std::string out, err;
  };
  Run run(const std::string& args) const {
    const std::string out = (dir_ / "stdout").string(), err = (dir_ / "stderr").string();
    const std::string command = "cd '" + dir_.string() + "' && '" CONTACT2D_BINARY "' " + args +
                                " >'" + out + "' 2>'" + err + "'";
    const int raw = std::system(command.c_str());
    auto slurp = [](const std::string& path) {
      std::ifstream in(path);
      std::ostringstream s;
      s << in.rdbuf();
      return s.str();
    };
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
  }

  fs::path dir_;
};

// The model text compiled by MuJoCo, for the measurements.
struct Sim {
  mj::ModelPtr model;
  mj::DataPtr data;
  explicit Sim(const std::string& xml) : model(mj::load_model(xml, "test model")) {
    data = mj::make_data(model.get());
  }
  mjModel* m() const { return model.get(); }
  mjData* d() const { return data.get(); }
};

double mean_contact_depth(const Sim& s) {
  double sum = 0.0;
  for (int i = 0; i < s.d()->ncon; ++i) sum -= s.d()->contact[i].dist;
  return s.d()->ncon ? sum / s.d()->ncon : 0.0;
}

TEST_F(Inspect, BoxOnAPlaneWithDefaultsRestsAtThePrintedStaticPenetration) {
  // The least-squares estimate at qpos0 (the box 1e-4 m off its rest).
  const mj::InspectReport rep = report(kBoxModel, "", std::nullopt, false, 0.0, true);
  EXPECT_TRUE(rep.loads_estimated);
  ASSERT_EQ(rep.contacts.size(), 4u);
  EXPECT_TRUE(rep.balanced);
  EXPECT_EQ(rep.cone, "pyramidal");
  for (const mj::InspectRow& r : rep.contacts) {
    EXPECT_NEAR(r.load, 9.81 / 4.0, 1e-9);  // the minimum-norm share of the weight
    EXPECT_EQ(r.condim, 3);
    EXPECT_DOUBLE_EQ(r.solref[0], 0.02);
    // μ = 1, condim 3, impratio 1: φ = 1·2/2, the normal sees Â itself.
    EXPECT_DOUBLE_EQ(r.phi, 1.0);
    // A free box pushed at a corner along the normal: 1/m + |r × n|²/I with
    // r × n = (0.1, −0.1, 0) m and I = m·(0.2² + 0.2²)/12: 1 + 0.02/(0.08/12) = 4 1/kg,
    // four times MuJoCo's Â = 1/m.
    EXPECT_NEAR(r.A, 4.0, 1e-9);
    EXPECT_NEAR(r.inv_weight, 1.0, 1e-9);
  }
  Sim s(kBoxModel);
  for (int i = 0; i < 1500; ++i) mj_step(s.m(), s.d());  // 3 s: ζ = 1, ω ≈ 50 /s
  ASSERT_EQ(s.d()->ncon, 4);
  const double depth = mean_contact_depth(s);
  // Settled for 3 s (e^(−150) of the initial offset is left): measured
  // 8e-17 m apart, 8e-13 relative (the solver's residual and rounding of the
  // bisection); bound 1e-9 relative. A wrong load share (mg instead of mg/4)
  // or a wrong Â would move p by a factor of 2 or more.
  EXPECT_NEAR(depth, rep.contacts[0].penetration, 1e-9 * rep.contacts[0].penetration);
}

TEST_F(Inspect, SettledBoxCarriesMujocosForcesAndRestsAtThePrintedDepths) {
  // The user's way: --settle 3, MuJoCo's own forces as the loads.
  const mj::InspectReport rep = report(kBoxModel, "", std::nullopt, false, 3.0);
  EXPECT_TRUE(rep.at_rest);
  EXPECT_FALSE(rep.loads_estimated);
  EXPECT_GT(rep.settled, 0.0);
  EXPECT_LE(rep.settled, 3.0);
  ASSERT_EQ(rep.contacts.size(), 4u);
  double total = 0.0;
  for (const mj::InspectRow& r : rep.contacts) {
    total += r.load;
    EXPECT_DOUBLE_EQ(r.load, r.force);
    // The printed rest depth against the state's own: the settle stops once
    // |qvel| ≤ 0.01 and |qacc| ≤ 0.1, so the force is within ~1 % of g·m/4 of
    // the rest load; measured below; bound 2 % (the issue's target).
    EXPECT_NEAR(r.penetration, -r.dist, 0.02 * r.penetration);
  }
  // The four corners carry the weight (1 kg) to within the rest criterion's 1 % of g.
  EXPECT_NEAR(total, 9.81, 0.01 * 9.81);
}

// The box crept for 1 s on gravity tilted by θ, after 1 s to settle; returns
// (measured, printed averaged over the four corners).
std::pair<double, double> box_creep(const mj::InspectReport& rep, const std::string& xml,
                                    double theta) {
  double printed = 0.0;
  for (const mj::InspectRow& r : rep.contacts) printed += r.creep / 4.0;
  Sim s(xml);
  const double th = theta * kPiInspect / 180.0;
  s.m()->opt.gravity[0] = 9.81 * std::sin(th);
  s.m()->opt.gravity[2] = -9.81 * std::cos(th);
  for (int i = 0; i < 500; ++i) mj_step(s.m(), s.d());  // 1 s: the creep settles at ~2e3 /s
  const double x0 = s.d()->qpos[0];
  for (int i = 0; i < 500; ++i) mj_step(s.m(), s.d());
  return {(s.d()->qpos[0] - x0) / 1.0, printed};
}

TEST_F(Inspect, BoxCreepsOnATiltedGravityAtThePrintedSpeed) {
  const mj::InspectReport rep = report(kBoxModel, "", 10.0);
  ASSERT_EQ(rep.contacts.size(), 4u);
  const auto [measured, printed] = box_creep(rep, kBoxModel, 10.0);
  ASSERT_GT(printed, 0.0);
  // The printed speed gives every corner the same load share and d; on the
  // tilt the box's downhill corners carry more than its uphill ones (the
  // friction at the face against the weight at the centre, 0.1 m up), which
  // moves d(p) a little apart between them (solimp's x² start near d = 0.9).
  // Measured 3.6e-4 relative (0.000887500 against 0.000887819 m/s); bound
  // 2e-3. The (1 + μ²) of the pyramidal cone alone is a factor of 2.
  EXPECT_NEAR(measured, printed, 2e-3 * printed);
}

TEST_F(Inspect, BoxCreepsAtThePrintedSpeedInAnEllipticCone) {
  std::string xml = kBoxModel;
  xml.replace(xml.find("<worldbody>"), 11, "<option cone=\"elliptic\"/>\n  <worldbody>");
  const mj::InspectReport rep = report(xml, "", 10.0);
  ASSERT_EQ(rep.contacts.size(), 4u);
  EXPECT_EQ(rep.cone, "elliptic");
  const auto [measured, printed] = box_creep(rep, xml, 10.0);
  ASSERT_GT(printed, 0.0);
  // No (1 + μ²) here: half the pyramidal cone's speed. Same bound and reason
  // as the pyramidal case; measured 3.6e-4 relative (0.000443750 against
  // 0.000443909 m/s).
  EXPECT_NEAR(measured, printed, 2e-3 * printed);
}

// MuJoCo's noslip pass (noslip_iterations > 0) re-solves the friction forces
// after the main solver without their regulariser R_t, which is what sets the
// viscous creep: MuJoCo creeps far slower than the formula (measured with
// noslip 1 while writing this: 5.24e-5 m/s along the slope against the
// formula's 8.88e-4 for the same box without it, which MuJoCo meets:
// BoxCreepsOnATiltedGravityAtThePrintedSpeed).
// inspect and solref --model print no creep then and say why.
TEST_F(Inspect, NoCreepIsEstimatedUnderTheNoslipPass) {
  std::string xml = kBoxModel;
  xml.replace(xml.find("<worldbody>"), 11, "<option noslip_iterations=\"1\"/>\n  <worldbody>");
  const mj::InspectReport plain = report(kBoxModel, "", 10.0);
  const mj::InspectReport rep = report(xml, "", 10.0);
  ASSERT_EQ(rep.contacts.size(), 4u);
  const double measured = box_creep(rep, xml, 10.0).first;
  const double formula = plain.contacts[0].creep;
  ASSERT_GT(formula, 0.0);
  // The formula is 17× MuJoCo's speed here; bound: more than 2× off.
  EXPECT_LT(measured, 0.5 * formula);
  for (const mj::InspectRow& r : rep.contacts) {
    EXPECT_FALSE(std::isfinite(r.creep));
    EXPECT_EQ(r.creep_note.rfind("not estimated: noslip_iterations = 1 (", 0), 0u) << r.creep_note;
  }
  write("model.xml", xml);
  const Run json = run("inspect model.xml --slope 10 --json");
  EXPECT_EQ(json.status, 0) << json.err;
  EXPECT_NE(
      json.out.find("\"creep\": null, \"creep_note\": \"not estimated: noslip_iterations = 1"),
      std::string::npos)
      << json.out;
  const Run solref = run("solref --model model.xml --body box --k 20000 --c 30 --slope 10");
  EXPECT_EQ(solref.status, 0) << solref.err;
  EXPECT_NE(solref.out.find("not estimated: the model's noslip_iterations = 1"), std::string::npos)
      << solref.out;
}

TEST_F(Inspect, PyramidalCreepIsNotPrintedWhereAnEdgeUnloads) {
  // μ = 1, condim 3: each corner's edges carry f/4 ± f_t/2, one unloads at
  // tanθ = 1/2; beyond it the viscous closed form does not hold.
  const mj::InspectReport above = report(kBoxModel, "", 30.0);  // tan = 0.577
  ASSERT_EQ(above.contacts.size(), 4u);
  EXPECT_FALSE(std::isfinite(above.contacts[0].creep));
  EXPECT_NE(above.contacts[0].creep_note.find("an edge of the pyramidal cone unloads"),
            std::string::npos);
  EXPECT_TRUE(std::isfinite(report(kBoxModel, "", 25.0).contacts[0].creep));  // tan = 0.466
  // The formula evaluated by hand at 30° against MuJoCo: measured 0.00335
  // m/s against 0.00256, 31 % faster (bound: 10 %).
  const mj::InspectRow& r = above.contacts[0];
  const double th = 30.0 * kPiInspect / 180.0;
  const double p = mj::static_penetration(r.solimp, r.K, r.normal_weight, r.load * std::cos(th));
  const double d = mj::mujoco_impedance(r.solimp, -p);
  const double formula = r.load * std::sin(th) * (1 - d) * r.inv_weight * 2.0 / (r.B * d);
  EXPECT_GT(box_creep(above, kBoxModel, 30.0).first, 1.1 * formula);
}

TEST_F(Inspect, BallPairOverridesItsClassAndRestsAtThePrintedDepth) {
  const mj::InspectReport rep = report(kBallModel, "", std::nullopt, false, 3.0);
  ASSERT_EQ(rep.contacts.size(), 1u);
  const mj::InspectRow& r = rep.contacts[0];
  EXPECT_EQ(r.source, "explicit <pair>");
  EXPECT_EQ(r.condim, 1);
  EXPECT_DOUBLE_EQ(r.solref[0], -10000.0);
  EXPECT_NEAR(r.k, 1e4, 1e-6);  // A = Â = 1/m: k = d²·K·m = −solref[0]·m
  EXPECT_NEAR(r.c, 20.0, 1e-9);
  Sim s(kBallModel);
  for (int i = 0; i < 30000; ++i) mj_step(s.m(), s.d());  // 3 s at ζ = 0.1, ω = 100: e^(−30)
  ASSERT_EQ(s.d()->ncon, 1);
  // p = m·g·(1 − d)·Â/(K·d²) = 9.81e-6 m; measured 8e-17 m apart (9e-12
  // relative: e^(−30) of the initial 1e-4 m offset is 1e-17 m, and rounding);
  // bound 1e-9 relative.
  EXPECT_NEAR(-s.d()->contact[0].dist, r.penetration, 1e-9 * r.penetration);
  EXPECT_NEAR(r.penetration, 9.81 * 0.01 / 1e4, 1e-12);
}

// The ball dropped on the floor without gravity (the closed form has none)
// from 5 mm above at 1 m/s: its speed once the contact has ended.
double ball_rebound(const std::string& xml) {
  Sim s(xml);
  s.m()->opt.gravity[2] = 0.0;
  s.d()->qpos[2] = 0.105;
  s.d()->qvel[2] = -1.0;
  bool touched = false;
  for (int steps = 0; steps < 100000; ++steps) {
    mj_step(s.m(), s.d());
    if (s.d()->ncon > 0) touched = true;
    if (touched && s.d()->ncon == 0) return s.d()->qvel[2] / 1.0;
  }
  return std::nan("");
}

TEST_F(Inspect, BallReboundsWithThePrintedRestitution) {
  const mj::InspectReport rep = report(kBallModel);
  ASSERT_EQ(rep.contacts.size(), 1u);
  const double printed = rep.contacts[0].restitution;
  EXPECT_NEAR(rep.contacts[0].zeta, 0.1, 1e-9);
  const double measured = ball_rebound(kBallModel);
  // The closed form is the continuous oscillator; MuJoCo steps it with
  // semi-implicit Euler at ω·Δt = 0.01 (the contact lasts ~300 steps) and
  // lets go at a step boundary: an O(ω·Δt) error, measured 8.4e-4 (0.74324
  // against 0.74408); bound 2e-3. The unclamped formula exp(−ζπ/√(1 − ζ²))
  // = 0.7292 is 0.015 away.
  EXPECT_NEAR(measured, printed, 2e-3);
}

TEST_F(Inspect, BallReboundsWithThePrintedRestitutionUnderAndOverDamped) {
  // c = 100 and 300 N·s/m: ζ = 0.5 and 1.5 (the closed form's other branch).
  // The same O(ω·Δt) error of the step as at ζ = 0.1: measured −2.2e-3
  // (0.29624 against 0.29844) and −2.0e-3 (0.07358 against 0.07559) at the
  // model's Δt = 1e-4 s, +2.0e-4 and +6.6e-5 at Δt/4 (run once by hand), so
  // it is the step's and shrinks with it; bound 4e-3, twice the larger.
  for (const auto& [c, zeta] :
       {std::pair<const char*, double>{"-100", 0.5}, std::pair<const char*, double>{"-300", 1.5}}) {
    std::string xml = kBallModel;
    xml.replace(xml.find("-10000 -20"), 10, std::string("-10000 ") + c);
    const mj::InspectReport rep = report(xml);
    ASSERT_EQ(rep.contacts.size(), 1u);
    EXPECT_NEAR(rep.contacts[0].zeta, zeta, 1e-9);
    EXPECT_NEAR(ball_rebound(xml), rep.contacts[0].restitution, 4e-3) << "ζ = " << zeta;
  }
}

TEST_F(Inspect, PairsResolveClassPriorityAndPairsAsMujocoDoes) {
  // At the wall both contacts exist: the printed pair values must be what
  // MuJoCo put into d->contact.
  const mj::InspectReport rep = report(kBallModel, "at_wall", std::nullopt, true);
  ASSERT_EQ(rep.contacts.size(), 2u);
  ASSERT_EQ(rep.pairs.size(), 2u);  // ball–floor (explicit), ball–wall (default)
  for (const mj::InspectRow& p : rep.pairs) {
    EXPECT_EQ(p.contacts_now, 1) << p.geom1_name << " " << p.geom2_name;
    for (const mj::InspectRow& c : rep.contacts) {
      if (c.geom1 != p.geom1 || c.geom2 != p.geom2) continue;
      EXPECT_EQ(c.condim, p.condim);
      for (size_t i = 0; i < 2; ++i) EXPECT_EQ(c.solref[i], p.solref[i]);
      for (size_t i = 0; i < 5; ++i) EXPECT_EQ(c.solimp[i], p.solimp[i]);
      for (size_t i = 0; i < 5; ++i) EXPECT_EQ(c.friction[i], p.friction[i]);
    }
  }
  for (const mj::InspectRow& p : rep.pairs) {
    if (p.source != "default collision") continue;
    EXPECT_EQ(p.condim, 4);               // the ball's class: higher priority
    EXPECT_DOUBLE_EQ(p.solref[0], 0.01);  // not the wall's 0.05
    EXPECT_DOUBLE_EQ(p.friction[0], 0.7);
  }
}

TEST_F(Inspect, PairsFollowContypeConaffinityTheParentFilterAndExclude) {
  auto names = [](const mj::InspectReport& rep) {
    std::set<std::string> out;
    for (const mj::InspectRow& p : rep.pairs) out.insert(p.geom1_name + "/" + p.geom2_name);
    return out;
  };
  // upper and fore are parent and child (filtered); each meets the wall.
  EXPECT_EQ(names(report(kArmModel, "", std::nullopt, true)),
            (std::set<std::string>{"wall/upper", "wall/fore", "wall/tip"}));
  std::string xml = kArmModel;
  xml.replace(xml.find("<keyframe>"), 10,
              "<contact><exclude body1=\"world\" body2=\"upper\"/></contact>\n  <keyframe>");
  EXPECT_EQ(names(report(xml, "", std::nullopt, true)),
            (std::set<std::string>{"wall/fore", "wall/tip"}));
  xml = kArmModel;
  xml.replace(xml.find("name=\"tip\""), 10, "name=\"tip\" contype=\"2\" conaffinity=\"2\"");
  EXPECT_EQ(names(report(xml, "", std::nullopt, true)),
            (std::set<std::string>{"wall/upper", "wall/fore"}));
  // And MuJoCo agrees that the tip no longer touches the wall at the key.
  EXPECT_TRUE(report(xml, "touch").contacts.empty());
  xml = kArmModel;
  xml.replace(xml.find("<worldbody>"), 11,
              "<option><flag contact=\"disable\"/></option>\n  <worldbody>");
  const mj::InspectReport off = report(xml, "touch", std::nullopt, true);
  EXPECT_TRUE(off.contacts.empty());
  EXPECT_TRUE(off.pairs.empty());
  ASSERT_EQ(off.warnings.size(), 1u);
  EXPECT_NE(off.warnings[0].find("disables contacts"), std::string::npos);
}

TEST_F(Inspect, ArmEffectiveMassIsWhatAForceAtTheTipMeasures) {
  const mj::InspectReport rep = report(kArmModel, "touch");
  ASSERT_EQ(rep.contacts.size(), 1u);
  const mj::InspectRow& r = rep.contacts[0];
  EXPECT_EQ(r.geom2_name, "tip");
  // MuJoCo's estimate differs from the true value here (the point of this model).
  EXPECT_GT(std::abs(r.inv_weight / r.A - 1.0), 0.2);
  // Measure: push the tip along the normal with 1 N (mj_applyFT at the
  // contact point), contacts off, at rest; MuJoCo's forward dynamics gives
  // qacc, and the point's normal acceleration n·J·qacc (no velocity term at
  // rest, Jacobian by finite differences of the point's position) is A·F.
  Sim s(kArmModel);
  mj_resetDataKeyframe(s.m(), s.d(), 0);
  s.m()->opt.disableflags |= mjDSBL_CONTACT;
  const int tip = mj_name2id(s.m(), mjOBJ_GEOM, "tip");
  const int body = s.m()->geom_bodyid[tip];
  mj_forward(s.m(), s.d());
  double point[3] = {r.pos[0], r.pos[1], r.pos[2]};
  double force[3] = {r.normal[0], r.normal[1], r.normal[2]}, torque[3] = {0, 0, 0};
  mj_applyFT(s.m(), s.d(), force, torque, point, body, s.d()->qfrc_applied);
  mj_forward(s.m(), s.d());
  // The point fixed to the forearm, in its frame, moved by each joint.
  double local[3], rel[3];
  mju_sub3(rel, point, s.d()->xpos + 3 * body);
  mju_mulMatTVec(local, s.d()->xmat + 9 * body, rel, 3, 3);
  auto normal_position = [&](const double* qpos) {
    mj::DataPtr probe = mj::make_data(s.m());
    mju_copy(probe->qpos, qpos, s.m()->nq);
    mj_kinematics(s.m(), probe.get());
    double world[3];
    mju_mulMatVec(world, probe->xmat + 9 * body, local, 3, 3);
    mju_addTo3(world, probe->xpos + 3 * body);
    return mju_dot3(world, force);
  };
  double measured = 0.0;
  const double h = 1e-6;  // central differences: error h²·(curvature) ≈ 1e-12 relative
  for (int j = 0; j < s.m()->nv; ++j) {
    double plus[2] = {s.d()->qpos[0], s.d()->qpos[1]}, minus[2] = {plus[0], plus[1]};
    plus[j] += h;
    minus[j] -= h;
    measured += (normal_position(plus) - normal_position(minus)) / (2 * h) * s.d()->qacc[j];
  }
  // Rounding of the differences (~1e-16 m over 2e-6 m per joint, 5e-11):
  // measured 3.3e-11 relative; bound 1e-8.
  EXPECT_NEAR(measured, r.A, 1e-8 * r.A);
}

TEST_F(Inspect, PairNotInContactGetsItsAAtTheClosestPoints) {
  // At qpos0 the tip is 1 mm from the wall: MuJoCo's collision with a margin
  // finds the closest points, and A there is the contact's A at the key
  // where it touches (the shoulder turned by 0.0022 rad: measured 7e-6
  // relative apart; bound 1e-4). Â would be 6.7× off.
  const mj::InspectReport apart = report(kArmModel, "", std::nullopt, true);
  const mj::InspectReport touching = report(kArmModel, "touch");
  ASSERT_EQ(touching.contacts.size(), 1u);
  bool found = false;
  for (const mj::InspectRow& p : apart.pairs) {
    if (p.geom2_name != "tip") continue;
    found = true;
    EXPECT_EQ(p.contacts_now, 0);
    EXPECT_TRUE(p.closest);
    EXPECT_NEAR(p.dist, 0.001, 1e-9);
    EXPECT_NEAR(p.A, touching.contacts[0].A, 1e-4 * p.A);
  }
  EXPECT_TRUE(found);
}

TEST_F(Inspect, ArmReboundsWithThePrintedRestitution) {
  const mj::InspectReport rep = report(kArmModel, "touch");
  ASSERT_EQ(rep.contacts.size(), 1u);
  const mj::InspectRow& r = rep.contacts[0];
  // With A ≠ Â the damping ratio is not solref's 0.2: ζ = dr·√(A/(d·A + (1 − d)·Â)).
  EXPECT_NEAR(r.zeta, 0.2 * std::sqrt(r.A / (0.5 * r.A + 0.5 * r.inv_weight)), 1e-12);
  Sim s(kArmModel);
  s.m()->opt.timestep = 2e-5;  // ω·Δt = 0.013 (see the bound below)
  const int tip = mj_name2id(s.m(), mjOBJ_GEOM, "tip");
  s.d()->qvel[0] = 0.4;  // the tip at 0.2 m/s toward the wall, 1 mm away
  mj_forward(s.m(), s.d());
  auto normal_speed = [&] {
    double jacp[6];
    mj_jac(s.m(), s.d(), jacp, nullptr, s.d()->geom_xpos + 3 * tip, s.m()->geom_bodyid[tip]);
    return -(jacp[2] * s.d()->qvel[0] + jacp[3] * s.d()->qvel[1]);  // along the wall's −y normal
  };
  double v_in = 0.0;
  bool touched = false;
  int steps = 0;
  for (; steps < 1000000; ++steps) {
    if (!touched) v_in = normal_speed();
    mj_step(s.m(), s.d());
    if (s.d()->ncon > 0) touched = true;
    if (touched && s.d()->ncon == 0) break;
  }
  ASSERT_TRUE(touched);
  ASSERT_LT(steps, 1000000);
  mj_forward(s.m(), s.d());
  const double measured = -normal_speed() / v_in;
  // Semi-implicit Euler at ω·Δt = 0.013 (as for the ball, O(ω·Δt)), and the
  // arm turns by ~1e-4 rad during the bounce: measured 1.2e-3 (0.49116
  // against 0.48997); bound 3e-3. With Â in place of A (ζ = 0.2, solref's
  // dampratio) the closed form gives 0.572.
  EXPECT_NEAR(measured, r.restitution, 3e-3);
}

// The printed K, B, d and the Â the normal sees are what MuJoCo's own
// mj_makeImpedance put into efc_KBIP and efc_diagApprox (which it adjusts so
// that R = (1 − d)/d·diagApprox; a pyramidal contact's normal force is the
// sum of its 2(condim − 1) edge rows, so the normal sees diagApprox/(2(condim − 1))).
void expect_impedance_as_mujoco(const mj::InspectReport& rep, const std::string& xml,
                                const std::string& key) {
  Sim s(xml);
  if (!key.empty()) mj_resetDataKeyframe(s.m(), s.d(), mj_name2id(s.m(), mjOBJ_KEY, key.c_str()));
  mj_forward(s.m(), s.d());
  ASSERT_EQ(s.d()->ncon, static_cast<int>(rep.contacts.size()));
  for (const mj::InspectRow& r : rep.contacts) {
    const mjContact& con = s.d()->contact[r.contact];
    const int adr = con.efc_address;
    ASSERT_GE(adr, 0);
    SCOPED_TRACE(xml.substr(0, 60) + " contact " + std::to_string(r.contact));
    EXPECT_NEAR(r.K, s.d()->efc_KBIP[4 * adr], 1e-12 * r.K);
    EXPECT_NEAR(r.B, s.d()->efc_KBIP[4 * adr + 1], 1e-12 * r.B);
    EXPECT_NEAR(r.d_now, s.d()->efc_KBIP[4 * adr + 2], 1e-12);
    const bool pyramidal = s.m()->opt.cone == mjCONE_PYRAMIDAL && con.dim > 1;
    const double normal = s.d()->efc_diagApprox[adr] / (pyramidal ? 2.0 * (con.dim - 1) : 1.0);
    EXPECT_NEAR(r.normal_weight, normal, 1e-12 * normal);
  }
}

// The box dropped flat without gravity at 1 m/s, its bottom starting
// `phase` of one step's travel above the floor: its speed once no corner
// touches, over 1 m/s.
double flat_drop(const std::string& xml, double phase) {
  Sim s(xml);
  s.m()->opt.gravity[2] = 0.0;
  const double dt = s.m()->opt.timestep;
  // The box's half-height is 0.1 (kBoxModel) or 0.05 (box_on_plane); its
  // bottom at phase·dt above the floor, so the first step in contact finds
  // it (1 − phase)·dt·1 m/s deep.
  s.d()->qpos[2] = s.m()->geom_size[3 * 1 + 2] + phase * dt;
  s.d()->qvel[2] = -1.0;
  bool touched = false;
  for (int steps = 0; steps < 1000000; ++steps) {
    mj_step(s.m(), s.d());
    if (s.d()->ncon > 0) touched = true;
    if (touched && s.d()->ncon == 0) return s.d()->qvel[2];
  }
  return std::nan("");
}

// The body's bounce as printed — all four corners together at the model's
// Δt — against MuJoCo's own flat drops at the same 8 phases of the first
// contact within a step, on MuJoCo's defaults and on a stiff calibrated
// contact (ω·Δt 0.56), Euler and RK4. Measured equal to 12 digits (the
// same steps; MuJoCo's Newton solver converges on these 4 rows); bound
// 1e-6 relative, far inside the issue's 2 %. The spread over phases is
// ±10–15 %: one drop from an arbitrary height lands anywhere in it. (One
// corner's continuous-time restitution on the defaults is 0.128.)
TEST_F(Inspect, BodyBounceIsMujocosFlatDropAtTheModelsTimestep) {
  const std::string stiff =
      R"(<mujoco><option timestep="0.002" cone="elliptic" integrator="INTEGRATOR"/><worldbody>
  <geom name="floor" type="plane" size="2 2 0.1"/>
  <body name="box" pos="0 0 0.05"><freejoint/>
    <geom name="box" type="box" size="0.1 0.1 0.05" mass="1.5"
          solref="-13333.333 -33.333" solimp="0.0001 0.0001 0.001 0.5 2" priority="1"/>
  </body></worldbody></mujoco>)";
  for (const std::string integrator : {"Euler", "RK4"}) {
    std::string defaults = kBoxModel;
    defaults.replace(defaults.find("<worldbody>"), 11,
                     "<option integrator=\"" + integrator + "\"/><worldbody>");
    std::string calibrated = stiff;
    calibrated.replace(calibrated.find("INTEGRATOR"), 10, integrator);
    for (const std::string& xml : {defaults, calibrated}) {
      const mj::InspectReport rep = report(xml, "", std::nullopt, false, 1.0);
      ASSERT_EQ(rep.bodies.size(), 1u);
      const mj::BodySummary& b = rep.bodies[0];
      double mean = 0.0, low = INFINITY, high = -INFINITY;
      for (int k = 0; k < 8; ++k) {
        const double e = flat_drop(xml, (k + 0.5) / 8.0);
        mean += e / 8.0;
        low = std::min(low, e);
        high = std::max(high, e);
      }
      std::printf("%s: printed %.12f ± %.6f, MuJoCo %.12f in [%.6f, %.6f]\n", integrator.c_str(),
                  b.bounce, b.bounce_spread / 2, mean, low, high);
      EXPECT_NEAR(b.bounce, mean, 1e-6 * mean) << integrator;
      EXPECT_NEAR(b.bounce_spread, high - low, 1e-6) << integrator;
    }
  }
}

// Friction, against MuJoCo on a box with solref's calibrated contact, an
// elliptic cone, μ = 0.5, impratio 2: set sliding at its rest depth,
// MuJoCo's normal force is (f + μ·c·|v_t|)/(1 + μ²/impratio) per corner —
// the printed push μ·c on the rest load f; the printed lift-off speed is
// where a sliding contact would need k·p ≤ 0 to carry f.
TEST_F(Inspect, SlidingPushIsMujocosNormalForce) {
  // The calibrated contact of solref (flat d = 1e-4), where the law holds.
  const std::string xml =
      R"(<mujoco><option timestep="0.002" cone="elliptic" impratio="2"/><worldbody>
  <geom name="floor" type="plane" size="2 2 0.1"/>
  <body name="box" pos="0 0 0.0999"><freejoint/>
    <geom name="box" type="box" size="0.1 0.1 0.1" mass="1" friction="0.5"
          solref="-13333.333 -33.333" solimp="0.0001 0.0001 0.001 0.5 2" priority="1"/>
  </body></worldbody></mujoco>)";
  const mj::InspectReport rep = report(xml, "", std::nullopt, false, 3.0);
  ASSERT_EQ(rep.contacts.size(), 4u);
  const mj::InspectRow& r = rep.contacts[0];
  EXPECT_NEAR(r.push, 0.5 * r.c, 1e-12 * r.c);
  EXPECT_NEAR(r.lift_off, r.load * (1.0 + 0.25 / 2.0) / r.push, 1e-12 * r.lift_off);
  Sim s(xml);
  for (int i = 0; i < 1500; ++i) mj_step(s.m(), s.d());
  for (const double v : {0.02, 0.05, 0.1}) {
    mjData* d = s.d();
    d->qvel[0] = v;  // sliding along x, the box otherwise at rest
    for (int i = 1; i < 6; ++i) d->qvel[i] = 0.0;
    mj_forward(s.m(), d);
    ASSERT_EQ(d->ncon, 4);
    double total = 0.0, predicted = 0.0;
    for (int i = 0; i < d->ncon; ++i) {
      double f[6];
      mj_contactForce(s.m(), d, i, f);
      total += f[0];
      const mj::InspectRow& c = rep.contacts[static_cast<size_t>(i)];
      predicted += (c.load + c.push * v) / (1.0 + 0.25 / 2.0);
    }
    std::printf("v = %g: MuJoCo %.9f N, printed push %.9f N\n", v, total, predicted);
    // Sliding (impratio·c·v above μ·f): the law holds as d·A/((1 − d)·Â)
    // → 0, here 1e-4·4/1 = 4e-4; measured 1.8e-4 relative; bound 1e-3.
    EXPECT_NEAR(total, predicted, 1e-3 * predicted) << v;
  }
}

// The impratio cap, against MuJoCo: the calibrated box (elliptic, μ = 0.5)
// on a 10° tilt creeps at the printed speed below the cap, and above it
// MuJoCo's friction rows reverse the slip each step and it creeps faster
// than the viscous formula, which inspect then does not print (a warning
// says why).
TEST_F(Inspect, ImpratioAboveTheCapChattersAndIsWarned) {
  auto model = [](double impratio) {
    return R"(<mujoco><option timestep="0.002" cone="elliptic" impratio=")" +
           std::to_string(impratio) + R"("/><worldbody>
  <geom name="floor" type="plane" size="2 2 0.1"/>
  <body name="box" pos="0 0 0.0999"><freejoint/>
    <geom name="box" type="box" size="0.1 0.1 0.1" mass="1" friction="0.5"
          solref="-13333.333 -33.333" solimp="0.0001 0.0001 0.001 0.5 2" priority="1"/>
  </body></worldbody></mujoco>)";
  };
  const double cap = report(model(1.0), "", 10.0, false, 3.0).contacts[0].impratio_cap;
  ASSERT_TRUE(std::isfinite(cap));
  // Below: printed and measured.
  const std::string below = model(0.5 * cap);
  const mj::InspectReport ok = report(below, "", 10.0, false, 3.0);
  const auto [measured, printed] = box_creep(ok, below, 10.0);
  std::printf("cap %.6g; at cap/2 MuJoCo %.6g m/s, printed %.6g\n", cap, measured, printed);
  // Measured equal to 6 digits (0.00679904 m/s); bound 1e-3 relative.
  EXPECT_NEAR(measured, printed, 1e-3 * printed);
  // Above: no creep printed, a warning, and MuJoCo faster than the formula.
  const std::string above = model(3.0 * cap);
  const mj::InspectReport bad = report(above, "", 10.0, false, 3.0);
  bool warned = false;
  for (const std::string& w : bad.warnings)
    warned |= w.find("MuJoCo chatters") != std::string::npos;
  EXPECT_TRUE(warned);
  const mj::InspectRow& r = bad.contacts[0];
  EXPECT_FALSE(std::isfinite(r.creep));
  double formula = 0.0;  // the viscous formula at 3× the cap, per corner, averaged
  for (const mj::InspectRow& c : bad.contacts)
    formula += c.load * std::sin(10.0 * kPiInspect / 180.0) * (1.0 - c.d_rest) * c.inv_weight /
               (3.0 * cap * c.B * c.d_rest) / 4.0;
  const auto [fast, none] = box_creep(bad, above, 10.0);
  std::printf("at 3 cap MuJoCo %.6g m/s, the formula %.6g\n", fast, formula);
  // Measured 4.3× the formula (0.00488 against 0.00113 m/s); bound 1.2×.
  EXPECT_GT(fast, 1.2 * formula);
}

TEST_F(Inspect, KBImpedanceAndNormalWeightAreWhatMujocoComputes) {
  std::string elliptic = kBoxModel, rough = kBoxModel, refsafe = kBoxModel;
  elliptic.replace(elliptic.find("<worldbody>"), 11, "<option cone=\"elliptic\"/><worldbody>");
  rough.replace(rough.find("<worldbody>"), 11,
                "<option impratio=\"0.5\"/><default><geom friction=\"2\"/></default><worldbody>");
  refsafe.replace(refsafe.find("<worldbody>"), 11,
                  "<default><geom solref=\"0.001 1\"/></default><worldbody>");
  for (const std::string& xml : {std::string(kBoxModel), elliptic, rough, refsafe})
    expect_impedance_as_mujoco(report(xml), xml, "");
  expect_impedance_as_mujoco(report(kBallModel, "at_wall"), kBallModel, "at_wall");
  expect_impedance_as_mujoco(report(kArmModel, "touch"), kArmModel, "touch");
}

// inspect's JSON goes through the one JSON writer (io/json.hpp): a geom
// name with a tab and a carriage return (&#9; and &#13; in the MJCF) is
// escaped, never written raw (inspect had an escaper of its own that passed
// both). The name is the tool's printable one (model.hpp's printable_name:
// \x09, \x0d), as the text prints it, its backslashes JSON-escaped.
TEST_F(Inspect, JsonEscapesControlCharactersInNames) {
  std::string model = kBoxModel;
  const std::string floor = "name=\"floor\"";
  ASSERT_NE(model.find(floor), std::string::npos);
  model.replace(model.find(floor), floor.size(), "name=\"the&#9;floor&#13;\"");
  const std::string json = mj::format_inspect_json(report(model, "", std::nullopt, false, 0.0));
  EXPECT_NE(json.find("the\\\\x09floor\\\\x0d"), std::string::npos) << json.substr(0, 600);
  EXPECT_EQ(json.find('\t'), std::string::npos);
  EXPECT_EQ(json.find('\r'), std::string::npos);
}

TEST_F(Inspect, KelvinVoigtRestitutionClampedAtZeroMatchesItsKnownValues) {
  // Undamped: no loss. Light damping: the clamp lets go before x = 0, so e
  // is below the unclamped exp(−ζπ/√(1 − ζ²)).
  EXPECT_NEAR(benchmarks::kelvin_voigt_restitution(0.0), 1.0, 1e-12);
  const double z = 0.1;
  EXPECT_GT(benchmarks::kelvin_voigt_restitution(z), benchmarks::dashpot_restitution(z));
  // Continuous across critical damping, decreasing.
  EXPECT_NEAR(benchmarks::kelvin_voigt_restitution(0.999),
              benchmarks::kelvin_voigt_restitution(1.001), 1e-3);
  EXPECT_GT(benchmarks::kelvin_voigt_restitution(0.5), benchmarks::kelvin_voigt_restitution(2.0));
}

TEST_F(Inspect, WarnsWhenRefsafeChangesTheTimeconst) {
  std::string xml = kBoxModel;
  xml.replace(xml.find("<worldbody>"), 11,
              "<default><geom solref=\"0.001 1\"/></default>\n  <worldbody>");
  const mj::InspectReport rep = report(xml);
  ASSERT_FALSE(rep.contacts.empty());
  EXPECT_TRUE(rep.contacts[0].refsafe_changes);
  EXPECT_DOUBLE_EQ(rep.contacts[0].timeconst_used, 0.004);
  // (Its friction rows also pass their impratio cap at this timeconst: a
  // warning of its own, before this one.)
  bool found = false;
  for (const std::string& w : rep.warnings)
    found |= w.find("refsafe raises the solref timeconst 0.001 s") != std::string::npos;
  EXPECT_TRUE(found);
  EXPECT_TRUE(report(kBoxModel).warnings.empty());
}

TEST_F(Inspect, WarnsWhenOmegaDtExceedsTheIntegratorsLimit) {
  std::string xml = kBoxModel;
  xml.replace(xml.find("<worldbody>"), 11,
              "<default><geom solref=\"-1e7 -100\"/></default>\n  <worldbody>");
  const mj::InspectReport rep = report(xml);
  ASSERT_FALSE(rep.contacts.empty());
  EXPECT_GT(rep.contacts[0].omega_dt, rep.contacts[0].limit);
  bool found = false;
  for (const std::string& w : rep.warnings)
    found |= w.find("exceeds Euler's limit") != std::string::npos;
  EXPECT_TRUE(found);
  // And MuJoCo does blow up: the box leaves the plane faster than any fall.
  Sim s(xml);
  bool diverged = false;
  for (int i = 0; i < 500 && !diverged; ++i) {
    mj_step(s.m(), s.d());
    diverged = !(std::abs(s.d()->qvel[2]) < 10.0) || s.d()->warning[mjWARN_BADQACC].number > 0;
  }
  EXPECT_TRUE(diverged);
}

TEST_F(Inspect, MujocoTurnsUnstableWhereThePrintedOmegaDtLimitIs) {
  // The ball's pair (flat d, ζ = 0.1, ω = 100 /s) resting on the floor, 1e-6 m
  // off its rest depth, at timesteps of 0.9× and 1.1× the printed limit, under
  // each of MuJoCo's integrators.
  for (const std::string integrator : {"Euler", "RK4", "implicit"}) {
    std::string xml = kBallModel;
    xml.replace(xml.find("<option timestep=\"0.0001\"/>"), 28,
                "<option timestep=\"0.0001\" integrator=\"" + integrator + "\"/>");
    const mj::InspectReport rep = report(xml, "", std::nullopt, false, 3.0);
    EXPECT_EQ(rep.integrator, integrator);
    ASSERT_EQ(rep.contacts.size(), 1u);
    const mj::InspectRow& r = rep.contacts[0];
    const double dt_limit = r.limit / r.omega_max;
    auto growth = [&](double dt) {
      Sim s(xml);
      s.m()->opt.timestep = dt;
      s.d()->qpos[2] = 0.1 - r.penetration - 1e-6;
      mj_forward(s.m(), s.d());
      double largest = 0.0;
      for (int i = 0; i < 400; ++i) {
        mj_step(s.m(), s.d());
        if (i >= 300) largest = std::max(largest, std::abs(s.d()->qpos[2] - (0.1 - r.penetration)));
      }
      return largest / 1e-6;
    };
    // Semi-implicit Euler's update at ζ = 0.1 has |λ| = 0.82 at 0.9× its
    // limit (1.81) and 2.07 at 1.1×: over steps 300–400 the offset is ~1e-26
    // of its start, or the ball has long left the floor. Measured 1.4e-11
    // (rounding of the rest position) and 1.2e7 (it bounces) for Euler, 1.4e-11
    // and 3.6e7 for RK4 (limit 2.95), 0 and 7.5e6 for implicit (Euler's limit:
    // MuJoCo's implicit integrator treats contacts explicitly); bounds ×0.5, ×2.
    const double stable = growth(0.9 * dt_limit), unstable = growth(1.1 * dt_limit);
    EXPECT_LT(stable, 0.5) << "dt " << 0.9 * dt_limit;
    EXPECT_GT(unstable, 2.0) << "dt " << 1.1 * dt_limit;
  }
}

// solimp with d0 above d_max (MuJoCo allows it: the impedance falls with
// depth): the contact is stiffest at first touch, d0 = 0.99 here, where
// k = d²K/(d·A + (1 − d)·Â) with K = 308000/0.5² (direct solref, A = Â = 1)
// gives ω = 1099 rad/s, twice d_max's 555. The ball 1 % of its rest depth
// off it at 0.9× and 1.1× the printed stable timestep, as in
// MujocoTurnsUnstableWhereThePrintedOmegaDtLimitIs: measured 0.19 of the
// offset left over steps 300–400 at 0.9× (ζ = 0.0045 damps slowly) and
// 1.8e8 at 1.1×; bounds 0.5 and 2. Before the fix the limit was taken at
// d_max (ω·Δt 1.11, "ok", at the model's 2 ms, where MuJoCo launches the
// ball: 2.2 > 1.99), and 0.9× its timestep (3.2 ms) is unstable.
TEST_F(Inspect, AnImpedanceFallingWithDepthIsStiffestAtFirstTouch) {
  const std::string xml = R"(<mujoco>
  <default><geom solimp="0.99 0.5 0.01 0.5 2" solref="-308000 -5" condim="1"/></default>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="ball" pos="0 0 0.09997"><freejoint/><geom type="sphere" size="0.1" mass="1"/></body>
  </worldbody>
</mujoco>
)";
  const mj::InspectReport rep = report(xml, "", std::nullopt, false, 0.0, true);
  ASSERT_EQ(rep.contacts.size(), 1u);
  const mj::InspectRow& r = rep.contacts[0];
  const double dt_limit = r.limit / r.omega_max;
  // The rest depth is 8.1e-8 m (R-dominated: p·K·d² = f·Â·(1 − d)): the
  // offset is 1 % of it, so the ball stays in contact.
  const double offset = 0.01 * r.penetration;
  auto growth = [&](double dt) {
    Sim s(xml);
    s.m()->opt.timestep = dt;
    s.d()->qpos[2] = 0.1 - r.penetration - offset;
    mj_forward(s.m(), s.d());
    double largest = 0.0;
    for (int i = 0; i < 400; ++i) {
      mj_step(s.m(), s.d());
      if (i >= 300) largest = std::max(largest, std::abs(s.d()->qpos[2] - (0.1 - r.penetration)));
    }
    return largest / offset;
  };
  EXPECT_LT(growth(0.9 * dt_limit), 0.5) << "dt " << 0.9 * dt_limit;
  EXPECT_GT(growth(1.1 * dt_limit), 2.0) << "dt " << 1.1 * dt_limit;
  // At the model's 2 ms it says unstable.
  EXPECT_GT(r.omega_dt, r.limit);
}

TEST_F(Inspect, WarnsForAPyramidalConeWithHighFrictionAndForImpratioBelowOne) {
  std::string xml = kBoxModel;
  xml.replace(xml.find("<worldbody>"), 11,
              "<option impratio=\"0.5\"/><default><geom friction=\"2\"/></default>\n  <worldbody>");
  const mj::InspectReport rep = report(xml, "", std::nullopt, false, 3.0);
  ASSERT_FALSE(rep.contacts.empty());
  // φ = μ²(1 + μ²)/((condim − 1)·impratio) = 4·5/(2·0.5) = 20.
  EXPECT_DOUBLE_EQ(rep.contacts[0].phi, 20.0);
  bool cone = false, impratio = false;
  for (const std::string& w : rep.warnings) {
    cone |= w.find("pyramidal cone with μ = 2") != std::string::npos;
    impratio |= w.find("impratio = 0.5 < 1") != std::string::npos;
  }
  EXPECT_TRUE(cone);
  EXPECT_TRUE(impratio);
  // The box does rest at the printed depth, the one φ gives.
  Sim s(xml);
  for (int i = 0; i < 1500; ++i) mj_step(s.m(), s.d());
  // Measured 1.5e-14 relative; bound 1e-9 (the default box, φ = 1, rests 9.1× shallower).
  EXPECT_NEAR(mean_contact_depth(s), rep.contacts[0].penetration,
              1e-9 * rep.contacts[0].penetration);
}

TEST_F(Inspect, WarnsWhenABodysEffectiveMassDiffersTenfoldAcrossItsContacts) {
  // A rod hinged at x = 0 resting on two posts, at x = 0.1 and x = 0.9: A ∝ x²/I.
  const char* xml = R"(<mujoco>
  <worldbody>
    <geom name="near" type="box" pos="0.1 0 -0.05" size="0.02 0.1 0.05"/>
    <geom name="far" type="box" pos="0.9 0 -0.05" size="0.02 0.1 0.05"/>
    <body name="rod" pos="0 0 0.0199">
      <joint type="hinge" axis="0 1 0"/>
      <geom name="rod" type="capsule" fromto="0 0 0 1 0 0" size="0.02" mass="1"/>
    </body>
  </worldbody>
</mujoco>
)";
  const mj::InspectReport rep = report(xml);
  ASSERT_GE(rep.contacts.size(), 2u);
  bool found = false;
  for (const std::string& w : rep.warnings)
    found |= w.find("body rod: its effective mass") != std::string::npos;
  EXPECT_TRUE(found);
  EXPECT_FALSE(report(kBoxModel).warnings.size());
}

TEST_F(Inspect, SaysSoWhenTheNormalForcesCannotHoldTheModel) {
  // A ball on a plane tilted by 20° about y: without friction nothing holds it
  // along the slope; the least-squares load is the weight's normal part.
  const char* xml = R"(<mujoco>
  <worldbody>
    <geom name="slope" type="plane" size="2 2 0.1" euler="0 20 0"/>
    <body name="ball" pos="0 0 0.0999">
      <freejoint/>
      <geom name="ball" type="sphere" size="0.1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
)";
  const mj::InspectReport rep = report(xml, "", std::nullopt, false, 0.0, true);
  ASSERT_EQ(rep.contacts.size(), 1u);
  EXPECT_FALSE(rep.balanced);
  EXPECT_NEAR(rep.residual, std::sin(20.0 * kPiInspect / 180.0), 1e-9);
  EXPECT_NEAR(rep.contacts[0].load, 9.81 * std::cos(20.0 * kPiInspect / 180.0), 1e-9);
  bool found = false;
  for (const std::string& w : rep.warnings)
    found |= w.find("normal forces alone do not hold the model") != std::string::npos;
  EXPECT_TRUE(found);
  EXPECT_TRUE(report(kBoxModel, "", std::nullopt, false, 0.0, true).balanced);
}

TEST_F(Inspect, AContactItsJointsCannotMoveAlongTheNormalHasNoDynamics) {
  // A sphere on a hinge through its centre touching the floor: n·J = 0.
  const char* xml = R"(<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="wheel" pos="0 0 0.0999">
      <joint type="hinge" axis="0 1 0"/>
      <geom name="wheel" type="sphere" size="0.1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
)";
  const mj::InspectReport rep = report(xml);
  ASSERT_EQ(rep.contacts.size(), 1u);
  EXPECT_NEAR(rep.contacts[0].A, 0.0, 1e-15);
  EXPECT_TRUE(std::isnan(rep.contacts[0].zeta));
  EXPECT_TRUE(rep.warnings.empty()) << rep.warnings[0];  // no ω·Δt warning from a NaN limit
  EXPECT_NE(mj::format_inspect_text(rep).find("no contact dynamics"), std::string::npos);
}

// A contact its joints cannot move gets an A of round-off rather than 0
// when the arithmetic is not exact: 5e-33 to 1.1e-16 1/kg on Debian's
// samples, where the text printed ω = 1e-14 rad/s and "nan as MuJoCo steps
// it" (and "effective mass inf kg" where A is exactly 0). Two spheres on
// hinges through their centres, one axis along z (A exactly 0) and one
// tilted, and a wall, with --pairs (A at the closest points): MuJoCo moves
// no contact point along its normal under a 1 N push there (|n·J·qacc|
// within 1e-12 of the pushed body's Â or 1/m, inspect.hpp's kNoMotion: Â
// is 0 for a body that only turns), and the
// text says of each pair that it moves nothing, with no nan or inf
// anywhere. Run time: one inspect (~20 ms).
TEST_F(Inspect, AContactThatMovesNothingIsSaidSoWithoutNanOrInf) {
  const char* xml = R"(<mujoco>
  <worldbody>
    <geom name="wall" type="plane" pos="1 0 0" zaxis="-1 0 0" size="2 2 0.1"/>
    <body name="level" pos="0 0 0.5">
      <joint type="hinge" axis="0 0 1"/>
      <geom name="level" type="sphere" size="0.1" mass="1"/>
    </body>
    <body name="tilted" pos="0.1 0.7 0.5">
      <joint type="hinge" axis="0.3 0.5 0.8"/>
      <geom name="tilted" type="sphere" size="0.1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
)";
  const mj::InspectReport rep = report(xml, "", std::nullopt, true);
  ASSERT_EQ(rep.pairs.size(), 3u);
  Sim s(xml);
  for (const mj::InspectRow& r : rep.pairs) {
    SCOPED_TRACE(r.geom1_name + " – " + r.geom2_name);
    for (const int body : {r.body1, r.body2}) {
      if (s.m()->body_dofnum[body] == 0) continue;
      mju_zero(s.d()->qfrc_applied, s.m()->nv);
      double point[3] = {r.pos[0], r.pos[1], r.pos[2]};
      double force[3] = {r.normal[0], r.normal[1], r.normal[2]}, torque[3] = {0, 0, 0};
      mj_applyFT(s.m(), s.d(), force, torque, point, body, s.d()->qfrc_applied);
      mj_forward(s.m(), s.d());
      std::vector<double> jac(3 * static_cast<size_t>(s.m()->nv));
      mj_jac(s.m(), s.d(), jac.data(), nullptr, point, body);
      double accel = 0.0;
      for (int k = 0; k < 3; ++k)
        for (int v = 0; v < s.m()->nv; ++v)
          accel += r.normal[static_cast<size_t>(k)] * jac[static_cast<size_t>(k * s.m()->nv + v)] *
                   s.d()->qacc[v];
      EXPECT_LE(std::abs(accel),
                1e-12 * std::max(s.m()->body_invweight0[2 * body], 1.0 / s.m()->body_mass[body]));
    }
  }
  const Run text = run("inspect model.xml --pairs --no-rest-search");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_FALSE(std::regex_search(text.out, std::regex(R"(\b(nan|inf)\b)"))) << text.out;
  size_t said = 0;
  for (size_t at = 0; (at = text.out.find("it moves nothing", at)) != std::string::npos; ++at)
    ++said;
  EXPECT_EQ(said, 3u) << text.out;
}

TEST_F(Inspect, CliPrintsMujocosMessageOnOneLineForAModelItCannotLoad) {
  write("bad.xml", "<mujoco><worldbody><geom type=\"sphere\" size=\"-1\"/></wordbody></mujoco>\n");
  const Run r = run("inspect bad.xml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("bad.xml: MuJoCo cannot load the model: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("XML parse error"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  const Run missing = run("inspect missing.xml");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("missing.xml: cannot read the MJCF file (No such file"),
            std::string::npos)
      << missing.err;
}

TEST_F(Inspect, CliSaysSoForAModelWithNoContactsAndExitsZero) {
  write("free.xml",
        "<mujoco><worldbody><body pos=\"0 0 1\"><freejoint/><geom type=\"sphere\" "
        "size=\"0.1\"/></body></worldbody></mujoco>\n");
  const Run r = run("inspect free.xml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("no contacts at qpos0"), std::string::npos) << r.out;
  const Run json = run("inspect free.xml --json");
  EXPECT_EQ(json.status, 0);
  EXPECT_NE(json.out.find("\"contacts\": []"), std::string::npos) << json.out;
}

TEST_F(Inspect, CliNamesABadKeyOrSlopeAndItsRange) {
  write("box.xml", kBoxModel);
  const Run key = run("inspect box.xml --key nowhere");
  EXPECT_EQ(key.status, 2);
  EXPECT_NE(key.err.find("--key nowhere: no keyframe of that name"), std::string::npos) << key.err;
  const Run slope = run("inspect box.xml --slope 95");
  EXPECT_EQ(slope.status, 2);
  EXPECT_NE(slope.err.find("--slope 95: must be in [0, 90) degrees"), std::string::npos)
      << slope.err;
  // The text names identical contacts once; the JSON lists each.
  const Run text = run("inspect box.xml");
  EXPECT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("\ncontacts 1, 2, 3: the same as contact 0"), std::string::npos)
      << text.out;
  const Run ok = run("inspect box.xml --slope 10 --json");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"creep\": "), std::string::npos);
}

}  // namespace
}  // namespace contact2d
