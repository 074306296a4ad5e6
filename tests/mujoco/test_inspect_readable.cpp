// inspect reads like an answer: the per-body table's header, load against
// weight per kinematic tree, and a model not at rest said once, first, with
// the settle time that brings it to rest (mujoco/inspect.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "mujoco/inspect.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco3/inspect_versions.hpp"

namespace contact2d::mujoco {
namespace {

namespace fs = std::filesystem;

std::string write_model(const std::string& name, const std::string& xml) {
  const fs::path path = fs::temp_directory_path() / ("contact2d_readable_" + name + ".xml");
  std::ofstream(path) << xml;
  return path.string();
}

// Two free boxes (1 kg and 2 kg as the file states), the second on the
// first, and a 0.5 kg rod on a hinge to the world resting its tip on the
// floor: three trees.
const char* kStack = R"(<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="low" pos="0 0 0.1">
      <freejoint/>
      <geom name="low" type="box" size="0.1 0.1 0.1" mass="1"/>
    </body>
    <body name="high" pos="0 0 0.3">
      <freejoint/>
      <geom name="high" type="box" size="0.05 0.05 0.1" mass="2"/>
    </body>
    <body name="rod" pos="1 0 0.2">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom name="rod" type="capsule" fromto="0 0 0 0.3 0 -0.19" size="0.01" mass="0.5"/>
    </body>
  </worldbody>
</mujoco>)";

// At rest each free tree's contacts carry its weight m·g (m from the file):
// the low box its own 1 kg plus nothing of the high box's (that is another
// tree, whose contact pushes the low box down), the high box its 2 kg; the
// hinged rod less than its weight (its hinge holds the rest).
TEST(InspectReadable, LoadAgainstWeightPerTree) {
  InspectOptions o;
  o.path = write_model("stack", kStack);
  o.settle = 2.0;
  const InspectReport rep = inspect(o);
  fs::remove(o.path);
  ASSERT_TRUE(rep.at_rest);
  ASSERT_EQ(rep.trees.size(), 3u);
  const double g = 9.81;
  EXPECT_EQ(rep.trees[0].root, "low");
  EXPECT_NEAR(rep.trees[0].weight, 1.0 * g, 1e-12);
  EXPECT_NEAR(rep.trees[0].support, 1.0 * g, 1e-3 * g);
  EXPECT_TRUE(rep.trees[0].free);
  EXPECT_EQ(rep.trees[1].root, "high");
  EXPECT_NEAR(rep.trees[1].weight, 2.0 * g, 1e-12);
  EXPECT_NEAR(rep.trees[1].support, 2.0 * g, 2e-3 * g);
  EXPECT_EQ(rep.trees[2].root, "rod");
  EXPECT_FALSE(rep.trees[2].free);
  EXPECT_GT(rep.trees[2].support, 0.0);
  EXPECT_LT(rep.trees[2].support, 0.5 * g);
  const std::string text = format_inspect_text(rep);
  EXPECT_NE(text.find("  body  contacts  load (sum)  deepest rest depth"), std::string::npos)
      << text;
  EXPECT_NE(text.find("load against weight, per kinematic tree"), std::string::npos);
  EXPECT_NE(text.find("(jointed to the world: its joints hold the rest)"), std::string::npos);
  EXPECT_EQ(text.find("NOT AT REST"), std::string::npos);
  const std::string json = format_inspect_json(rep);
  EXPECT_NE(json.find("\"trees\": ["), std::string::npos);
  EXPECT_NE(json.find("{\"root\": \"high\", \"bodies\": 1, \"mass\": 2,"), std::string::npos)
      << json;
}

// A box dropped from 5 cm is not at rest after 0.2 s: the text says so
// once, right after the model line, with the settle time after which it is
// — the first of 1, 2, 4 … s at which read_model_state finds it at rest
// (measured here on its own) — and no contact repeats "a longer --settle".
TEST(InspectReadable, NotAtRestSaysHowLongFirst) {
  const std::string path = write_model("drop", R"(<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="box" pos="0 0 0.15">
      <freejoint/>
      <geom name="box" type="box" size="0.1 0.1 0.1" mass="1"/>
    </body>
  </worldbody>
</mujoco>)");
  InspectOptions o;
  o.path = path;
  o.settle = 0.2;
  InspectReport rep = inspect(o);
  ASSERT_FALSE(rep.at_rest);
  ASSERT_FALSE(rep.contacts.empty());
  mujoco3::settle_time(rep, o, "mujoco");
  double expected = NAN;
  for (double settle = 1.0; settle <= 120.0; settle *= 2.0) {
    StateRequest request;
    request.path = path;
    request.settle = settle;
    if (at_rest(read_model_state(request))) {
      expected = settle;
      break;
    }
  }
  fs::remove(path);
  ASSERT_TRUE(std::isfinite(expected));
  EXPECT_DOUBLE_EQ(rep.rest_after, expected);
  const std::string text = format_inspect_text(rep);
  const size_t second_line = text.find('\n') + 1;
  EXPECT_EQ(text.find("NOT AT REST"), second_line) << text;
  EXPECT_EQ(text.find("NOT AT REST", second_line + 1), std::string::npos);
  char settle[64];
  std::snprintf(settle, sizeof settle, "run with --settle %g.", expected);
  EXPECT_NE(text.find(settle), std::string::npos) << text;
  EXPECT_EQ(text.find("not known:"), std::string::npos) << text;
  EXPECT_EQ(text.find("(a longer --settle)"), std::string::npos) << text;
  EXPECT_NE(format_inspect_json(rep).find("\"rest_after\": " +
                                          std::to_string(static_cast<int>(expected))),
            std::string::npos);
}

}  // namespace
}  // namespace contact2d::mujoco
