#include "game/offscreen.hpp"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GL/glext.h>
#include <GLFW/glfw3.h>
#ifdef CONTACT2D_WITH_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

#include <cstdio>

#include "core/input_error.hpp"
#include "game/draw2d.hpp"

namespace contact2d::game {
namespace {

std::string g_glfw_error;

void on_glfw_error(int, const char* description) {
  g_glfw_error = description ? description : "unknown error";
}

// GLFW with one hidden window whose back buffer is drawn and read back.
struct WindowContext {
  GLFWwindow* window = nullptr;
  int width = 0, height = 0;

  // Empty on success, else why not.
  std::string open(int w, int h) {
    glfwSetErrorCallback(on_glfw_error);
    g_glfw_error.clear();
    if (!glfwInit()) return "GLFW: " + g_glfw_error;
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    window = glfwCreateWindow(w, h, "contact2d offscreen", nullptr, nullptr);
    if (!window) {
      glfwTerminate();
      return "GLFW: cannot create an OpenGL 2.1 window (" + g_glfw_error + ")";
    }
    glfwMakeContextCurrent(window);
    glfwGetFramebufferSize(window, &width, &height);
    return "";
  }
  ~WindowContext() {
    if (!window) return;
    glfwDestroyWindow(window);
    glfwTerminate();
  }
};

#ifdef CONTACT2D_WITH_EGL
std::string egl_error(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  return std::string("EGL: ") + what + " failed (" + code + ")";
}

// EGL surfaceless: a context without any surface, drawing into a
// framebuffer object with one RGBA8 renderbuffer.
struct EglContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint fbo = 0, colour = 0;
  int width = 0, height = 0;
  PFNGLDELETEFRAMEBUFFERSPROC delete_framebuffers = nullptr;
  PFNGLDELETERENDERBUFFERSPROC delete_renderbuffers = nullptr;

  template <typename F>
  static F proc(const char* name) {
    return reinterpret_cast<F>(eglGetProcAddress(name));
  }

  std::string open(int w, int h) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || std::string(client).find("EGL_MESA_platform_surfaceless") == std::string::npos)
      return "EGL: no EGL_MESA_platform_surfaceless";
    const auto get_display = proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!get_display) return "EGL: no eglGetPlatformDisplayEXT";
    display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) return egl_error("eglGetPlatformDisplayEXT");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      std::string why = egl_error("eglInitialize");
      display = EGL_NO_DISPLAY;
      return why;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) return egl_error("eglBindAPI(OpenGL)");
    // Surfaceless needs no config (EGL_KHR_no_config_context) when none fits.
    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1)
      config = nullptr;  // EGL_NO_CONFIG_KHR
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 2, EGL_CONTEXT_MINOR_VERSION, 1,
                                         EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT) return egl_error("eglCreateContext(OpenGL 2.1)");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      return egl_error("eglMakeCurrent(no surface)");

    const auto gen_framebuffers = proc<PFNGLGENFRAMEBUFFERSPROC>("glGenFramebuffers");
    const auto bind_framebuffer = proc<PFNGLBINDFRAMEBUFFERPROC>("glBindFramebuffer");
    const auto gen_renderbuffers = proc<PFNGLGENRENDERBUFFERSPROC>("glGenRenderbuffers");
    const auto bind_renderbuffer = proc<PFNGLBINDRENDERBUFFERPROC>("glBindRenderbuffer");
    const auto storage = proc<PFNGLRENDERBUFFERSTORAGEPROC>("glRenderbufferStorage");
    const auto attach = proc<PFNGLFRAMEBUFFERRENDERBUFFERPROC>("glFramebufferRenderbuffer");
    const auto status = proc<PFNGLCHECKFRAMEBUFFERSTATUSPROC>("glCheckFramebufferStatus");
    delete_framebuffers = proc<PFNGLDELETEFRAMEBUFFERSPROC>("glDeleteFramebuffers");
    delete_renderbuffers = proc<PFNGLDELETERENDERBUFFERSPROC>("glDeleteRenderbuffers");
    if (!gen_framebuffers || !bind_framebuffer || !gen_renderbuffers || !bind_renderbuffer ||
        !storage || !attach || !status || !delete_framebuffers || !delete_renderbuffers)
      return "EGL: the context has no framebuffer objects";
    gen_renderbuffers(1, &colour);
    bind_renderbuffer(GL_RENDERBUFFER, colour);
    storage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gen_framebuffers(1, &fbo);
    bind_framebuffer(GL_FRAMEBUFFER, fbo);
    attach(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    if (status(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return "EGL: the framebuffer object is incomplete";
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    width = w;
    height = h;
    return "";
  }
  ~EglContext() {
    if (display == EGL_NO_DISPLAY) return;
    if (context != EGL_NO_CONTEXT) {
      if (fbo && delete_framebuffers) delete_framebuffers(1, &fbo);
      if (colour && delete_renderbuffers) delete_renderbuffers(1, &colour);
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    eglTerminate(display);
    eglReleaseThread();
  }
};
#endif

}  // namespace

struct OffscreenContext::Impl {
#ifdef CONTACT2D_WITH_EGL
  std::unique_ptr<EglContext> egl;
#endif
  std::unique_ptr<WindowContext> window;
};

bool offscreen_egl_built() {
#ifdef CONTACT2D_WITH_EGL
  return true;
#else
  return false;
#endif
}

OffscreenContext::OffscreenContext(int width, int height, OffscreenBackend backend,
                                   const std::string& option)
    : impl_(std::make_unique<Impl>()) {
  std::string egl_failure = "EGL: not built in";
#ifdef CONTACT2D_WITH_EGL
  if (backend != OffscreenBackend::Window) {
    impl_->egl = std::make_unique<EglContext>();
    egl_failure = impl_->egl->open(width, height);
    if (egl_failure.empty()) {
      draw::forget_gl_objects();  // an earlier context's text atlas is gone
      return;
    }
    impl_->egl.reset();
  }
#endif
  if (backend == OffscreenBackend::Egl) {
    throw InputError(option + ": no EGL surfaceless context (" + egl_failure +
                     "); run under xvfb-run for the window backend");
  }
  impl_->window = std::make_unique<WindowContext>();
  const std::string window_failure = impl_->window->open(width, height);
  if (!window_failure.empty()) {
    impl_->window.reset();
    std::string why = window_failure;
    if (backend == OffscreenBackend::Auto) why = egl_failure + "; " + why;
    throw InputError(option + " needs a display: run under xvfb-run, or set DISPLAY (" + why + ")");
  }
  draw::forget_gl_objects();
}

OffscreenContext::~OffscreenContext() = default;

int OffscreenContext::width() const {
#ifdef CONTACT2D_WITH_EGL
  if (impl_->egl) return impl_->egl->width;
#endif
  return impl_->window->width;
}

int OffscreenContext::height() const {
#ifdef CONTACT2D_WITH_EGL
  if (impl_->egl) return impl_->egl->height;
#endif
  return impl_->window->height;
}

OffscreenBackend OffscreenContext::backend() const {
  return impl_->window ? OffscreenBackend::Window : OffscreenBackend::Egl;
}

void OffscreenContext::read_pixels(std::vector<unsigned char>& rgb) const {
  rgb.resize(static_cast<size_t>(width()) * static_cast<size_t>(height()) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(impl_->window ? GL_BACK : GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, width(), height(), GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
}

}  // namespace contact2d::game
