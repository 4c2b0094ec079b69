// Fuzz target: read_gltf over .glb (inputs that start with the GLB magic) and .gltf (the others).
#include "fuzz_input.h"
#include "walkrad/formats/gltf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  const std::string path = walkrad::fuzz::write_input(data, size, binary ? ".glb" : ".gltf");
  walkrad::fuzz::expect_clean([&] { walkrad::read_gltf(path); });
  return 0;
}
