// Framebuffer: an offscreen render target (RGBA8 colour + 24-bit depth) for a context without a
// window, and the read-back of what was drawn into an Image. Needs a current GL context.
#pragma once

#include "walkrad/runtime/image.h"

namespace walkrad {

class Framebuffer {
 public:
  // Throws GraphicsError when the driver refuses the attachments (size beyond its limits).
  Framebuffer(int width, int height);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  // Makes it the target of the following draws.
  void bind() const;
  // Waits for the draws into it and returns the picture, top row first.
  Image read_pixels() const;

 private:
  void release();

  int width_, height_;
  unsigned framebuffer_ = 0, color_ = 0, depth_ = 0;  // GL object names
};

}  // namespace walkrad
