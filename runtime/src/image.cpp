// Image (image.h): PNG through stb_image_write and stb_image. Debian's libstb already compiles the
// implementations, so the headers are included for their declarations only.
#include "walkrad/runtime/image.h"

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <stb_image.h>
#include <stb_image_write.h>

#include "walkrad/formats/error.h"

namespace walkrad {

void write_png(const std::string& path, const Image& image) {
  const int stride = image.width * 4;
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), stride))
    throw OutputError(path + ": cannot write PNG");
}

Image read_png(const std::string& path) {
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &width, &height, &channels, 4),
                                                         stbi_image_free);
  if (!pixels) throw InputError(path, "", std::string("cannot read as PNG: ") + stbi_failure_reason());
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels.get(), pixels.get() + size_t(width) * size_t(height) * 4);
  return image;
}

double psnr(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("psnr: images of different sizes");
  double sum = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const double d = double(a.rgba[i + c]) - double(b.rgba[i + c]);
      sum += d * d;
    }
  const double mse = sum / (3.0 * double(a.width) * double(a.height));
  return mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace walkrad
