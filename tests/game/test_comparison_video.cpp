// `compare --video` as a library call (game/comparison_video.hpp), under
// Xvfb (ctest runs this through xvfb-run, label "window"): the video has
// comparison_video_frames(duration, fps) = round(duration·fps) frames, as
// ffprobe counts them, and a decoded frame shows both engines' body colours
// in the world area (below the HUD, whose legend also holds them). The
// "MuJoCo" trajectory here is the reference shifted sideways by 0.6 m, so
// the two bodies never overlap and both colours must be visible.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/input_error.hpp"
#include "engines/engines.hpp"
#include "game/comparison_video.hpp"
#include "game/video.hpp"
#include "reference/dense_reference.hpp"
#include "support/files.hpp"
#include "support/needs.hpp"
#include "support/stand_in.hpp"

namespace fs = std::filesystem;
using namespace contact2d;

namespace {

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("contact2d_video_" + std::to_string(::getpid()) + "_" + name);
}

using contact2d::test::read_file;

int sh(const std::string& command) {
  const int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::string capture(const std::string& command) {
  const fs::path out = temp("capture");
  sh(command + " >'" + out.string() + "' 2>/dev/null");
  std::string text = read_file(out);
  fs::remove(out);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

long count_frames(const fs::path& video) {
  return std::atol(capture("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                           "stream=nb_read_frames -of csv=p=0 '" +
                           video.string() + "'")
                       .c_str());
}

// Frame n (from 0) decoded to RGB, top row first.
std::vector<unsigned char> decode_frame(const fs::path& video, int n) {
  const fs::path raw = temp("frame.rgb");
  sh("ffmpeg -loglevel error -y -i '" + video.string() + "' -vf 'select=eq(n\\," +
     std::to_string(n) + ")' -frames:v 1 -f rawvideo -pix_fmt rgb24 '" + raw.string() + "'");
  const std::string bytes = read_file(raw);
  fs::remove(raw);
  return {bytes.begin(), bytes.end()};
}

// Pixels of the world area (below the HUD band) within `tolerance` of a
// colour in every channel.
long count_colour(const std::vector<unsigned char>& rgb, int width, int height,
                  const int (&colour)[3], int tolerance) {
  long n = 0;
  for (int y = game::kComparisonHudHeight; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i =
          3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
      bool near = true;
      for (int c = 0; c < 3; ++c)
        near = near && std::abs(rgb[i + static_cast<size_t>(c)] - colour[c]) <= tolerance;
      n += near ? 1 : 0;
    }
  }
  return n;
}

struct Fixture {
  Scene scene;
  Trajectory reference, mujoco;
  DenseTrajectory converged;
  game::ComparisonVideoInput input;

  Fixture() {
    scene = default_scene(Shape::Box);
    scene.sim.duration = 0.5;
    reference = engines::run_engine("ref", scene).trajectory;
    mujoco = reference;
    for (Sample& s : mujoco.samples) s.state.q.x() += 0.6;
    converged = converged_reference(scene, 1e-8);
    input.scene = &scene;
    input.reference = &reference;
    input.second = &mujoco;
    input.converged = &converged;
    input.title = "box: ref vs ref shifted by 0.6 m (test)";
  }
};

constexpr int kWidth = 960, kHeight = 540, kFps = 20;

// Writes the fixture's video through `backend` and checks it; returns
// frame 5 decoded.
std::vector<unsigned char> check_mp4(game::OffscreenBackend backend, const std::string& name) {
  const Fixture f;
  EXPECT_TRUE(f.converged.ok()) << f.converged.failure();
  const fs::path video = temp(name + ".mp4");
  game::write_comparison_video(video.string(), f.input, kFps, kWidth, kHeight, backend);
  EXPECT_FALSE(fs::exists(video.string() + ".tmp"));
  EXPECT_TRUE(fs::exists(video));

  // 0.5 s at 20 fps: frames at t = 0, 0.05, …, 0.45 s.
  const long expected = static_cast<long>(game::comparison_video_frames(0.5, kFps));
  EXPECT_EQ(expected, 10);
  const long frames = count_frames(video);
  EXPECT_EQ(frames, expected);
  EXPECT_EQ(capture("ffprobe -v error -select_streams v:0 -show_entries stream=width,height "
                    "-of csv=p=0 '" +
                    video.string() + "'"),
            "960,540");

  // Tolerance: frames are encoded as H.264 in yuv420p (8-bit limited-range
  // Y'CbCr, chroma shared by 2×2 pixels, crf 20). A flat area's colour comes
  // back within a few levels per channel (range quantisation ±2, encoder
  // error a few more); pixels whose 2×2 block straddles an edge get a mixed
  // chroma and fall outside. ±24 per channel keeps the interiors of the
  // filled body and of MuJoCo's 4 px outline and no other colour drawn (the
  // nearest, the ground and the background, are > 100 levels away in some
  // channel).
  std::vector<unsigned char> rgb = decode_frame(video, 5);
  EXPECT_EQ(rgb.size(), static_cast<size_t>(kWidth) * kHeight * 3);
  if (rgb.size() != static_cast<size_t>(kWidth) * kHeight * 3) return {};
  const long ref = count_colour(rgb, kWidth, kHeight, game::kReferenceRgb, 24);
  const long mj = count_colour(rgb, kWidth, kHeight, game::kSecondRgb, 24);
  const long conv = count_colour(rgb, kWidth, kHeight, game::kConvergedRgb, 40);
  std::printf(
      "mp4 (%s): %ld frames (expected %ld); frame 5: reference colour %ld px, MuJoCo "
      "colour %ld px, converged (dark) %ld px\n",
      name.c_str(), frames, expected, ref, mj, conv);
  // The box is ~0.4 × 0.2 m in a view a few metres across: thousands of
  // pixels filled, its outline several hundred.
  EXPECT_GT(ref, 1000);
  EXPECT_GT(mj, 200);
  fs::remove(video);
  return rgb;
}

TEST(ComparisonVideo, Mp4HasDurationTimesFpsFramesAndBothColoursThroughEgl) {
  CONTACT2D_NEEDS(game::offscreen_egl_built(), "built without libEGL");
  check_mp4(game::OffscreenBackend::Egl, "egl");
}

TEST(ComparisonVideo, Mp4HasDurationTimesFpsFramesAndBothColoursThroughAWindow) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "no X display: run under xvfb-run (ctest does)";
  const std::vector<unsigned char> window = check_mp4(game::OffscreenBackend::Window, "window");
  // Both backends draw with the same renderer (here both Mesa's llvmpipe):
  // the same picture.
  if (game::offscreen_egl_built() && !window.empty()) {
    const std::vector<unsigned char> egl = check_mp4(game::OffscreenBackend::Egl, "egl");
    // In the world area: the HUD's text at scale 1.5 lands on fractional
    // pixels, where the two contexts round a few glyph edges differently.
    long differ = 0;
    const size_t from = static_cast<size_t>(game::kComparisonHudHeight) * kWidth * 3;
    for (size_t i = from; i < std::min(egl.size(), window.size()); ++i)
      differ += std::abs(egl[i] - window[i]) > 24 ? 1 : 0;
    std::printf("EGL and window frames: %ld bytes of the world area differ by more than 24\n",
                differ);
    EXPECT_LT(differ, 50);
  }
}

