// solref --apply changes a contact's solref and solimp and nothing else
// (issue 48): each contact of the model, read by MuJoCo before and after,
// compared field by field on both versions. Before the fix the snippet's
// priority="1" made MuJoCo take the foot's condim 1 and friction over its
// mixing with the floor's condim 3, and moved the foot's contacts with its
// own leg to the new law too.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>

#include "core/input_error.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco/solref_request.hpp"
#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;
namespace mj = contact2d::mujoco;

using PairReader = std::function<mj::ModelState(const mj::StateRequest&)>;
struct PairVersion {
  const char* name;
  const char* engine;
  PairReader read;
};
const PairVersion kPairVersions[] = {
    {"2.2.2", "mujoco", [](const mj::StateRequest& r) { return mj::read_model_state(r); }},
    {"3.14", "mujoco3", [](const mj::StateRequest& r) { return mujoco3::read_model_state(r); }},
};

class ApplyPairs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_pairs_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::string pair_key(const mj::ModelState& s, const mj::StateContact& c) {
  std::string a = s.geom_names[static_cast<size_t>(c.geom1)];
  std::string b = s.geom_names[static_cast<size_t>(c.geom2)];
  // --apply names an unnamed geom contact2d_geomID: the same geom.
  for (std::string* n : {&a, &b})
    if (n->rfind("geom #", 0) == 0) *n = "contact2d_geom" + n->substr(6);
  return a < b ? a + "|" + b : b + "|" + a;
}

// Every contact after --apply whose geom pair MuJoCo also made before:
// condim, friction, margin and gap exactly as before; solref and solimp
// the mapping's on the pairs the body rested on, else as before. Returns
// how many were compared as mapped and as not.
std::pair<int, int> expect_only_solref_changed(const mj::ModelState& before,
                                               const mj::ModelState& after, const std::string& body,
                                               const mj::SolverSettings& mapping) {
  int body_id = -1;
  for (size_t b = 0; b < before.body_names.size(); ++b)
    if (before.body_names[b] == body) body_id = static_cast<int>(b);
  std::map<std::string, const mj::StateContact*> seen, rested;
  for (const mj::StateContact& c : before.contacts) {
    seen[pair_key(before, c)] = &c;
    if (c.body1 == body_id || c.body2 == body_id) rested[pair_key(before, c)] = &c;
  }
  int mapped = 0, other = 0;
  for (const mj::StateContact& c : after.contacts) {
    const std::string key = pair_key(after, c);
    const auto it = seen.find(key);
    if (it == seen.end()) continue;
    const mj::StateContact& was = *it->second;
    SCOPED_TRACE(key);
    EXPECT_EQ(c.condim, was.condim);
    for (size_t k = 0; k < 5; ++k) EXPECT_EQ(c.friction[k], was.friction[k]) << "friction " << k;
    EXPECT_EQ(c.margin, was.margin);
    EXPECT_EQ(c.gap, was.gap);
    const bool is_mapped = rested.count(key) > 0;
    const std::array<double, 2> solref = is_mapped ? mapping.solref : was.solref;
    const std::array<double, 5> solimp = is_mapped ? mapping.solimp : was.solimp;
    for (size_t k = 0; k < 2; ++k) EXPECT_EQ(c.solref[k], solref[k]) << "solref " << k;
    for (size_t k = 0; k < 5; ++k) EXPECT_EQ(c.solimp[k], solimp[k]) << "solimp " << k;
    (is_mapped ? mapped : other)++;
  }
  return {mapped, other};
}

mj::SolrefReport apply_with(const PairVersion& v, const std::string& model, const std::string& body,
                            double settle, const std::string& out, double c = 150.0) {
  mj::SolrefRequest request;
  request.k = 1e4;
  request.c = c;
  request.model = model;
  request.body = body;
  request.settle = settle;
  request.apply = out;
  request.engine = v.engine;
  return mj::solref_request(request, {}, v.read);
}

