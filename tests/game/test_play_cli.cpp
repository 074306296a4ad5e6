// contact2d play --headless through the real program: the shipped goal
// replay, determinism of replays, record → replay round trips, and bad input
// (exit 2, one line naming the key or line and the allowed range).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/format.hpp"
#include "game/policy.hpp"
#include "support/files.hpp"

namespace fs = std::filesystem;

namespace {

struct Result {
  int status = -1;
  std::string out;
  std::string err;
};

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("contact2d_play_" + std::to_string(::getpid()) + "_" + name);
}

using contact2d::test::read_file;

Result run(const std::string& args) {
  const fs::path out = temp("stdout"), err = temp("stderr");
  const std::string command = std::string("'") + CONTACT2D_EXE + "' " + args + " >'" +
                              out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

const std::string kGoalReplay = CONTACT2D_SOURCE_DIR "/validation/replays/goal.replay";
const std::string kPitch = CONTACT2D_SOURCE_DIR "/validation/scenes/game/pitch.toml";

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PlayCli, TheShippedGoalReplayScoresWithTheReferenceEngine) {
  const Result r = run("play --headless --replay '" + kGoalReplay + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has(r.out, "\"goal\":true")) << r.out;
  EXPECT_TRUE(has(r.out, "\"outcome\":\"goal\"")) << r.out;
  EXPECT_TRUE(has(r.out, "\"counted\":true")) << r.out;
  EXPECT_TRUE(has(r.out, "\"engine\":\"ref\"")) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one JSON line";
  EXPECT_EQ(r.err, "") << "the replay matches the shipped pitch";
}

TEST(PlayCli, TheSameReplayGivesTheSameJsonTwice) {
  const Result a = run("play --headless --replay '" + kGoalReplay + "'");
  const Result b = run("play --headless --replay '" + kGoalReplay + "'");
  ASSERT_EQ(a.status, 0);
  EXPECT_EQ(a.out, b.out);
}

TEST(PlayCli, ARoundWithNoInputScoresNoGoal) {
  const Result r = run("play --headless --seed 7");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has(r.out, "\"goal\":false")) << r.out;
  EXPECT_TRUE(has(r.out, "\"kicks\":[]")) << r.out;
  EXPECT_TRUE(has(r.out, "\"seed\":7")) << r.out;
}

TEST(PlayCli, RecordingAReplayAndPlayingItBackGivesTheSameJson) {
  // --record-input on a replayed session writes the inputs it applied; that
  // file replays to the same outcome and is the same file.
  const fs::path copy = temp("copy.replay");
  const Result a =
      run("play --headless --replay '" + kGoalReplay + "' --record-input '" + copy.string() + "'");
  ASSERT_EQ(a.status, 0) << a.err;
  const Result b = run("play --headless --replay '" + copy.string() + "'");
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(a.out, b.out);
  const Result c = run("play --headless --replay '" + copy.string() + "' '" + kPitch + "'");
  EXPECT_EQ(a.out, c.out) << "the built-in pitch is the shipped file";
  fs::remove(copy);
}

// The built-in players: --seeds prints one line of statistics; a single
// scripted round records a replay that plays back to the same JSON.
TEST(PlayCli, TheBuiltInPlayersPlayThroughTheRealProgram) {
  const Result stats = run("play --headless --policy blind --seeds 3");
  ASSERT_EQ(stats.status, 0) << stats.err;
  EXPECT_TRUE(has(stats.out, "\"policy\":\"blind\"")) << stats.out;
  EXPECT_TRUE(has(stats.out, "\"seeds\":3,\"goals\":0")) << stats.out;
  EXPECT_EQ(std::count(stats.out.begin(), stats.out.end(), '\n'), 1) << stats.out;

  const fs::path recorded = temp("scripted.replay");
  const Result a =
      run("play --headless --policy scripted --seed 3 --record-input '" + recorded.string() + "'");
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_TRUE(has(a.out, "\"goal\":true")) << a.out;
  const Result b = run("play --headless --replay '" + recorded.string() + "'");
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(a.out, b.out);
  fs::remove(recorded);
}

