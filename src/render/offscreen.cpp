#include "render/offscreen.h"

#include <dlfcn.h>
#include <link.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <string_view>

#include "core/error.h"
#include "render/gl.h"

namespace softsub::render {

namespace {

std::string eglErrorText(EGLint e) { return fmt::format("EGL error 0x{:04x}", e); }

[[noreturn]] void noContext(const std::string& what) {
  throw IoError(fmt::format(
      "cannot draw off-screen: {} (softsub renders through EGL with Mesa; on Debian install "
      "libegl1 libegl-mesa0 libgl1-mesa-dri, which scripts/install-deps.sh does)",
      what));
}

EGLDisplay openDisplay() {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const std::string ext = clientExtensions ? clientExtensions : "";
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (getPlatformDisplay != nullptr) {
    // Surfaceless first: no display server and no device node needed.
    if (ext.find("EGL_MESA_platform_surfaceless") != std::string::npos) {
      EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (d != EGL_NO_DISPLAY) return d;
    }
    if (ext.find("EGL_EXT_platform_device") != std::string::npos) {
      auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLDeviceEXT devices[8];
      EGLint count = 0;
      if (queryDevices != nullptr && queryDevices(8, devices, &count) && count > 0) {
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
        if (d != EGL_NO_DISPLAY) return d;
      }
    }
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

int pinIfDriver(struct dl_phdr_info* info, std::size_t, void*) {
  const std::string_view name = info->dlpi_name != nullptr ? info->dlpi_name : "";
  const std::string_view base = name.substr(name.find_last_of('/') + 1);
  const bool driver = base.find("_dri.so") != std::string_view::npos || base.starts_with("libEGL_") ||
                      base.starts_with("libGLX_") || base.starts_with("libgallium") ||
                      base.starts_with("libvulkan_");
  // RTLD_NOLOAD: only what is loaded already; RTLD_NODELETE: never unloaded.
  if (driver) (void)dlopen(std::string(name).c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
  return 0;
}

}  // namespace

void pinGraphicsDrivers() { dl_iterate_phdr(pinIfDriver, nullptr); }

struct OffscreenContext::Egl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

OffscreenContext::OffscreenContext() : egl_(std::make_unique<Egl>()) {
  Egl& e = *egl_;
  e.display = openDisplay();
  if (e.display == EGL_NO_DISPLAY) noContext("no EGL display");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(e.display, &major, &minor)) noContext("eglInitialize failed, " + eglErrorText(eglGetError()));
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(e.display);
    noContext("this EGL has no desktop OpenGL");
  }
  const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  eglChooseConfig(e.display, configAttributes, &config, 1, &configs);
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  // Without a config, a context that never needs a surface (EGL_KHR_no_config_context).
  e.context = eglCreateContext(e.display, configs > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                               contextAttributes);
  if (e.context == EGL_NO_CONTEXT) {
    const EGLint err = eglGetError();
    eglTerminate(e.display);
    noContext("no OpenGL 3.3 core context, " + eglErrorText(err));
  }
  if (!eglMakeCurrent(e.display, EGL_NO_SURFACE, EGL_NO_SURFACE, e.context)) {
    const EGLint err = eglGetError();
    eglDestroyContext(e.display, e.context);
    eglTerminate(e.display);
    noContext("cannot make the context current without a surface, " + eglErrorText(err));
  }
  pinGraphicsDrivers();
}

OffscreenContext::~OffscreenContext() {
  eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(egl_->display, egl_->context);
  eglTerminate(egl_->display);
  eglReleaseThread();
}

std::string OffscreenContext::description() const {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return fmt::format("{}, OpenGL {}", renderer ? renderer : "?", version ? version : "?");
}

Framebuffer::Framebuffer(int width, int height, int samples) : width_(width), height_(height) {
  GLint maxSize = 0, maxSamples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (width < 1 || height < 1 || width > maxSize || height > maxSize)
    throw IoError(fmt::format("cannot draw a {}x{} picture: this OpenGL allows 1 to {} pixels a side", width,
                              height, maxSize));
  // A large picture may not fit with several samples a pixel (a software rasteriser's
  // 12000 x 12000 x 4 samples is 4.6 GB): fewer samples, down to one, before giving up.
  for (int s = std::clamp(samples, 0, maxSamples);; s /= 2) {
    if (allocate(s)) return;
    release();
    if (s == 0) break;
  }
  const double megabytes = 12.0 * width * height / (1 << 20);  // colour, depth and the resolved copy
  throw IoError(
      fmt::format("cannot draw a {}x{} picture: OpenGL could not make a framebuffer that large (about "
                  "{:.0f} MB at one sample a pixel); draw it smaller (--width, --height)",
                  width, height, megabytes));
}

bool Framebuffer::allocate(int samples) {
  glGenRenderbuffers(1, &colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width_, height_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width_, height_);
  glGenFramebuffers(1, &drawFbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, drawFbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum drawStatus = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glGenRenderbuffers(1, &resolveColour_);
  glBindRenderbuffer(GL_RENDERBUFFER, resolveColour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
  glGenFramebuffers(1, &resolveFbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolveColour_);
  const GLenum resolveStatus = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, drawFbo_);
  while (glGetError() != GL_NO_ERROR) {
  }  // an allocation that failed also set an error: cleared, the status says it
  return drawStatus == GL_FRAMEBUFFER_COMPLETE && resolveStatus == GL_FRAMEBUFFER_COMPLETE;
}

void Framebuffer::release() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLuint fbos[] = {drawFbo_, resolveFbo_};
  glDeleteFramebuffers(2, fbos);
  const GLuint rbs[] = {colour_, depth_, resolveColour_};
  glDeleteRenderbuffers(3, rbs);
  drawFbo_ = resolveFbo_ = colour_ = depth_ = resolveColour_ = 0;
}

Framebuffer::~Framebuffer() { release(); }

void Framebuffer::bind() { glBindFramebuffer(GL_FRAMEBUFFER, drawFbo_); }

Image Framebuffer::read() {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, drawFbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
  Image image = readPixels(width_, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, drawFbo_);
  return image;
}

Image readPixels(int width, int height) {
  Image image;
  image.width = width;
  image.height = height;
  const std::size_t row = 3 * static_cast<std::size_t>(width);
  std::vector<std::uint8_t> flipped(row * static_cast<std::size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, flipped.data());
  image.rgb.resize(flipped.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(image.rgb.data() + row * static_cast<std::size_t>(y),
                flipped.data() + row * static_cast<std::size_t>(height - 1 - y), row);
  return image;
}

}  // namespace softsub::render
