// compare_bakes REFERENCE_BAKE BAKE...: the relative RMS difference of each bake's radiosity from the
// reference's, as the scene's first viewpoint sees it (96×96 primary rays; emitters left out).
// Used by bench/hierarchical_vs_classic.py.
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <vector>

#include "walkrad/formats/manifest.h"
#include "walkrad/accuracy/error_measures.h"
#include "walkrad/accuracy/bake_sampler.h"

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
    std::vector<double> ref = BakeSampler::open(ref_dir).luminance_image(m.viewpoints[0], 96);
    for (double& r : ref)
      if (r > 20.0) r = NAN;  // emitters (B ≈ 40 in the Cornell box) left out
    for (int i = 2; i < argc; ++i) {
      const std::string dir = argv[i];
      const auto img = BakeSampler::open(dir).luminance_image(m.viewpoints[0], 96);
      std::printf("%s %.5f\n", dir.c_str(), relative_errors(img, ref).rms);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_bakes: %s\n", e.what());
    return 1;
  }
  return 0;
}
