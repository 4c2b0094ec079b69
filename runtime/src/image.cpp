// write_png (image.h) through stb_image_write. Debian's libstb already compiles the
// implementation, so the header is included for its declarations only.
#include "walkrad/runtime/image.h"

#include <stb_image_write.h>

#include "walkrad/formats/error.h"

namespace walkrad {

void write_png(const std::string& path, const Image& image) {
  const int stride = image.width * 4;
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), stride))
    throw OutputError(path + ": cannot write PNG");
}

}  // namespace walkrad
