#include "walkrad/core/file_hash.h"

#include <cstdint>
#include <cstdio>
#include <fstream>

namespace walkrad {

std::string hash_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint64_t h = 0xcbf29ce484222325ull;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) h = fnv1a(buf, size_t(in.gcount()), h);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace walkrad
