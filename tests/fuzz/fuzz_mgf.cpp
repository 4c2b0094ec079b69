// Fuzz target: read_mgf. Includes resolve against the temporary file's folder, so an input can
// only name files that exist there or absolute paths (which the reader must refuse or read safely).
#include "fuzz_input.h"
#include "walkrad/formats/mgf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = walkrad::fuzz::write_input(data, size, ".mgf");
  walkrad::MgfOptions options;
  options.max_polygons = 200'000;  // a bounded run per input; the limit itself is part of what is tested
  walkrad::fuzz::expect_clean([&] { walkrad::read_mgf(path, options); });
  return 0;
}
