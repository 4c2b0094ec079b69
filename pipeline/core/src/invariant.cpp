#include "walkrad/core/invariant.h"

#include <cstdio>
#include <cstdlib>

namespace walkrad {

void invariant_broken(const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "walkrad: invariant broken at %s:%d: %s\n", file, line, what.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace walkrad
