// The fuzz targets' shared part: the readers take paths (a scene's buffers and includes are
// resolved against its folder), so each input is written to a private temporary file first.
// Only InputError is an accepted outcome; any other exception, a crash, a sanitizer report or a
// hang is a finding (docs/reliability.md).
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "walkrad/formats/error.h"

namespace walkrad::fuzz {

// A per-process file in a private folder of $TMPDIR (or /tmp), rewritten for every input. The
// folder is the input's whole input folder: the URIs and includes a fuzzer invents can name only
// the input itself, whatever else lies in /tmp, so a run replays the same way anywhere.
inline const std::string& input_path(const char* extension) {
  static const std::string path = [&] {
    const char* tmp = std::getenv("TMPDIR");
    const std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/walkrad-fuzz-" + std::to_string(getpid());
    if (mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) {
      std::fprintf(stderr, "fuzz: cannot make %s\n", dir.c_str());
      std::abort();
    }
    return dir + "/input" + extension;
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