// Where the scripted player stops the ball has one source
// (game::kScriptedDribbleTo): `play --help` prints it (it said 2 m while the
// player stopped at 2.5 m) and docs/game.md states the same number.
TEST(PlayCli, TheScriptedPlayersDribbleDistanceIsOneNumber) {
  const std::string metres =
      contact2d::format_number("%g", contact2d::game::kScriptedDribbleTo) + " m";
  const Result help = run("play --help");
  ASSERT_EQ(help.status, 0) << help.err;
  EXPECT_TRUE(has(help.out, "dribbles to " + metres + " from the goal line")) << help.out;
  const std::string docs = read_file(CONTACT2D_SOURCE_DIR "/docs/game.md");
  EXPECT_TRUE(has(docs, "dribbles it to " + metres + " from the line")) << "docs/game.md";
}

#ifdef CONTACT2D_WITH_MUJOCO
// The same replay on the MuJoCo engine: the same JSON twice (MuJoCo's step
// is deterministic on one machine, and the player's force reaches it as the
// same xfrc_applied at the same steps), naming the engine.
TEST(PlayCli, AMujocoReplayGivesTheSameJsonTwice) {
  const Result a = run("play --headless --engine mujoco --replay '" + kGoalReplay + "'");
  const Result b = run("play --headless --engine mujoco --replay '" + kGoalReplay + "'");
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_TRUE(has(a.out, "\"engine\":\"mujoco\"")) << a.out;
  EXPECT_TRUE(has(a.out, "\"kicks\":[{")) << a.out;
}
#endif

