// FNV-1a 64 of a file's bytes, as 16 hex digits (Fowler–Noll–Vo): identifies an input (the manifest's
// scene_hash, the sweep's reference key). Not a security hash. An unreadable file hashes as empty:
// callers have already read it, and say so themselves if they need to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace walkrad {

std::string hash_file(const std::string& path);

// FNV-1a 64 of bytes, continued from h (the offset basis to start).
inline uint64_t fnv1a(const void* data, size_t size, uint64_t h = 0xcbf29ce484222325ull) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  for (size_t k = 0; k < size; ++k) h = (h ^ bytes[k]) * 0x100000001b3ull;
  return h;
}

}  // namespace walkrad
