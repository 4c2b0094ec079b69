// Bounds-checked access to glTF accessors: every size is checked against its buffer before a byte
// is read, so a lying file is refused with the accessor's index instead of read out of bounds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace walkrad::gltf_access {

// Floats of a float accessor with `components` per element (VEC3 or VEC4 read as VEC3 when
// components == 3), appended to out.
void append_floats(const tinygltf::Model& m, int accessor, int components, std::vector<float>& out,
                   const std::string& file, const std::string& name);

// Float VEC2 texture coordinates appended to out (u, v per vertex); false when the accessor is not
// float VEC2 (normalised integer coordinates are not read).
bool append_uvs(const tinygltf::Model& m, int accessor, std::vector<float>& out, const std::string& file);

// Unsigned integer indices (u8, u16, u32), each plus offset, appended to out.
void append_indices(const tinygltf::Model& m, int accessor, uint32_t offset, std::vector<uint32_t>& out,
                    const std::string& file);

// Loads .gltf or .glb (by extension). Refuses a missing file or tinygltf's errors as InputError.
// folder: where its buffers and images may lie (input_limits::input_folder; empty: the file's own).
tinygltf::Model load(const std::string& path, bool load_images, const std::string& folder = {});

}  // namespace walkrad::gltf_access
