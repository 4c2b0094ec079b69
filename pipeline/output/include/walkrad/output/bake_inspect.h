// `walkrad inspect BAKE`: what a bake folder holds (chunks, sizes, compression, the report's
// totals), and optionally its whole surface as JSON for scripts and tests that do not decode Draco.
#pragma once

#include <string>

namespace walkrad {

// Prints to stdout; mesh_json non-empty: also writes {positions, normals, colors, radiosity, indices}
// (flat arrays) there. Throws InputError / OutputError.
void inspect_bake(const std::string& folder, const std::string& mesh_json);

}  // namespace walkrad
