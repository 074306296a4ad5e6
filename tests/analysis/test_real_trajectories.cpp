// The trajectory fit (analysis/real_trajectories.hpp) on recordings made
// by the reference itself: 12 drops of the 0.06 m square with a known law,
// written as CSV in a temporary folder with a peer file (poses only) that
// is the recording moved 1 mm along x, then read back and fitted with no
// engines. And the trajectory reader's error for a time that does not
// increase.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "analysis/real_trajectories.hpp"
#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "core/stepper.hpp"
#include "io/recording.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;

constexpr double kFrameRate = 250.0;
constexpr int kTrajectories = 12;
constexpr int kSamples = 101;  // 0 … 0.4 s

class RealTrajectories : public ::testing::Test {
 public:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_real_trajectories_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }

  std::string manifest(bool peer) {
    std::string text = "kind = \"trajectories\"\ncsv = \"trajectories.csv\"\n";
    if (peer) text += "peer_csv = \"peer.csv\"\npeer = \"shifted\"\n";
    text +=
        "gravity = 9.81\nframe_rate = 250.0\n\n[body]\nshape = \"box\"\nwidth = 0.06\n"
        "height = 0.06\nmass = 1.0\n";
    return write("recording.toml", text);
  }

 private:
  fs::path dir_;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);  // round-trips the double exactly
  return text;
}

// The recording and its peer: kTrajectories drops from random starts, each
// sampled every frame by the scene the fit replays `law` with (its default
// ω·Δt, 0.05). The starts land nearly flat and slide (|vx| 0.8 … 1.6 m/s),
// so that every drop depends on μ as well as on the bounce.
void make_recording(const analysis::PenaltyParams& law, std::string& csv, std::string& peer) {
  Recording shape;
  shape.body = default_scene(Shape::Box);
  shape.body.width = shape.body.height = 0.06;
  shape.frame_rate = kFrameRate;
  const Scene scene = analysis::trajectory_replay_scene(shape, law, 0.05, 0.4);
  ReferenceStepper stepper(scene);
  csv = "traj,t,x,y,theta,vx,vy,omega\n";
  peer = "traj,t,x,y,theta\n";  // poses only: the velocity columns are optional there
  std::uint64_t rng = 47;
  auto uniform = [&rng](double lo, double hi) { return lo + (hi - lo) * next_uniform(rng); };
  for (int n = 1; n <= kTrajectories; ++n) {
    State s;
    s.q = Vec3(uniform(-0.1, 0.1), uniform(0.08, 0.15), uniform(-0.3, 0.3));
    s.v = Vec3((n % 2 ? 1.0 : -1.0) * uniform(0.8, 1.6), uniform(-2.0, -1.0), uniform(-2.0, 2.0));
    stepper.reset(s);
    long long at = 0;
    for (int i = 0; i < kSamples; ++i) {
      const double t = i / kFrameRate;
      for (const long long target = std::llround(t / scene.sim.dt); at < target; ++at)
        ASSERT_EQ(stepper.step(), StepStatus::Ok);
      const State& x = stepper.state();
      const std::string head = std::to_string(n) + "," + number(t) + ",";
      csv += head + number(x.q.x()) + "," + number(x.q.y()) + "," + number(x.q.z()) + "," +
             number(x.v.x()) + "," + number(x.v.y()) + "," + number(x.v.z()) + "\n";
      peer += head + number(x.q.x() + 1e-3) + "," + number(x.q.y()) + "," + number(x.q.z()) + "\n";
    }
  }
}

// Makes the recording with `law`, reads it back and fits it (no engines).
analysis::TrajectoryFit fit_own_recording(RealTrajectories& t, const analysis::PenaltyParams& law) {
  std::string csv, peer;
  make_recording(law, csv, peer);
  t.write("trajectories.csv", csv);
  t.write("peer.csv", peer);
  const Recording rec = read_recording(t.manifest(true));
  EXPECT_EQ(rec.trajectories.size(), static_cast<size_t>(kTrajectories));
  EXPECT_FALSE(rec.peer_trajectories.front().velocities);
  return analysis::fit_trajectories(rec, analysis::TrajectoryFitOptions{});
}

double parameter(const analysis::TrajectoryModel& m, const std::string& name) {
  for (const auto& [n, v] : m.parameters)
    if (n == name) return v;
  return NAN;
}

