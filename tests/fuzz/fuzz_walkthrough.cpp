// Fuzz target: read_walkthrough (walkthrough JSON, viewpoints or a sampled path).
#include "fuzz_input.h"
#include "walkrad/formats/walkthrough.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = walkrad::fuzz::write_input(data, size, ".json");
  walkrad::fuzz::expect_clean([&] { walkrad::read_walkthrough(path); });
  return 0;
}
