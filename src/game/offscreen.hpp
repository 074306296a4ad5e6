// An OpenGL 2.1 (compatibility) context to draw frames that are read back,
// never shown: `compare --video` (game/comparison_video.hpp).
//
//   Egl      EGL on Mesa's surfaceless platform (EGL_MESA_platform_surfaceless)
//            drawing into a framebuffer object: no display at all (llvmpipe
//            without a GPU).
//   Window   a hidden GLFW window (its back buffer): needs an X display,
//            e.g. Xvfb through xvfb-run.
//   Auto     Egl, else Window.
//
// Egl is available when contact2d was built with libEGL (CMake's
// OpenGL::EGL; CONTACT2D_WITH_EGL inside offscreen.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace contact2d::game {

enum class OffscreenBackend { Auto, Egl, Window };

class OffscreenContext {
 public:
  // Makes the context current. Throws InputError naming `option` when no
  // backend can be opened; without a display and without EGL the message is
  // "<option> needs a display: run under xvfb-run, or set DISPLAY (...)".
  OffscreenContext(int width, int height, OffscreenBackend backend, const std::string& option);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  int width() const;
  int height() const;
  OffscreenBackend backend() const;  // Egl or Window: the one opened
  // The frame just drawn, RGB, bottom row first (as glReadPixels gives it);
  // resized to width·height·3.
  void read_pixels(std::vector<unsigned char>& rgb) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Whether this build can try the EGL backend at all.
bool offscreen_egl_built();

}  // namespace contact2d::game
