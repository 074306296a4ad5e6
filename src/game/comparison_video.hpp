// Two engines on screen (`contact2d compare --video FILE`): the bodies of
// the reference and a second engine (MuJoCo by default) overlaid in real
// time, drawn with the game's
// renderer (game/draw2d.hpp) offscreen (game/offscreen.hpp: EGL surfaceless,
// else a hidden GLFW window) and piped to ffmpeg
// (game/video.hpp: "<FILE>.tmp", renamed when complete, removed on Ctrl-C).
//
//   reference   filled, orange (kReferenceRgb)
//   second      outlined, blue (kSecondRgb), 4 px
//   converged   a thin dark outline (1.5 px), when given
//
// with the ground (and the scene's obstacles), a HUD with the title, the
// time, the distance between the centres of mass of the bodies shown, and
// a legend. The camera holds every sample of both trajectories (and the
// converged solution at the frame times) and the ground in view, at one
// scale for x and y; the second run's samples widen the reference's view by at most
// its own size on each side (a run blowing up leaves the frame rather than
// shrinking the bodies to dots).
//
// Real time: frame i shows t_i = i / fps, i = 0 … N − 1 with
// N = comparison_video_frames(duration, fps) = max(1, round(duration·fps)):
// a frame is shown from its time for 1/fps, so the video lasts exactly the
// scene's duration. States are interpolated linearly between samples; a
// trajectory that ended early (divergence) holds its last state and the HUD
// says when it stopped. The converged solution is drawn up to its t_end.
//
// Offscreen: by default EGL on Mesa's surfaceless platform (no display
// needed), else a hidden window on the X display (Xvfb will do:
// `xvfb-run -a contact2d compare ...`); with neither it throws InputError
// "--video needs a display: run under xvfb-run, or set DISPLAY (...)".
#pragma once

#include <memory>
#include <string>

#include "core/run.hpp"
#include "core/scene.hpp"
#include "game/offscreen.hpp"
#include "io/atomic_file.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::game {

struct ComparisonVideoInput {
  const Scene* scene = nullptr;                // shape, geometry, obstacles, sim.duration
  const Trajectory* reference = nullptr;       // drawn filled
  const Trajectory* second = nullptr;          // drawn outlined
  const DenseTrajectory* converged = nullptr;  // may be null: a thin outline when present
  std::string
      title;  // e.g. "box: ref vs MuJoCo, semi_implicit_euler (MuJoCo Euler), calibrated mapping"
  std::string reference_label = "reference";  // legend and HUD names
  std::string second_label = "second";
};

// The body colours (sRGB, 0-255) as drawn; what a decoded frame shows within
// the encoder's error.
inline constexpr int kReferenceRgb[3] = {242, 140, 26};
inline constexpr int kSecondRgb[3] = {26, 89, 217};
inline constexpr int kConvergedRgb[3] = {20, 20, 20};
// Height of the HUD band at the top of every frame, pixels; the world is
// drawn below it.
inline constexpr int kComparisonHudHeight = 84;

// Number of frames of a video of `duration` seconds at `fps`:
// max(1, round(duration·fps)).
long long comparison_video_frames(double duration, int fps);

// Throws InputError unless `path` ends in .mp4 or .gif (any case): the check
// write_comparison_video makes first, for a command to fail before its runs.
void check_video_path(const std::string& path);

// Writes the video. Throws InputError for a bad path (see check_video_path),
// a missing input, fps outside [1, 240], a size that is odd or outside
// [64, 4096], no offscreen context (see above), or ffmpeg failing or
// leaving a file that does not decode with every frame (game/video.hpp);
// nothing is left at `path` then. `backend` chooses the offscreen context
// (tests pin one; a command leaves it at Auto).
void write_comparison_video(const std::string& path, const ComparisonVideoInput& input,
                            int fps = 30, int width = 960, int height = 540,
                            OffscreenBackend backend = OffscreenBackend::Auto);

// The same video, finished and checked but not yet in place: a command
// commits it together with its other outputs, so that an interrupt leaves
// all of them or none.
std::unique_ptr<AtomicFile> render_comparison_video(
    const std::string& path, const ComparisonVideoInput& input, int fps = 30, int width = 960,
    int height = 540, OffscreenBackend backend = OffscreenBackend::Auto);

}  // namespace contact2d::game
