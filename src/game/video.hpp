// A video file written by ffmpeg (Debian's package) from raw RGB frames on
// its standard input: H.264 in MP4, yuv420p so that every player reads it.
#pragma once

#include <sys/types.h>
#include <cstdio>
#include <string>
#include <vector>

namespace contact2d::game {

class VideoWriter {
 public:
  // Starts ffmpeg; throws InputError when it cannot be started.
  VideoWriter(const std::string& path, int width, int height, int fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // One frame, bottom row first (as glReadPixels returns it). False once
  // ffmpeg has gone away.
  bool write(const std::vector<unsigned char>& rgb);
  // Closes the pipe and waits; throws InputError when ffmpeg failed.
  void finish();

 private:
  std::string path_;
  FILE* pipe_ = nullptr;
  pid_t pid_ = -1;
  int temp_slot_ = -1;  // "<path>.tmp", removed if a signal ends the program (io/interrupt.hpp)
};

}  // namespace contact2d::game