// The peer is the recording moved 1 mm along x: its error is 1 mm at every
// sample of every trajectory, to rounding (the positions are ~0.1 m, so
// 1e-12 m is ~1e4 units in the last place).
void expect_peer_one_millimetre_off(const analysis::TrajectorySplit& split) {
  ASSERT_EQ(split.models.size(), 2u);
  const analysis::TrajectoryModel& moved = split.models[1];
  EXPECT_EQ(moved.engine, "peer");
  EXPECT_EQ(moved.name, "shifted");
  EXPECT_NEAR(moved.points.q1, 1e-3, 1e-12) << split.split;
  EXPECT_NEAR(moved.points.q3, 1e-3, 1e-12) << split.split;
}

// A law on the fit's grid (log10 k 5, ζ 0.3, μ 0.15): the grid's point
// replays the recording bit for bit (the same scene, the same steps, the
// sample times on step times, the CSV's 17 digits round-trip), so the
// training median is 0, BOBYQA cannot improve on it and the held-out
// error is 0 exactly. Any slip in the start, the sampling or the split
// shows here.
TEST_F(RealTrajectories, ReplaysARecordingOfItsOwnLawBitForBit) {
  const analysis::PenaltyParams law{5.0, 0.3, 0.15, 0.0};
  const analysis::TrajectoryFit fit = fit_own_recording(*this, law);
  ASSERT_EQ(fit.splits.size(), 2u);
  EXPECT_EQ(fit.lifted, 0);
  EXPECT_EQ(fit.samples, static_cast<size_t>(kSamples));
  for (const analysis::TrajectorySplit& split : fit.splits) {
    ASSERT_FALSE(split.models.empty());
    const analysis::TrajectoryModel& ref = split.models[0];
    ASSERT_EQ(ref.engine, "ref");
    EXPECT_EQ(ref.points.q3, 0.0) << split.split;
    EXPECT_EQ(parameter(ref, "k"), 1e5) << split.split;
    EXPECT_EQ(parameter(ref, "zeta"), law.zeta) << split.split;
    EXPECT_EQ(parameter(ref, "mu"), law.mu) << split.split;
    expect_peer_one_millimetre_off(split);
  }
}

// A law off the grid (log10 k 5.1, ζ 0.28, μ 0.16), inside the basin of the
// grid's point (5, 0.3, 0.15): the fit refines that start with BOBYQA. The
// floor is 0 (the test above), but the error surface is rough: a replay of
// 0.4 s bounces and turns, and 0.003 in log10 k moves the training median
// by 5 mm here, so BOBYQA's trust region shrinks to its stopping size
// (relative 1e-4) before the error reaches 0. Measured: held-out medians
// 1.6 and 4.9 mm, μ and ζ within 0.002 of the law, log10 k within 0.06.
// Bounds, with a margin of 2 to 5 over those: 1 cm (a fifth of the square
// recording's held-out median, 0.047 m, docs/real-trajectories.md), 0.01 in
// μ and ζ, 0.2 in log10 k (the grid's spacing is 1, 0.2-0.3 and 0.1-0.25).
TEST_F(RealTrajectories, RecoversALawOffTheGrid) {
  const analysis::PenaltyParams law{5.1, 0.28, 0.16, 0.0};
  const analysis::TrajectoryFit fit = fit_own_recording(*this, law);
  ASSERT_EQ(fit.splits.size(), 2u);
  for (const analysis::TrajectorySplit& split : fit.splits) {
    ASSERT_FALSE(split.models.empty());
    const analysis::TrajectoryModel& ref = split.models[0];
    ASSERT_EQ(ref.engine, "ref");
    EXPECT_LT(ref.points.median, 0.01) << split.split;
    EXPECT_NEAR(parameter(ref, "mu"), law.mu, 0.01) << split.split;
    EXPECT_NEAR(parameter(ref, "zeta"), law.zeta, 0.01) << split.split;
    EXPECT_NEAR(std::log10(parameter(ref, "k")), law.log_k, 0.2) << split.split;
    expect_peer_one_millimetre_off(split);
  }
}

TEST_F(RealTrajectories, RefusesATimeThatDoesNotIncreaseNamingTheLineAndField) {
  const std::string path = write("trajectories.csv",
                                 "traj,t,x,y,theta,vx,vy,omega\n"
                                 "1,0.0,0,0.1,0,0,-1,0\n"
                                 "1,0.004,0,0.096,0,0,-1,0\n"
                                 "1,0.004,0,0.092,0,0,-1,0\n");
  try {
    read_recording(manifest(false));
    FAIL() << "a time that does not increase was read";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ":4: field 't' = 0.004 is not after"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
  }
}

}  // namespace
}  // namespace contact2d
