// Fuzz target: read_chunk, the runtime's reader of a bake's .glb chunks (Draco decoded there).
#include "fuzz_input.h"
#include "walkrad/formats/chunk.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = walkrad::fuzz::write_input(data, size, ".glb");
  walkrad::fuzz::expect_clean([&] { walkrad::read_chunk(path); });
  return 0;
}
