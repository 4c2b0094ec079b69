// FNV-1a 64 of a file's bytes, as 16 hex digits (Fowler–Noll–Vo): identifies an input (the manifest's
// scene_hash, the sweep's reference key). Not a security hash. An unreadable file hashes as empty:
// callers have already read it, and say so themselves if they need to.
#pragma once

#include <string>

namespace walkrad {

std::string hash_file(const std::string& path);

}  // namespace walkrad
