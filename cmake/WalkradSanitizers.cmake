# Instrumented builds (docs/reliability.md). Both apply to every walkrad target, so a finding in a
# reader is caught wherever it is called from; third-party libraries stay uninstrumented.
#   WALKRAD_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer, any compiler (scripts/test.sh
#                        builds build-asan/ with it and runs the ctest suite there)
#   WALKRAD_FUZZ=ON:     clang only: libFuzzer coverage on every target and the fuzzers in tests/fuzz/
#                        (which also get ASan + UBSan); scripts/fuzz.sh builds and runs them
option(WALKRAD_SANITIZE "Build with -fsanitize=address,undefined" OFF)
option(WALKRAD_FUZZ "Build the libFuzzer targets in tests/fuzz (clang only)" OFF)

if(WALKRAD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "WALKRAD_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  set(WALKRAD_SANITIZE ON CACHE BOOL "" FORCE)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(WALKRAD_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_definitions(WALKRAD_CHECK_INVARIANTS)  # walkrad/core/invariant.h: the invariants checked too
  add_link_options(-fsanitize=address,undefined -fno-sanitize-recover=all)
endif()
