// Clear glass (fresnel.h, RayScene::transmittance): a thin pane's Fresnel transmittance, and the sun, the
// sky and the reference tracer through a glazed window against the exact values; glTF and MGF read it,
// the writer keeps it.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "walkrad/accuracy/reference_tracer.h"
#include "walkrad/bake/bake.h"
#include "walkrad/core/fresnel.h"
#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/mgf_reader.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/formfactor/sky_light.h"
#include "walkrad/scene/scene_cleanup.h"
#include "walkrad/testing/floor_check.h"
#include "walkrad/testing/temp_dir_test.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

const Vec3 kUp(0, 0, 1);
constexpr double kFilter = 0.9, kIor = 1.5, kL = 1000;

TEST(Fresnel, APaneOfGlass) {
  EXPECT_NEAR(pane_transmittance(1, 1.5), 0.96 / 1.04, 1e-12);  // R = 0.04 at each face
  EXPECT_EQ(pane_transmittance(0, 1.5), 0.0);
  EXPECT_NEAR(pane_transmittance(0.7, 1), 1.0, 1e-12);  // no interface at all
  double before = 1;
  for (int k = 0; k <= 90; ++k) {  // falls with the angle
    const double t = pane_transmittance(std::cos(k * kPi / 180), 1.5);
    EXPECT_LE(t, before + 1e-12) << k;
    before = t;
  }
  // At Brewster's angle p-polarised light passes each face whole.
  const double brewster = std::atan(1.5), c = std::cos(brewster), ct = std::sqrt(1 - std::sin(brewster) * std::sin(brewster) / 2.25);
  const double rs = (c - 1.5 * ct) / (c + 1.5 * ct), Rs = rs * rs;
  EXPECT_NEAR(pane_transmittance(c, 1.5), 0.5 * ((1 - Rs) / (1 + Rs) + 1), 1e-12);
}

// The window room (test_scenes.h) with a pane of glass (filter 0.9, index 1.5) in its window; taken out
// of the solve (separate_clear_glass) as a bake takes it.
Scene pane_in_window() {
  Scene s = test::window_room();
  Material glass{"glass", {}, {}};
  glass.clear = {kFilter, kFilter, kFilter};
  glass.ior = kIor;
  s.materials.push_back(glass);
  Polygon pane = test::window_opening();
  pane.material = uint32_t(s.materials.size() - 1);
  s.polygons.push_back(pane);
  return s;
}
Scene glazed_room() {
  Scene s = pane_in_window();
  EXPECT_EQ(separate_clear_glass(s), 1u);
  return s;
}

// The uniform sky through the pane at a floor point: L ∫ T(θg) cos θx cos θg / r² dA over the window,
// by an N × N midpoint rule, N from 80 far from the window's plane to 400 within 6 cm of it.
double exact_through_glass(const Vec3& x) {
  const int kN = std::clamp(int(24 / std::max(6 - x.x, 1e-3)), 80, 400);
  double sum = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const Vec3 y(6, 2 + 2.0 * (i + 0.5) / kN, 1 + 1.2 * (j + 0.5) / kN);
      const Vec3 d = y - x;
      const double r2 = dot(d, d), r = std::sqrt(r2), cx = d.z / r, cg = d.x / r;
      sum += kFilter * pane_transmittance(cg, kIor) * cx * cg / r2;
    }
  return kL * sum * (2.0 * 1.2) / double(kN * kN);
}

TEST(ClearGlass, TheSunThroughAGlazedWindow) {
  Scene s = glazed_room();
  PunctualLight sun;
  sun.type = PunctualLight::Type::directional;
  sun.direction = {-std::cos(kPi / 6), 0, -std::sin(kPi / 6)};  // 30° high, from +x
  sun.intensity = {100, 100, 100};
  sun.angular_diameter = 0;
  s.lights.push_back(sun);
  const RayScene rays(s);
  uint64_t cast = 0;
  // Through the window onto x ∈ [6 − 2.2 / tan 30°, 6 − 1 / tan 30°] = [2.19, 4.27], y ∈ [2, 4].
  const double lit = 100 * 0.5 * kFilter * pane_transmittance(std::cos(kPi / 6), kIor);
  EXPECT_NEAR(point_irradiance({3.2, 3, 0}, kUp, s.lights, &rays, cast).x, lit, 1e-9 * lit);
  EXPECT_EQ(point_irradiance({1.5, 3, 0}, kUp, s.lights, &rays, cast).x, 0.0);
  // The reference tracer: the same.
  const ReferenceTracer tracer(s, rays);
  uint64_t traced = 0;
  EXPECT_NEAR(tracer.estimate({0, {3.2, 3, 0}}, 64, 1, 0, traced).B.x, 0.5 * lit, 1e-6 * lit);
}