TEST(ComparisonVideo, GifHasTheSameFramesAndColours) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "no X display: run under xvfb-run (ctest does)";
  const Fixture f;
  const fs::path video = temp("both.GIF");  // the extension's case does not matter
  game::write_comparison_video(video.string(), f.input, kFps, kWidth, kHeight);  // Auto
  EXPECT_FALSE(fs::exists(video.string() + ".tmp"));
  ASSERT_TRUE(fs::exists(video));
  EXPECT_EQ(capture("ffprobe -v error -select_streams v:0 -show_entries stream=codec_name "
                    "-of csv=p=0 '" +
                    video.string() + "'"),
            "gif");
  const long frames = count_frames(video);
  EXPECT_EQ(frames, game::comparison_video_frames(0.5, kFps));
  // A GIF's palette (palettegen over all frames, no dithering) holds every
  // colour of these few-colour frames exactly; ±4 allows for a palette
  // entry merged with a neighbour.
  const std::vector<unsigned char> rgb = decode_frame(video, 5);
  ASSERT_EQ(rgb.size(), static_cast<size_t>(kWidth) * kHeight * 3);
  const long ref = count_colour(rgb, kWidth, kHeight, game::kReferenceRgb, 4);
  const long mj = count_colour(rgb, kWidth, kHeight, game::kSecondRgb, 4);
  std::printf("gif: %ld frames; frame 5: reference colour %ld px, MuJoCo colour %ld px\n", frames,
              ref, mj);
  EXPECT_GT(ref, 1000);
  EXPECT_GT(mj, 200);
  fs::remove(video);
}

