// Fuzz target: read_ies, then what reads the profile: intensity in fixed directions, the flux and
// the tilt table. An accepted profile must give finite, non-negative candela no larger than its
// largest tabulated value (bilinear interpolation mixes neighbours), and a non-negative flux.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.h"
#include "walkrad/formats/ies.h"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz: accepted profile breaks: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = walkrad::fuzz::write_input(data, size, ".ies");
  walkrad::fuzz::expect_clean([&] {
    const walkrad::IesProfile p = walkrad::read_ies(path);
    const double max = p.max_candela();
    check(std::isfinite(max) && max >= 0, "max_candela finite and >= 0");
    for (int i = 0; i < 33; ++i) {  // the six axes (the poles of every type), then a 3 × 3 × 3 spread
      const int k = i - 6, axis = i % 3;
      const walkrad::Vec3 d = i < 6 ? walkrad::Vec3(axis == 0, axis == 1, axis == 2) * (i < 3 ? 1 : -1)
                                    : walkrad::Vec3(k % 3 - 1 + 0.1 * (k & 1), (k / 3) % 3 - 1, k / 9 - 1 + 0.01 * k);
      const double c = p.intensity(d);
      check(std::isfinite(c) && c >= 0 && c <= max * (1 + 1e-12), "0 <= intensity <= max_candela");
    }
    check(!(p.flux() < 0) && !std::isnan(p.flux()), "flux >= 0");
    for (double t : {-10.0, 0.0, 12.5, 45.0, 90.0, 200.0}) check(std::isfinite(p.tilt_factor(t)), "finite tilt factor");
  });
  return 0;
}