// Debian's humanoid (its geoms condim 1, friction 0.7; its floor condim 3,
// friction 1 0.1 0.1): the right foot's contacts keep the floor's condim 3,
// and the foot's contacts with the rest of the body keep their law. The
// output is written outside the samples' folder (read-only to a user).
TEST_F(ApplyPairs, TheHumanoidsFootKeepsItsCondimFrictionAndOtherContacts) {
  CONTACT2D_NEEDS_MUJOCO3();
  const fs::path humanoid = "/usr/share/mujoco/model/humanoid/humanoid.xml";
  if (!fs::exists(humanoid)) GTEST_FAIL() << "libmujoco-samples is missing: scripts/setup";
  for (const PairVersion& v : kPairVersions) {
    SCOPED_TRACE(v.name);
    const std::string out = (dir_ / (std::string("applied_") + v.engine + ".xml")).string();
    const mj::SolrefReport report = apply_with(v, humanoid.string(), "right_foot", 3.0, out);
    const mj::ModelState before = v.read({humanoid.string(), "", 3.0, ""});
    const mj::ModelState after = v.read({out, "", 3.0, ""});
    const auto [mapped, other] =
        expect_only_solref_changed(before, after, "right_foot", report.mappings.front().settings);
    EXPECT_GE(mapped, 1);  // the foot on the floor
    EXPECT_GE(other, 1);   // the rest of the humanoid on the floor
    for (const mj::StateContact& c : after.contacts) {
      const std::string key = pair_key(after, c);
      const bool foot = key.find("right_right_foot") != std::string::npos ||
                        key.find("left_right_foot") != std::string::npos;
      if (foot && key.find("floor") != std::string::npos) {
        EXPECT_EQ(c.condim, 3) << key;
      }
    }
  }
}

// Geoms that mix differently: the block's box (friction 0.9 0.01 0.0001,
// condim 6) mixes with the floor (0.3 0.02 0.001, condim 3, margin 2 mm,
// gap 0.5 mm, solmix 2); its unnamed sphere has priority 2 (its condim 1
// and friction 0.4 win); its second sphere already has an explicit <pair>
// (edited in place, not doubled; its margin and gap those the others get on
// either version, so all three rest in contact on both); a ball elsewhere
// on the floor is not the body's. Every one keeps its fields; the unnamed
// geom gets a name.
TEST_F(ApplyPairs, GeomsThatMixDifferentlyKeepWhatMujocoMixed) {
  CONTACT2D_NEEDS_MUJOCO3();
  const fs::path model = dir_ / "mix.xml";
  std::ofstream(model) << R"(<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.1" friction="0.3 0.02 0.001" condim="3"
          margin="0.002" gap="0.0005" solmix="2"/>
    <body name="block" pos="0 0 0.05">
      <freejoint/>
      <geom name="box" type="box" size="0.1 0.1 0.05" mass="2" friction="0.9 0.01 0.0001"
            condim="6"/>
      <geom type="sphere" size="0.05" pos="0.25 0 0" mass="0.5" friction="0.4 0.005 0.0001"
            condim="1" priority="2"/>
      <geom name="cap" type="sphere" size="0.05" pos="-0.25 0 0" mass="0.5"/>
    </body>
    <body name="ball" pos="1 0 0.1">
      <freejoint/>
      <geom name="ball" type="sphere" size="0.1" mass="1" friction="0.6 0.01 0.001"/>
    </body>
  </worldbody>
  <contact>
    <pair geom1="floor" geom2="cap" condim="4" friction="0.7 0.7 0.01 0.001 0.001"
          margin="0.002" gap="0.0005"/>
  </contact>
</mujoco>
)";
  for (const PairVersion& v : kPairVersions) {
    SCOPED_TRACE(v.name);
    const std::string out = (dir_ / (std::string("applied_") + v.engine + ".xml")).string();
    const mj::SolrefReport report = apply_with(v, model.string(), "block", 1.0, out);
    const mj::ModelState before = v.read({model.string(), "", 1.0, ""});
    const mj::ModelState after = v.read({out, "", 1.0, ""});
    const auto [mapped, other] =
        expect_only_solref_changed(before, after, "block", report.mappings.front().settings);
    EXPECT_GE(mapped, 3);  // box, the unnamed sphere, cap: each on the floor
    EXPECT_GE(other, 1);   // the ball
    // The pair of cap was edited, not doubled: MuJoCo makes as many contacts.
    EXPECT_EQ(after.contacts.size(), before.contacts.size());
    std::ifstream in(out);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    size_t pairs = 0;
    for (size_t at = text.find("<pair "); at != std::string::npos; at = text.find("<pair ", at + 1))
      ++pairs;
    EXPECT_EQ(pairs, 3u);  // cap's, and one each for box and the sphere
  }
}

