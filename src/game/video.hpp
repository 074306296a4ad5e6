// A video file written by ffmpeg (Debian's package) from raw RGB frames on
// its standard input: H.264 in MP4, yuv420p so that every player reads it,
// or an animated GIF (a palette computed over all frames: palettegen then
// paletteuse, without dithering, so flat colours stay flat).
#pragma once

#include <sys/types.h>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"

namespace contact2d::game {

enum class VideoFormat { Mp4, Gif };

class VideoWriter {
 public:
  // Starts ffmpeg; throws InputError when it cannot be started. `option`
  // names the command-line option in error messages ("--record", "--video").
  VideoWriter(const std::string& path, int width, int height, int fps,
              VideoFormat format = VideoFormat::Mp4, std::string option = "--record");
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // One frame, bottom row first (as glReadPixels returns it). False once
  // ffmpeg has gone away.
  bool write(const std::vector<unsigned char>& rgb);
  // Closes the pipe and waits; throws InputError when ffmpeg failed.
  void finish();
  // Stops ffmpeg and removes its temporary: no video. What the destructor
  // does when finish() was not called (an exception left the frame loop):
  // a video appears only when it is complete.
  void abandon();

 private:
  std::string path_;
  std::string option_;
  FILE* pipe_ = nullptr;
  pid_t pid_ = -1;
  // What ffmpeg writes (its temporary file, unique to this process, renamed
  // onto the path or written through a device or FIFO at finish(): io/atomic_file.hpp).
  std::unique_ptr<AtomicFile> out_;
};

}  // namespace contact2d::game
