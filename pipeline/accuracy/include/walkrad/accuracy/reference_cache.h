// A sweep's reference kept for the next sweep (`walkrad sweep --reference DIR`): the reference costs
// minutes (32,768 paths a point), the bakes it judges seconds, and judging a change to the solver
// needs the same reference before and after. Saved as OUTPUT/reference.bin beside the CSV, with a key
// that names everything the reference depends on (the scene's and walkthrough's bytes, the points,
// paths, images and seed), so that a reference is reused only where it would come out the same.
#pragma once

#include <string>

#include "walkrad/accuracy/reference_set.h"

namespace walkrad {

// The key of a reference: FNV-1a digests of the scene and walkthrough files and the settings text.
std::string reference_key(const std::string& scene_path, const std::string& views_path, const std::string& settings);

// Writes both sets (the sample points and the image pixels). Throws OutputError.
void save_reference(const std::string& path, const std::string& key, const ReferenceSet& points, const ReferenceSet& image);

// Reads what save_reference wrote. Throws InputError (exit 3) naming the file when it cannot be read,
// or when its key differs (the message says which reference was asked for).
void load_reference(const std::string& path, const std::string& key, ReferenceSet& points, ReferenceSet& image);

}  // namespace walkrad
