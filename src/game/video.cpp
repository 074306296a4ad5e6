#include "game/video.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <utility>

#include "core/input_error.hpp"
#include "io/interrupt.hpp"

namespace contact2d::game {
namespace {

// One palette for the whole GIF from every frame, applied without dithering.
const char* const kGifFilter =
    "vflip,split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=none";

}  // namespace

VideoWriter::VideoWriter(const std::string& path, int width, int height, int fps,
                         VideoFormat format, std::string option)
    : path_(path), option_(std::move(option)), out_(std::make_unique<AtomicFile>(path)) {
  // A write to a dead ffmpeg must fail with EPIPE, not kill the game.
  std::signal(SIGPIPE, SIG_IGN);
  const std::string& temporary = out_->temp_path();
  int fds[2];
  if (pipe(fds) != 0)
    throw InputError(option_ + " " + path + ": cannot create a pipe (" + std::strerror(errno) +
                     ")");
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string rate = std::to_string(fps);
  std::vector<std::string> args = {
      "ffmpeg", "-loglevel",   "error", "-y",         "-f", "rawvideo", "-pixel_format",
      "rgb24",  "-video_size", size,    "-framerate", rate, "-i",       "-"};
  const std::vector<std::string> encoding =
      format == VideoFormat::Gif
          ? std::vector<std::string>{"-vf", kGifFilter, "-f", "gif", temporary}
          : std::vector<std::string>{"-vf",       "vflip",      "-c:v", "libx264",  "-preset",
                                     "veryfast",  "-crf",       "20",   "-pix_fmt", "yuv420p",
                                     "-movflags", "+faststart", "-f",   "mp4",      temporary};
  args.insert(args.end(), encoding.begin(), encoding.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  // No interrupt between starting ffmpeg and registering it and its file
  // (io/interrupt.hpp); ffmpeg itself starts with no signal blocked.
  const InterruptsHeld held;
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  const int rc = posix_spawnp(&pid_, "ffmpeg", &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  if (rc != 0) {
    close(fds[1]);
    throw InputError(option_ + " " + path + ": cannot start ffmpeg (" + std::strerror(rc) +
                     "); install Debian's ffmpeg package");
  }
  pipe_ = fdopen(fds[1], "wb");
  register_child(pid_);
}

VideoWriter::~VideoWriter() { abandon(); }

void VideoWriter::abandon() {
  if (pid_ < 0) return;
  if (pipe_) std::fclose(pipe_);
  pipe_ = nullptr;
  kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
  register_child(0);
  pid_ = -1;
  out_.reset();  // removes the temporary
}

bool VideoWriter::write(const std::vector<unsigned char>& rgb) {
  if (!pipe_) return false;
  return std::fwrite(rgb.data(), 1, rgb.size(), pipe_) == rgb.size();
}

void VideoWriter::finish() {
  if (pid_ < 0) return;
  if (pipe_) std::fclose(pipe_);
  pipe_ = nullptr;
  int status = 0;
  waitpid(pid_, &status, 0);
  register_child(0);
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    out_.reset();
    throw InputError(option_ + " " + path_ + ": ffmpeg failed (exit status " +
                     std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                     "); no video written");
  }
  // Like every output of contact2d: the file appears only when complete.
  try {
    out_->commit();
  } catch (const InputError& e) {
    out_.reset();
    throw InputError(option_ + " " + e.what());
  }
  out_.reset();
}

}  // namespace contact2d::game
