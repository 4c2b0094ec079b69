// The bakes the runtime's bake tests render: made by ctest fixtures (tests/CMakeLists.txt), named by
// CMake, overridable by an environment variable of the same name. The tests skip while one is missing.
#pragma once

#include <cstdlib>
#include <string>

namespace walkrad {

inline std::string test_bake_dir(const char* variable, const char* configured) {
  const char* env = std::getenv(variable);
  return env && *env ? env : configured;
}

}  // namespace walkrad
