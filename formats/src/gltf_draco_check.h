// KHR_draco_mesh_compression checked before tinygltf decodes it: tinygltf 2.7 indexes the bufferView,
// its buffer, the accessors and the decoded attributes without bounds checks (found by the chunk
// fuzzer, tests/fuzz/crashers/chunk/). Each Draco primitive's bufferView, buffer, accessors and
// attribute ids must exist, and its data must lie in the GLB's BIN chunk (Draco data elsewhere is
// refused as a missing feature). Refusals name the file and the primitive.
#pragma once

#include <string>
#include <vector>

namespace walkrad::gltf_access {

// json: the glTF JSON text; bin: the GLB BIN chunk's bytes (empty for .gltf).
void check_draco(const char* json, size_t json_size, const unsigned char* bin, size_t bin_size, const std::string& file);

}  // namespace walkrad::gltf_access
