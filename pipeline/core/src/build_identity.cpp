#include "walkrad/core/build_identity.h"

#include "walkrad/core/file_hash.h"

namespace walkrad {

const std::string& build_identity() {
  // FNV-1a over the executable's bytes (tens of MB: a few tens of milliseconds).
  static const std::string id = std::string("walkrad ") + WALKRAD_VERSION + ", executable " + hash_file("/proc/self/exe");
  return id;
}

}  // namespace walkrad