// Each version's margin and gap, checked against MuJoCo's own
// includemargin: a sphere 1 mm above the floor (a keyframe), margins 2 and
// 3 mm, gaps 0.5 and 1 mm. MuJoCo reports dist 1 mm, and the state's dist is
// con.dist − includemargin. 2.2.2 takes the larger margin and gap and keeps
// margin − gap (3 − 1 = 2 mm); 3.x adds them and keeps the margin (5 mm; its
// gap, 1.5 mm, widens only the distance a contact is detected at, which an
// excluded contact would show, and the mujoco3 reader lists none).
TEST_F(ApplyPairs, MarginAndGapAreTheVersionsOwn) {
  CONTACT2D_NEEDS_MUJOCO3();
  const fs::path model = dir_ / "margin.xml";
  std::ofstream(model) << R"(<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1" margin="0.002" gap="0.0005"/>
    <body name="ball" pos="0 0 1"><freejoint/>
      <geom name="ball" type="sphere" size="0.1" margin="0.003" gap="0.001"/></body>
  </worldbody>
  <keyframe><key name="above" qpos="0 0 0.101 1 0 0 0"/></keyframe>
</mujoco>
)";
  const double margin[] = {0.003, 0.005}, gap[] = {0.001, 0.0015};
  const double included[] = {0.003 - 0.001, 0.005};
  for (size_t i = 0; i < 2; ++i) {
    const PairVersion& v = kPairVersions[i];
    SCOPED_TRACE(v.name);
    const mj::ModelState s = v.read({model.string(), "above", 0.0, ""});
    ASSERT_EQ(s.contacts.size(), 1u);
    const mj::StateContact& c = s.contacts[0];
    EXPECT_NEAR(c.margin, margin[i], 1e-15);
    EXPECT_NEAR(c.gap, gap[i], 1e-15);
    EXPECT_NEAR(c.dist, 0.001 - included[i], 1e-9);
  }
}

// A model with files beside it (the mug's mesh and texture), applied into
// another folder: its references made absolute, it loads and rests there.
TEST_F(ApplyPairs, AModelWithMeshesAppliesIntoAnotherFolder) {
  CONTACT2D_NEEDS_MUJOCO3();
  const fs::path mug = "/usr/share/mujoco/model/mug/mug.xml";
  if (!fs::exists(mug)) GTEST_FAIL() << "libmujoco-samples is missing: scripts/setup";
  for (const PairVersion& v : kPairVersions) {
    SCOPED_TRACE(v.name);
    const std::string out = (dir_ / (std::string("mug_") + v.engine + ".xml")).string();
    // c = 20: ζ ≈ 0.2 on the mug's contacts (A ≈ 4 1/kg); at c = 150 it is
    // overdamped and still creeping on 3.14 after 3 s.
    const mj::SolrefReport report = apply_with(v, mug.string(), "mug", 3.0, out, 20.0);
    ASSERT_TRUE(report.applied.has_value());
    EXPECT_TRUE(report.applied->at_rest);
    EXPECT_FALSE(report.applied->contacts.empty());
  }
}

// An <include>d file that names its files relative to the model's folder
// cannot be rebased from here: one line, and no file.
TEST_F(ApplyPairs, AnIncludeWithRelativeFilesIsRefusedElsewhere) {
  fs::create_directories(dir_ / "model");
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "model" / "assets.xml")
      << "<mujoco><asset><mesh name=\"t\" file=\"t.obj\"/></asset></mujoco>\n";
  std::ofstream(dir_ / "model" / "t.obj")
      << "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(dir_ / "model" / "m.xml") << R"(<mujoco><include file="assets.xml"/>
  <worldbody><geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="ball" pos="0 0 0.1"><freejoint/><geom name="b" type="sphere" size="0.1"/></body>
  </worldbody></mujoco>
)";
  const PairVersion& v = kPairVersions[0];
  try {
    apply_with(v, (dir_ / "model" / "m.xml").string(), "ball", 0.5,
               (dir_ / "out" / "applied.xml").string());
    ADD_FAILURE() << "applied";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("assets.xml (an <include> of the model) names t.obj"), std::string::npos)
        << what;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "applied.xml"));
}

}  // namespace
}  // namespace contact2d
