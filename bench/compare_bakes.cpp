// compare_bakes REFERENCE_BAKE BAKE...: the relative RMS difference of each bake's radiosity from the
// reference's, as the scene's first viewpoint sees it (96×96 primary rays; emitters left out).
// Used by bench/hierarchical_vs_classic.py.
#include <cstdio>
#include <exception>

#include "../pipeline/tests/radiosity_image.h"
#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/manifest.h"

int main(int argc, char** argv) {
  using namespace walkrad;
  if (argc < 3) {
    std::fprintf(stderr, "usage: compare_bakes REFERENCE_BAKE BAKE...\n");
    return 2;
  }
  try {
    const std::string ref_dir = argv[1];
    const Manifest m = read_manifest(ref_dir + "/manifest.json");
    if (m.viewpoints.empty()) throw std::runtime_error("the reference bake has no viewpoint");
    const auto ref = test::radiosity_image(read_bake_mesh(ref_dir), m.viewpoints[0], 96);
    for (int i = 2; i < argc; ++i) {
      const std::string dir = argv[i];
      const Manifest o = read_manifest(dir + "/manifest.json");
      const auto img = test::radiosity_image(read_bake_mesh(dir), m.viewpoints[0], 96);
      std::printf("%s %.5f\n", dir.c_str(), test::relative_rms(img, ref, 20.0));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_bakes: %s\n", e.what());
    return 1;
  }
  return 0;
}
