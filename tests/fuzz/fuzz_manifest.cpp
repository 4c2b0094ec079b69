// Fuzz target: read_manifest (a bake folder's manifest.json, read by the runtime and by diff).
#include "fuzz_input.h"
#include "walkrad/formats/manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = walkrad::fuzz::write_input(data, size, ".json");
  walkrad::fuzz::expect_clean([&] { walkrad::read_manifest(path); });
  return 0;
}
