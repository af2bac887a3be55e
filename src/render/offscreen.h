#pragma once
/// Off-screen drawing without a window or display: an EGL context on Mesa's surfaceless
/// platform (software rasteriser when there is no GPU), and a framebuffer to draw into and
/// read back. Used by `softsub render`, `run --preview` and the tests.
#include <memory>
#include <string>

#include "render/image.h"

namespace softsub::render {

/// An OpenGL 3.3 core context with no surface, current on the calling thread while it
/// lives. Throws IoError naming what the system lacks when none can be made.
class OffscreenContext {
 public:
  OffscreenContext();
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6", say.
  [[nodiscard]] std::string description() const;

 private:
  struct Egl;
  std::unique_ptr<Egl> egl_;
};

/// A multisampled colour + depth framebuffer in the current context, resolved and read
/// back as an Image. Sizes from 1 to the driver's limit; IoError beyond it.
class Framebuffer {
 public:
  /// `samples` a pixel, or fewer where a large picture does not fit with them (down to
  /// one); IoError when it does not fit at all or is larger than OpenGL allows.
  Framebuffer(int width, int height, int samples = 4);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  /// Makes it the draw target.
  void bind();
  /// The pixels drawn so far, rows top to bottom.
  [[nodiscard]] Image read();

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

 private:
  /// Makes the buffers at `samples` a pixel; false when OpenGL could not (incomplete).
  bool allocate(int samples);
  /// Deletes the buffers (none made: nothing).
  void release();

  int width_, height_;
  unsigned drawFbo_ = 0, resolveFbo_ = 0, colour_ = 0, depth_ = 0, resolveColour_ = 0;
};

/// Keeps the OpenGL drivers loaded so far (Mesa's EGL/GLX vendor libraries and its DRI
/// driver) loaded until the process exits. A later context then starts without reloading
/// them, and LeakSanitizer still sees the driver's globals at exit: an unloaded driver's
/// allocations are otherwise reported as leaks in an unknown module. Call after a
/// context is made; harmless to call again.
void pinGraphicsDrivers();

/// Reads the currently bound framebuffer's (0, 0, width, height) into an Image, rows top
/// to bottom (the viewer's screenshots).
[[nodiscard]] Image readPixels(int width, int height);

}  // namespace softsub::render
