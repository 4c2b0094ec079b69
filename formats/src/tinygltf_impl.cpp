// The one translation unit that compiles tinygltf, with Draco decoding enabled: Debian's
// libtinygltf is built without Draco and cannot load Draco glTF (../shared/design/deps.md, pitfall 1).
// stb_image's implementation comes from Debian's libstb, linked explicitly (pitfall 2).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_ENABLE_DRACO
#include <tiny_gltf.h>
