// A bulb inside a translucent shade (examples/lamp-room: KHR_materials_diffuse_transmission, a point
// light and a spot, no area emitter), baked with the defaults a user gets and its camera, read back as
// a viewer sees it against the independent reference tracer (reference_tracer.h) at points on the
// shade's two faces the camera sees and on the table under it. What the shade shows outside is τ times
// what lights its inside, a bulb 20 cm away: it varies threefold over a face. About 1.5% RMS at the
// medium default (the reference's standard error 1.0%). The table under the shade needs the shade's
// bottom, a close source of the table's points, read part by part with its twin (without it, 36-46%
// dark) and the table split under the shade's link (one element, 6% off). The shade needs its inside,
// seen by no viewpoint, refined, and the outside's vertices to depart from the inside's mean rather
// than their own (see docs/numerics.md; otherwise 17% off); the table under the shade needs a
// point's overfilled row (an occluder and what it hides both counted) not scaled down as a whole
// (otherwise 24-29% dark).
#include <cstdio>

#include <gtest/gtest.h>

#include "default_bake.h"
#include "walkrad/testing/reference_comparison.h"

namespace walkrad {
namespace {

const std::string kLampRoom = std::string(WALKRAD_SOURCE_DIR) + "/examples/lamp-room/lamp-room.gltf";

TEST(LampShade, OutsideShowsTheBulbThroughIt) {
  const test::DefaultBake baked("lamp-shade", kLampRoom);
  const Scene& scene = baked.scene;

  // The shade is the box (1.9, 1.8, 0.85)-(2.3, 2.2, 1.25), the bulb at its centre (2.1, 2.0, 1.05);
  // the table top at z = 0.75. Points over the faces the camera sees (+x, +y), corners and middles.
  struct Probe {
    SurfacePoint at;
    Vec3 normal;
  };
  std::vector<Probe> probes;
  const uint32_t east = test::polygon_at(scene, "shade", {1, 0, 0}, {2.3, 2.0, 1.05});
  const uint32_t north = test::polygon_at(scene, "shade", {0, 1, 0}, {2.1, 2.2, 1.05});
  const uint32_t table = test::polygon_at(scene, "table", {0, 0, 1}, {2.0, 2.0, 0.75});
  for (const double u : {0.03, 0.12, 0.2, 0.28, 0.37})
    for (const double z : {0.88, 1.0, 1.1, 1.22}) {
      probes.push_back({{east, {2.3, 1.8 + u, z}}, {1, 0, 0}});
      probes.push_back({{north, {1.9 + u, 2.2, z}}, {0, 1, 0}});
    }
  for (const double x : {1.95, 2.04, 2.25})
    for (const double y : {1.86, 2.0, 2.13}) probes.push_back({{table, {x, y, 0.75}}, {0, 0, 1}});
  std::vector<SurfacePoint> at;
  for (const Probe& p : probes) at.push_back(p.at);
  std::vector<Vec3> up;
  for (const Probe& p : probes) up.push_back(p.normal);
  const test::ReferenceComparison c = test::compare_with_reference(baked.tracer, baked.sampler, at, up, 0.01, 16384);
  std::printf("shade and table: RMS %.2f%% (the reference's standard error %.2f%%)\n", 100 * c.rms, 100 * c.bar);
  EXPECT_LT(c.rms, 0.05);
}

// A vertex on a wall's foot lies on the wall's plane: its shadow ray to a punctual light, lifted off
// the floor alone, would leave from the wall itself and meet it. The punctual lights' rays leave from
// the gather's origin, moved in (final_gather.cpp); otherwise the floor 1 cm from the wall y = 0 under
// the spot reads 39% dark at x = 3.10 and 16% at x = 1.70, in the pool of light (these 12 points
// 22.6% RMS against about 1.4%; the reference's own standard error 0.9%).
TEST(LampShade, TheFloorAtAWallsFootIsLitByTheSpot) {
  const test::DefaultBake baked("wall-foot", kLampRoom);
  const Scene& scene = baked.scene;
  std::vector<SurfacePoint> at;
  std::vector<Vec3> up;
  for (const double x : {1.1, 1.7, 2.3, 2.7, 3.1, 3.5})
    for (const double y : {0.01, 0.03}) {
      at.push_back({test::polygon_at(scene, "floor", {0, 0, 1}, {x, y, 0}), {x, y, 0}});
      up.push_back({0, 0, 1});
    }
  // 2^20 paths a point: the pool's reference is noisy, about 10% a point at 16,384.
  const test::ReferenceComparison c = test::compare_with_reference(baked.tracer, baked.sampler, at, up, 0.005, 1 << 20);
  std::printf("floor beside the wall under the spot: RMS %.2f%% (the reference's standard error %.2f%%)\n", 100 * c.rms,
              100 * c.bar);
  EXPECT_LT(c.rms, 0.03);
}

}  // namespace
}  // namespace walkrad
