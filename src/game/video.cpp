#include "game/video.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <variant>

#include "core/input_error.hpp"

namespace contact2d::game {
namespace {

// One palette for the whole GIF from every frame, applied without dithering.
const char* const kGifFilter =
    "vflip,split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=none";

}  // namespace

VideoWriter::VideoWriter(const std::string& path, int width, int height, int fps,
                         VideoFormat format, std::string option)
    : path_(path), option_(std::move(option)), out_(std::make_unique<AtomicFile>(path)) {
  const std::string& temporary = out_->temp_path();
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
  try {
    ffmpeg_ = std::make_unique<ChildProcess>(args, std::string(), /*writes_output=*/true);
  } catch (const ChildProcessError& e) {
    throw InputError(option_ + " " + path + ": cannot start ffmpeg (" +
                     std::strerror(e.spawn_error ? e.spawn_error : EIO) +
                     "); install Debian's ffmpeg package");
  }
}

VideoWriter::~VideoWriter() { abandon(); }

void VideoWriter::abandon() {
  if (!ffmpeg_) return;
  ::kill(ffmpeg_->pid(), SIGTERM);
  ffmpeg_.reset();  // waits for it (and kills it if it lingers)
  out_.reset();     // removes the temporary
}

bool VideoWriter::write(const std::vector<unsigned char>& rgb) {
  if (!ffmpeg_) return false;
  try {
    ffmpeg_->write(reinterpret_cast<const char*>(rgb.data()), rgb.size());
  } catch (const ChildProcessError&) {
    return false;  // finish() says why
  }
  ++frames_;
  return true;
}

namespace {

// The frames of the video at `file` as ffprobe decodes them, or the reason
// it cannot.
std::variant<long long, std::string> decoded_frames(const std::string& file) {
  try {
    ChildProcess probe({"ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                        "-show_entries", "stream=nb_read_frames", "-of",
                        "default=noprint_wrappers=1:nokey=1", file});
    const ChildEnding end = probe.finish();
    char* rest = nullptr;
    const long long n = std::strtoll(end.output.c_str(), &rest, 10);
    if (end.status != 0 || rest == end.output.c_str()) return "ffprobe " + end.description;
    return n;
  } catch (const ChildProcessError& e) {
    return std::string(e.what());
  }
}

}  // namespace

std::unique_ptr<AtomicFile> VideoWriter::finish_uncommitted() {
  if (!ffmpeg_) throw InputError(option_ + " " + path_ + ": the video was abandoned");
  const ChildEnding end = ffmpeg_->finish();
  ffmpeg_.reset();
  if (end.status != 0) {
    out_.reset();
    throw InputError(
        option_ + " " + path_ + ": ffmpeg failed (" +
        (end.status > 0 ? "exit status " + std::to_string(end.status) : end.description) +
        "); no video written");
  }
  // ffmpeg exits 0 on some write errors (a full disk: it cannot write an
  // MP4's index or the end of a GIF): decode what it wrote.
  const auto frames = decoded_frames(out_->temp_path());
  if (const auto* why = std::get_if<std::string>(&frames)) {
    out_.reset();
    throw InputError(option_ + " " + path_ + ": ffmpeg's file does not decode (" + *why +
                     "; a full disk?); no video written");
  }
  if (const long long n = std::get<long long>(frames); n != frames_) {
    out_.reset();
    throw InputError(option_ + " " + path_ + ": ffmpeg's file has " + std::to_string(n) +
                     " of the " + std::to_string(frames_) +
                     " frames written (a full disk?); no video written");
  }
  return std::move(out_);
}

void VideoWriter::finish() {
  const std::unique_ptr<AtomicFile> video = finish_uncommitted();
  // Like every output of contact2d: the file appears only when complete.
  try {
    video->commit();
  } catch (const InputError& e) {
    throw InputError(option_ + " " + e.what());
  }
}

}  // namespace contact2d::game