TEST(PlayCli, ADivergingPitchExitsThreeWithTheDiagnosis) {
  // A contact 1000 times stiffer at a 500 times larger step: ω·Δt ≈ 24,
  // far past semi-implicit Euler's limit of ~1.7 at this damping.
  std::string text = read_file(kPitch);
  const auto set = [&](const std::string& key, const std::string& value) {
    const size_t at = text.find("\n" + key + " = ");
    ASSERT_NE(at, std::string::npos) << key;
    text.replace(at + 1, text.find('\n', at + 1) - at - 1, key + " = " + value);
  };
  set("k", "1e8");
  set("dt", "5e-3");
  const fs::path pitch = temp("diverging.toml");
  std::ofstream(pitch) << text;
  const Result r = run("play --headless --seed 1 '" + pitch.string() + "'");
  EXPECT_EQ(r.status, 3) << r.out << r.err;
  EXPECT_TRUE(has(r.out, "\"outcome\":\"diverged\"")) << r.out;
  EXPECT_TRUE(has(r.err, "simulation diverged")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  fs::remove(pitch);
}

struct BadPlay {
  const char* name;
  const char* pitch_extra;  // appended to a copy of the shipped pitch ("" = no pitch file)
  const char* replay_text;  // a replay file's contents ("" = none)
  const char* args;         // further arguments
  const char* expected;     // part of the one-line message
};

class PlayBadInput : public ::testing::TestWithParam<BadPlay> {};

TEST_P(PlayBadInput, ExitsTwoWithOneLineNamingTheProblem) {
  const BadPlay& c = GetParam();
  std::string args = "play --headless ";
  const fs::path pitch = temp(std::string(c.name) + ".toml"),
                 replay = temp(std::string(c.name) + ".replay");
  if (*c.pitch_extra) {
    std::string text = read_file(kPitch);
    // Replace a [game] key by appending a second [game]-free override: TOML
    // forbids duplicate keys, so edit the value in place.
    const std::string extra = c.pitch_extra;
    const size_t eq = extra.find('=');
    const std::string key = extra.substr(0, eq);
    const size_t at = text.find("\n" + key + "=");
    if (at != std::string::npos) {
      const size_t end = text.find('\n', at + 1);
      text.replace(at + 1, end - at - 1, extra);
    } else {
      text += "\n" + extra + "\n";
    }
    std::ofstream(pitch) << text;
    args += "'" + pitch.string() + "' ";
  }
  if (*c.replay_text) {
    std::ofstream(replay) << c.replay_text;
    args += "--replay '" + replay.string() + "' ";
  }
  const Result r = run(args + c.args);
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_TRUE(has(r.err, c.expected)) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.out, "");
  fs::remove(pitch);
  fs::remove(replay);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PlayBadInput,
    ::testing::Values(
        BadPlay{"unknown_game_key", "speed = 3", "", "",  // appended: the file ends inside [game]
                "unknown key 'game.speed' (allowed here: control_force, control_time, crossbar, "
                "goal_line, keeper,"},
        BadPlay{"keeper_is_the_crossbar", "keeper =0", "", "",
                "game.keeper = 0 is out of range: must be -1 (no keeper) or the index of a box in "
                "[[obstacle]] other than the crossbar"},
        BadPlay{"keeper_above_the_bar", "keeper =1", "", "",
                "game.keeper = 1 is out of range: must be a box whose top is below the crossbar's "
                "underside (2.44 m)"},
        BadPlay{"keeper_speed_negative", "keeper_speed_hard =-1.0", "", "",
                "game.keeper_speed_hard = -1 is out of range: must be in [0, 100] m/s"},
        BadPlay{"power_below_min", "kick_power =0.2", "", "",
                "game.kick_power = 0.2 is out of range: must be in [game.kick_power_min, 1] = "
                "[0.3, 1]"},
        BadPlay{"lift_order", "pass_lift_min =4.0", "", "",
                "game.pass_lift_max = 3.5 is out of range: must be >= game.pass_lift_min = 4 m/s"},
        BadPlay{"bad_level", "", "", "--level insane",
                "--level insane: must be easy, normal or hard"},
        BadPlay{"bad_policy", "", "", "--policy random",
                "--policy random: must be blind or scripted"},
        BadPlay{"seeds_without_policy", "", "", "--seeds 3",
                "--seeds 3: counts the rounds a --policy plays; give --policy blind|scripted"},
        BadPlay{"level_conflict", "", "contact2d-replay 1\nseed 1\ndt 1e-05\nlevel hard\n",
                "--level easy", "--level easy conflicts with the replay's level hard"},
        BadPlay{"replay_bad_level", "", "contact2d-replay 1\nseed 1\ndt 1e-05\nlevel insane\n", "",
                ":4: level must be easy, normal or hard"},
        BadPlay{"kick_negative", "kick_impulse =-1.0", "", "",
                "game.kick_impulse = -1 is out of range: must be in [0, 1e4] N·s"},
        BadPlay{"crossbar_missing", "crossbar =7", "", "",
                "game.crossbar = 7 is out of range: must be the index of a box in [[obstacle]]"},
        BadPlay{"pass_order", "pass_speed_max =1.0", "", "",
                "game.pass_speed_max = 1 is out of range: must be >= game.pass_speed_min = 3 m/s"},
        BadPlay{"angle_outside", "kick_angle =75.0", "", "",
                "game.kick_angle = 75 is out of range"},
        BadPlay{"replay_garbage", "", "hello\n", "", ":1: not a replay file"},
        BadPlay{"replay_bad_key", "", "contact2d-replay 1\nseed 1\ndt 1e-05\n10 jump down\n", "",
                ":4: key 'jump' is not one of left, right, up, down, kick, angle_up, angle_down, "
                "reset, control, power_up, power_down, level_easy, level_normal, level_hard"},
        BadPlay{"replay_bad_order", "",
                "contact2d-replay 1\nseed 1\ndt 1e-05\n10 kick down\n5 kick up\n", "",
                ":5: step 5 is earlier than the line before"},
        BadPlay{"replay_no_seed", "", "contact2d-replay 1\ndt 1e-05\n", "", "missing 'seed' line"},
        BadPlay{"replay_dt_mismatch", "", "contact2d-replay 1\nseed 1\ndt 1e-4\n", "",
                "dt 0.0001 s does not match the pitch's sim.dt = 1e-05 s"},
        BadPlay{"seed_conflict", "", "contact2d-replay 1\nseed 1\ndt 1e-05\n", "--seed 2",
                "--seed 2 conflicts with the replay's seed 1"},
        BadPlay{"record_headless", "", "", "--record /tmp/x.mp4", "--record needs the window"},
        BadPlay{"missing_pitch", "", "", "/nonexistent/pitch.toml", "cannot read pitch file"},
        BadPlay{"missing_replay", "", "", "--replay /nonexistent/x.replay",
                "cannot read replay file"},
        BadPlay{"bad_seed", "", "", "--seed -3",
                "--seed -3: must be an integer in [0, 18446744073709551615]"},
        BadPlay{"huge_seed", "", "", "--seed 18446744073709551616",
                "--seed 18446744073709551616: must be an integer"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