TEST(ComparisonVideo, OtherExtensionsAreRefusedNamingTheOption) {
  const Fixture f;
  for (const std::string name : {"clip.avi", "clip", "clip.mp4.txt", "dir.mp4/clip"}) {
    const fs::path video = temp(name);
    try {
      game::write_comparison_video(video.string(), f.input, kFps, kWidth, kHeight);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("--video"), std::string::npos) << what;
      EXPECT_NE(what.find(".mp4 or .gif"), std::string::npos) << what;
    }
    EXPECT_FALSE(fs::exists(video));
    EXPECT_FALSE(fs::exists(video.string() + ".tmp"));
  }
}

// A writer dropped before finish() (an exception left the frame loop)
// leaves neither the video nor its temporary: a video appears only complete.
TEST(ComparisonVideo, AnAbandonedWriterLeavesNoFile) {
  const fs::path video = temp("abandoned.mp4");
  {
    game::VideoWriter writer(video.string(), 64, 64, kFps, game::VideoFormat::Mp4, "--video");
    const std::vector<unsigned char> grey(64 * 64 * 3, 128);
    // Frames until ffmpeg has written to its output (up to 10 s).
    bool started = false;
    for (int i = 0; i < 1000 && !started; ++i) {
      ASSERT_TRUE(writer.write(grey));
      started = test::temporary_size(video) > 0;
      if (!started) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(started);
  }
  EXPECT_FALSE(fs::exists(video));
  EXPECT_EQ(test::temporary_size(video), -1);
}

// Without a display: the window backend fails with one line saying what to
// do; Auto still writes the video when EGL surfaceless is there.
TEST(ComparisonVideo, WithoutADisplay) {
  const Fixture f;
  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  ::unsetenv("DISPLAY");
  const fs::path video = temp("nodisplay.mp4");
  try {
    game::write_comparison_video(video.string(), f.input, kFps, kWidth, kHeight,
                                 game::OffscreenBackend::Window);
    ADD_FAILURE() << "opened a window without a display";
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::printf("window backend without DISPLAY: %s\n", what.c_str());
    EXPECT_EQ(what.find("--video needs a display: run under xvfb-run, or set DISPLAY"), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(video));
  EXPECT_FALSE(fs::exists(video.string() + ".tmp"));
  if (game::offscreen_egl_built()) {
    game::write_comparison_video(video.string(), f.input, kFps, kWidth, kHeight);
    EXPECT_EQ(count_frames(video), game::comparison_video_frames(0.5, kFps));
    std::printf("Auto without DISPLAY (EGL surfaceless): %ld frames\n", count_frames(video));
    fs::remove(video);
  }
  if (display) ::setenv("DISPLAY", saved.c_str(), 1);
}

}  // namespace

// Through the program: `contact2d compare SCENE --video FILE` writes the
// scene's duration × 30 frames (a 0.5 s scene: 15), and a bad extension is
// refused before any engine runs, with nothing left behind.
#ifdef CONTACT2D_EXE_WITH_MUJOCO
TEST(ComparisonVideo, CompareWritesTheVideoThroughTheProgram) {
  const fs::path scene = temp("scene.toml");
  std::ofstream(scene) << "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\nmu = 0.5\n"
                          "damping = \"kelvin_voigt\"\n[initial]\ny = 0.5\ntheta = 0.3\n"
                          "[sim]\ndt = 1e-4\nduration = 0.5\n";
  const fs::path video = temp("compare.mp4");
  const std::string exe = CONTACT2D_EXE_WITH_MUJOCO;
  ASSERT_EQ(sh("'" + exe + "' compare '" + scene.string() + "' --no-diagnosis --video '" +
               video.string() + "' >/dev/null"),
            0);
  EXPECT_EQ(count_frames(video), 15);
  fs::remove(video);
  const fs::path bad = temp("compare.avi");
  EXPECT_EQ(sh("'" + exe + "' compare '" + scene.string() + "' --video '" + bad.string() +
               "' >/dev/null 2>&1"),
            2);
  EXPECT_FALSE(fs::exists(bad));
  EXPECT_FALSE(fs::exists(bad.string() + ".tmp"));
  fs::remove(scene);
}
#endif

// A full disk: ffmpeg cannot write all of its file, and may still exit 0
// (an MP4 without its index, "moov atom not found", or a GIF cut short).
// The equivalent here is a file-size limit the test sets on the program
// alone (ulimit -f; SIGXFSZ ignored, so a write past it fails with EFBIG as
// on a full disk): 16 KiB, below the 37 KiB (MP4) and 41 KiB (GIF) the
// 15-frame video takes. ffmpeg exits 0 on both (measured), leaving an MP4
// that does not decode and a GIF of 4 frames; compare must fail with one
// line and leave nothing at the path.
#ifdef CONTACT2D_EXE_WITH_MUJOCO
TEST(ComparisonVideo, AVideoThatCannotBeWrittenWhollyIsAnErrorWithNoFile) {
  const fs::path dir = temp("full");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.toml") << "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\nmu = 0.5\n"
                                       "damping = \"kelvin_voigt\"\n[initial]\ny = 0.5\n"
                                       "theta = 0.3\n[sim]\ndt = 1e-4\nduration = 0.5\n";
  const std::string exe = CONTACT2D_EXE_WITH_MUJOCO;
  for (const std::string name : {"full.mp4", "full.gif"}) {
    const int status =
        sh("cd '" + dir.string() + "' && bash -c \"ulimit -f 16; trap '' XFSZ; exec '" + exe +
           "' compare scene.toml --no-diagnosis --video " + name + "\" >out.txt 2>err.txt");
    const std::string err = read_file(dir / "err.txt");
    std::printf("%s under a 16 KiB file limit: exit %d: %s", name.c_str(), status, err.c_str());
    EXPECT_NE(status, 0) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find("no video written"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / name));
    EXPECT_EQ(test::temporary_size(dir / name), -1);
  }
  fs::remove_all(dir);
}
#endif

