// Framebuffer (framebuffer.h): renderbuffers rather than textures, since the picture is only read
// back, never sampled. GL_RGBA8 is a linear format: the shader writes sRGB-encoded values itself.
#include "walkrad/runtime/framebuffer.h"

#include <algorithm>
#include <string>

#include <epoxy/gl.h>

#include "walkrad/runtime/graphics_error.h"

namespace walkrad {

Framebuffer::Framebuffer(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw GraphicsError("framebuffer size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  glGenRenderbuffers(1, &color_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    release();  // the constructor throws, so the destructor will not run
    throw GraphicsError("offscreen framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                        " is incomplete (status " + std::to_string(status) + ")");
  }
}

Framebuffer::~Framebuffer() { release(); }

void Framebuffer::release() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteRenderbuffers(1, &color_);
}

void Framebuffer::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }

Image Framebuffer::read_pixels() const {
  Image image;
  image.width = width_;
  image.height = height_;
  image.rgba.resize(size_t(width_) * size_t(height_) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  // OpenGL returns the bottom row first; image files and Image start at the top.
  const size_t row = size_t(width_) * 4;
  for (int y = 0; y < height_ / 2; ++y)
    std::swap_ranges(image.rgba.begin() + y * row, image.rgba.begin() + (y + 1) * row,
                     image.rgba.begin() + (height_ - 1 - y) * row);
  return image;
}

}  // namespace walkrad
