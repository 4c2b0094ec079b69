// Image: an 8-bit RGBA picture read back from the GPU, top row first (the order of image files,
// the reverse of OpenGL's), its PNG writer and reader, and the PSNR that golden tests compare with. Headless frames and the tests go through it.
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
// Reads a PNG (any channel count, expanded to RGBA). Throws InputError naming the file.
Image read_png(const std::string& path);

// Peak signal-to-noise ratio of b against a over the RGB channels, in dB:
// 10 log10(255² / mean squared difference); infinity when they are equal. Throws
// std::invalid_argument when the sizes differ.
double psnr(const Image& a, const Image& b);

}  // namespace walkrad
