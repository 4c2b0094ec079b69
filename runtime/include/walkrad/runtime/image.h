// Image: an 8-bit RGBA picture read back from the GPU, top row first (the order of image files,
// the reverse of OpenGL's), and its PNG writer. Headless frames and the tests go through it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace walkrad {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width × height × 4 bytes, row y = 0 is the top of the picture

  // The 4 bytes (R, G, B, A) of pixel (x, y), y counted from the top.
  const uint8_t* pixel(int x, int y) const { return &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4]; }
};

// Writes the image as a PNG. Throws OutputError naming the file when it cannot be written.
void write_png(const std::string& path, const Image& image);

}  // namespace walkrad
