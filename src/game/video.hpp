// A video file written by ffmpeg (Debian's package) from raw RGB frames on
// its standard input: H.264 in MP4, yuv420p so that every player reads it,
// or an animated GIF (a palette computed over all frames: palettegen then
// paletteuse, without dithering, so flat colours stay flat).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/child_process.hpp"

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
  // Closes ffmpeg's input, waits for it and checks what it wrote: ffmpeg
  // exited 0, and the file decodes with every frame written (ffprobe counts
  // them; on a full disk ffmpeg may exit 0 leaving an MP4 without its index
  // or a GIF cut short). Throws InputError otherwise, with no file left.
  // finish() then puts the video in place; finish_uncommitted() hands its
  // file back, to be committed with a command's other outputs.
  void finish();
  std::unique_ptr<AtomicFile> finish_uncommitted();
  // Stops ffmpeg and removes its temporary: no video. What the destructor
  // does when finish() was not called (an exception left the frame loop):
  // a video appears only when it is complete.
  void abandon();

 private:
  std::string path_;
  std::string option_;
  // What ffmpeg writes (its temporary file, unique to this process, renamed
  // onto the path or written through a device or FIFO at finish(): io/atomic_file.hpp).
  std::unique_ptr<AtomicFile> out_;
  std::unique_ptr<ChildProcess> ffmpeg_;  // io/child_process.hpp; killed on an interrupt
  long long frames_ = 0;                  // written to it
};

}  // namespace contact2d::game
