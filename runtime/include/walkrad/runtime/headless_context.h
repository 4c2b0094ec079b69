// HeadlessContext: an OpenGL 3.3 core context with no window and no display server, so frames can
// be rendered on a build machine or in CI (Mesa's llvmpipe without a GPU). EGL on Mesa's
// surfaceless platform; the context has no surface, so render into a Framebuffer (framebuffer.h).
#pragma once

#include <string>

namespace walkrad {

class HeadlessContext {
 public:
  // Creates the context and makes it current on the calling thread. Throws GraphicsError saying
  // which EGL step failed when EGL, its surfaceless platform or a 3.3 core context is missing.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // GL_RENDERER and GL_VERSION, for logs ("llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6").
  std::string description() const;

 private:
  void* display_ = nullptr;  // EGLDisplay, kept opaque so EGL stays out of the public headers
  void* context_ = nullptr;  // EGLContext
};

}  // namespace walkrad