namespace {

// A stand-in for ffmpeg or gnuplot, first on PATH: a shell script.
void fake_tool(const fs::path& bin, const std::string& name, const std::string& body) {
  fs::create_directories(bin);
  std::ofstream(bin / name) << "#!/bin/sh\n" << body;
  fs::permissions(bin / name, fs::perms::owner_all);
}

}  // namespace

// ffmpeg that exits 0 having written a file with fewer frames than it was
// given (here: it drops its input and writes a one-frame video): the frame
// count is checked, the file is not a video of the run.
TEST(ComparisonVideo, AFileWithMissingFramesIsRefusedThoughFfmpegSucceeded) {
  const fs::path dir = temp("short");
  fs::remove_all(dir);
  const std::string real = capture("command -v ffmpeg");
  ASSERT_FALSE(real.empty());
  // Writes one grey frame to the last argument (the output), ignores stdin.
  fake_tool(dir / "bin", "ffmpeg",
            "for last; do :; done\ncat >/dev/null\nexec '" + real +
                "' -loglevel error -y -f lavfi -i color=c=gray:s=64x64:d=0.04 -frames:v 1 "
                "-f mp4 \"$last\"\n");
  const char* old_path = std::getenv("PATH");
  const std::string saved = old_path ? old_path : "";
  ::setenv("PATH", ((dir / "bin").string() + ":" + saved).c_str(), 1);
  const fs::path video = dir / "short.mp4";
  try {
    game::VideoWriter writer(video.string(), 64, 64, kFps, game::VideoFormat::Mp4, "--video");
    const std::vector<unsigned char> grey(64 * 64 * 3, 128);
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(writer.write(grey));
    writer.finish();
    ADD_FAILURE() << "a one-frame file was taken for five frames";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ffmpeg's file has 1 of the 5 frames written"), std::string::npos) << what;
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_FALSE(fs::exists(video));
  EXPECT_EQ(test::temporary_size(video), -1);
  fs::remove_all(dir);
}

// An interrupt while the video is being made: compare's CSV and plot are
// finished by then, and must go with the video, not stay as the outputs of
// a run that did not end (they were once committed as each was done). The
// ffmpeg here is a stand-in first on PATH that notes its PID and waits.
#ifdef CONTACT2D_EXE_WITH_MUJOCO
TEST(ComparisonVideo, AnInterruptedCompareLeavesNoneOfItsOutputs) {
  const fs::path root = temp("interrupted");
  fs::remove_all(root);
  const fs::path dir = root / "work";
  fs::create_directories(dir);
  const fs::path mark = test::write_stand_in(root, "ffmpeg");
  std::ofstream(dir / "scene.toml") << "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\nmu = 0.5\n"
                                       "damping = \"kelvin_voigt\"\n[initial]\ny = 0.5\n"
                                       "theta = 0.3\n[sim]\ndt = 1e-4\nduration = 0.5\n";
  const test::Interrupted r =
      test::interrupt_while_tool_runs(root, dir, mark, CONTACT2D_EXE_WITH_MUJOCO,
                                      {"compare", "scene.toml", "--no-diagnosis", "--csv",
                                       "out.csv", "--plot", "out.png", "--video", "out.mp4"});
  ASSERT_TRUE(r.tool_started) << "ffmpeg was not started";
  EXPECT_EQ(r.exit_status, 128 + SIGINT);
  EXPECT_FALSE(r.tool_outlived) << "ffmpeg still ran after the program ended";
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename() != "scene.toml") left.push_back(entry.path().filename());
  EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
  fs::remove_all(root);
}
#endif
