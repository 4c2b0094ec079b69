// The fuzz targets' shared part: the readers take paths (a scene's buffers and includes are
// resolved against its folder), so each input is written to a private temporary file first.
// Only InputError is an accepted outcome; any other exception, a crash, a sanitizer report or a
// hang is a finding (docs/reliability.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include <unistd.h>

#include "walkrad/formats/error.h"

namespace walkrad::fuzz {

// A per-process file named for the target, in $TMPDIR (or /tmp), rewritten for every input.
inline const std::string& input_path(const char* extension) {
  static const std::string path = [&] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/walkrad-fuzz-" + std::to_string(getpid()) + extension;
  }();
  return path;
}

inline std::string write_input(const uint8_t* data, size_t size, const char* extension) {
  const std::string& path = input_path(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

// Runs a reader: a refusal (InputError) is fine, anything else that escapes is a finding.
template <typename Read>
void expect_clean(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: unexpected exception: %s\n", e.what());
    std::abort();
  }
}

}  // namespace walkrad::fuzz