// The uniform sky through the glazed window at the defaults: floor points within 1% of the Fresnel-weighted
// integral, the reference tracer within its error bar.
TEST(ClearGlass, TheSkyThroughAGlazedWindow) {
  Scene s = glazed_room();
  set_sky(s, parse_sky("uniform:1000", "--sky", "", kUp, {}));
  const RayScene rays(s);
  // A grid of the floor, and points 5 to 20 cm from the window's wall, where the pane is seen edge-on.
  std::vector<Vec3> points;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) points.push_back({0.5 + i, 0.5 + j, 0});
  for (const double y : {1.5, 2.0, 3.0, 3.98, 4.6}) points.push_back({5.95, y, 0}), points.push_back({5.8, y, 0});
  double worst = 0;
  for (const Vec3& x : points) {
    const double exact = exact_through_glass(x);
    uint64_t cast = 0;
    const double e = sky_irradiance(*s.lights[0].sky, kUp, x + kUp * rays.offset(), &rays, kSkyAtPoints, cast).x;
    worst = std::max(worst, std::fabs(e - exact) / exact);
    EXPECT_NEAR(e, exact, 0.01 * exact) << "at " << x.x << ", " << x.y;
    // Glass takes at least its reflection and filter away: below the open window's L π F.
    EXPECT_LT(e, 0.93 * kFilter * kL * kPi * point_to_polygon(x, kUp, test::window_opening()));
  }
  std::printf("worst %.3f%%\n", 100 * worst);
  const ReferenceTracer tracer(s, rays);
  for (const Vec3 x : {Vec3(5, 3, 0), Vec3(2, 2, 0)}) {
    uint64_t traced = 0;
    const RadiosityEstimate r = tracer.estimate({0, x}, 65536, 3, 1, traced);
    EXPECT_NEAR(r.B.x, 0.5 * exact_through_glass(x), 4 * r.standard_error.x) << "at " << x.x << ", " << x.y;
  }
}

class ClearGlassFile : public test::TempDirTest {};

// Read from glTF (KHR_materials_transmission with roughness 0, KHR_materials_ior) and MGF (ts with
// roughness 0, ir), written back by the writer; rough transmission stays diffuse.
TEST_F(ClearGlassFile, ReadAndWritten) {
  Scene s = test::window_room();
  Material glass{"glass", {0.095, 0.09, 0.085}, {}};  // a base colour (0.95, 0.9, 0.85), 90% transmitted
  glass.clear = {0.855, 0.81, 0.765};
  glass.ior = 1.52;
  s.materials.push_back(glass);
  Polygon pane = test::window_opening();
  pane.material = uint32_t(s.materials.size() - 1);
  s.polygons.push_back(pane);
  const std::string file = (dir_ / "glazed.gltf").string();
  write_scene_gltf(s, file);
  const Scene back = read_gltf(file);
  size_t clear = 0;
  for (const Material& m : back.materials)
    if (m.is_clear_glass()) {
      ++clear;
      EXPECT_NEAR(m.ior, 1.52, 1e-12);
      EXPECT_NEAR(m.clear.x, 0.855, 1e-6);
      EXPECT_NEAR(m.clear.z, 0.765, 1e-6);
      EXPECT_NEAR(m.reflectance.x, 0.095, 1e-6);
      EXPECT_EQ(m.transmittance, Vec3());
    }
  EXPECT_EQ(clear, 1u);
  // Rough: diffused as before.
  nlohmann::json g = nlohmann::json::parse(std::ifstream(file));
  for (auto& m : g["materials"])
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_transmission")) m["pbrMetallicRoughness"]["roughnessFactor"] = 0.5;
  const std::string rough = (dir_ / "rough.gltf").string();
  std::ofstream(rough) << g.dump();
  for (const Material& m : read_gltf(rough).materials) EXPECT_FALSE(m.is_clear_glass()) << m.name;
  // MGF.
  const std::string mgf = (dir_ / "pane.mgf").string();
  std::ofstream(mgf) << "m glass =\n c\n ts 0.9 0\n ir 1.52 0\nv a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 1 0\nf a b c\n";
  const Scene m = read_mgf(mgf);
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_TRUE(m.materials[0].is_clear_glass());
  EXPECT_NEAR(m.materials[0].ior, 1.52, 1e-12);
  EXPECT_NEAR(luminance(m.materials[0].clear), 0.9, 1e-3);
}

// The bake at its defaults: the floor under the uniform sky through the glazed window within 2% of
// ρ × the Fresnel-weighted integral (read a little way into each face: test::floor_range_near).
TEST_F(ClearGlassFile, TheSkyThroughAGlazedWindowInABake) {
  Scene s = pane_in_window();
  set_sky(s, parse_sky("uniform:1000", "--sky", "", kUp, {}));
  const std::string file = (dir_ / "glazed.glb").string();
  write_scene_gltf(s, file);
  BakeSettings b;
  b.scene = file;
  b.output = (dir_ / "bake").string();
  b.progress = false;
  b.exposure = 1.0;
  bake(b);
  std::ifstream in(b.output + "/report.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_NE(r["effects"]["transmission"]["reason"].get<std::string>().find("1 polygons of clear glass (index 1.5)"), std::string::npos);
  int seen = 0;
  const double worst =
      test::expect_floor_within(read_bake_mesh(b.output), [](const Vec3& y) { return 0.5 * exact_through_glass(y); }, 0.02, seen);
  EXPECT_GT(seen, 20);
  std::printf("%d floor vertices, worst %.3f%%\n", seen, 100 * worst);
}

}  // namespace
}  // namespace walkrad
