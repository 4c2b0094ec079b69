// read_scene: any scene file walkrad reads, chosen by extension — .gltf and .glb (gltf_reader.h),
// .mgf (mgf_reader.h) — as the plain scene arrays of scene.h.
#pragma once

#include <string>

#include "walkrad/formats/scene.h"

namespace walkrad {

// Throws InputError for an unknown extension and whatever the format's reader throws.
// input_folder: where the files the scene refers to may lie (buffers, images, includes, IES profiles);
// empty: the scene file's own folder. A reference outside it is refused before it is opened.
// mgf_sides: the sides of an MGF material that does not state them (MgfOptions::default_sides).
Scene read_scene(const std::string& path, const std::string& input_folder = {}, int mgf_sides = 1);

// Whether read_scene reads the path as MGF (its extension, in any case): messages name MGF lines and
// options, glTF meshes.
bool is_mgf(const std::string& path);

}  // namespace walkrad
