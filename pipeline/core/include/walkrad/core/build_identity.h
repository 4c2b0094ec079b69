// Which build of walkrad is running: its version and a hash of its own executable. Ranks of one bake
// must run the same build, and a checkpoint resumes only in the build that wrote it: another
// compiler or another commit may round differently, and the bake would no longer be byte-identical.
#pragma once

#include <string>

namespace walkrad {

// "walkrad 0.2.0, executable 0123456789abcdef" (hashed once, on the first call).
const std::string& build_identity();

}  // namespace walkrad
