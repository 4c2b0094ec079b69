// The sky (sky.h, sky_light.h): its radiance formulas, the irradiance it gives under the open sky
// (π L; the overcast sky's 7π Lz / 9), and through a window, where the uniform sky's light at a point
// is L π F(point → window) by the contour formula; the reference tracer the same; bakes through a file.
#include "walkrad/formfactor/sky_light.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "walkrad/accuracy/reference_tracer.h"
#include "walkrad/bake/bake.h"
#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/testing/floor_check.h"
#include "walkrad/testing/temp_dir_test.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;
const Vec3 kUp(0, 0, 1);

Sky sky(const std::string& spec, const std::vector<PunctualLight>& lights = {}) { return parse_sky(spec, "--sky", spec, kUp, lights); }

Scene open_floor() {
  Scene s;
  s.up = kUp;
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.polygons.push_back(test::rect(2, 0, -5, 5, -5, 5, +1, 0));
  return s;
}

// The room with its window (test_scenes.h), under a uniform sky bright enough that the chunks' 1/1000 of
// white (π at exposure 1) is far below what the floor shows.
constexpr double kL = 1000;
Scene window_room() {
  Scene s = test::window_room();
  set_sky(s, sky("uniform:1000"));
  return s;
}
const Polygon kWindow = test::window_opening();

TEST(Sky, Formulas) {
  const Sky overcast = sky("cie-overcast:900");
  EXPECT_NEAR(overcast.at(kUp).x, 900, 1e-9);
  EXPECT_NEAR(overcast.at(normalize(Vec3(1, 0, 1))).x, 900 * (1 + 2 * std::sqrt(0.5)) / 3, 1e-9);
  EXPECT_EQ(overcast.at(normalize(Vec3(1, 0, -0.1))).x, 0.0);  // below the horizon: the ground's
  // The clear sky: Lz at the zenith whatever the sun; towards the sun f(0) φ(θs) / (f(θs) φ(0)).
  const Vec3 sun = normalize(Vec3(1, 0, 1));
  const Sky clear = sky("cie-clear:1000@1,0,1");
  EXPECT_NEAR(clear.at(kUp).x, 1000, 1e-9);
  const double f0 = 0.91 + 10 + 0.45, fs = 0.91 + 10 * std::exp(-3 * kPi / 4) + 0.45 * 0.5;
  const double phi = 1 - std::exp(-0.32 / std::sqrt(0.5)), phi0 = 1 - std::exp(-0.32);
  EXPECT_NEAR(clear.at(sun).x, 1000 * f0 * phi / (fs * phi0), 1e-3);  // γ = acos(≈1): 1e-8 off
  // Its sun from the scene's directional light.
  PunctualLight l;
  l.type = PunctualLight::Type::directional;
  l.direction = -sun;
  EXPECT_NEAR(length(sky("cie-clear:1000", {l}).sun - sun), 0, 1e-12);
  EXPECT_EQ(sky("uniform:1,2,3").at(kUp), Vec3(1, 2, 3));
}

// Under the open sky: π L for the uniform sky on the ground, π L / 2 on a wall (half its hemisphere is
// the ground's), 7π Lz / 9 for the overcast sky on the ground; one ray a coarse cell where nothing
// changes.
TEST(SkyLight, TheOpenSky) {
  const Scene s = open_floor();
  const RayScene rays(s);
  uint64_t cast = 0;
  const Vec3 from(0, 0, 1e-6);
  const Sky uniform = sky("uniform:10");
  EXPECT_NEAR(sky_irradiance(uniform, kUp, from, &rays, kSkyAtPoints, cast).x, 10 * kPi, 1e-9);
  EXPECT_EQ(cast, uint64_t(kSkyAtPoints.base * kSkyAtPoints.base));
  const Vec3 wall = sky_irradiance(uniform, {1, 0, 0}, {0, 0, 1}, &rays, kSkyAtPoints, cast);
  EXPECT_NEAR(wall.x, 5 * kPi, 0.005 * 5 * kPi);
  const Sky overcast = sky("cie-overcast:9");
  EXPECT_NEAR(sky_irradiance(overcast, kUp, from, &rays, kSkyAtPoints, cast).x, 7 * kPi, 0.001 * 7 * kPi);
}

// Through a window, at the defaults: every floor point within 2% of L π F(point → window), with far
// fewer rays than the finest cells.
TEST(SkyLight, TheUniformSkyThroughAWindowIsTheContourFormula) {
  const Scene s = window_room();
  const RayScene rays(s);
  const Sky uniform = sky("uniform:1000");
  double worst = 0;
  uint64_t most = 0;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      const Vec3 x(0.25 + 0.5 * i, 0.25 + 0.5 * j, 0);
      const double exact = kL * kPi * point_to_polygon(x, kUp, kWindow);
      uint64_t cast = 0;
      const double e = sky_irradiance(uniform, kUp, x + kUp * rays.offset(), &rays, kSkyAtPoints, cast).x;
      worst = std::max(worst, std::fabs(e - exact) / exact);
      most = std::max(most, cast);
      EXPECT_NEAR(e, exact, 0.02 * exact) << "at " << x.x << ", " << x.y;
    }
  EXPECT_LE(most, uint64_t(kSkyAtPoints.budget));
  std::printf("worst %.3f%%, at most %llu rays a point\n", 100 * worst, static_cast<unsigned long long>(most));
}

// The reference tracer's sky (one cosine-weighted ray a vertex): the floor under the open sky shows
// ρ π L, the floor through the window ρ L π F, within its own standard error's reach.
TEST(SkyLight, TheReferenceTracerSeesTheSameSky) {
  Scene open = open_floor();
  set_sky(open, sky("uniform:10"));
  const RayScene open_rays(open);
  const ReferenceTracer open_tracer(open, open_rays);
  uint64_t rays = 0;
  const RadiosityEstimate o = open_tracer.estimate({0, {0, 0, 0}}, 4096, 1, 0, rays);
  EXPECT_NEAR(o.B.x, 0.5 * 10 * kPi, 1e-9);  // every ray leaves: no noise
  const Scene room = window_room();
  const RayScene room_rays(room);
  const ReferenceTracer tracer(room, room_rays);
  for (const Vec3 x : {Vec3(5, 3, 0), Vec3(3, 3, 0), Vec3(1, 1, 0)}) {
    const RadiosityEstimate e = tracer.estimate({0, x}, 65536, 7, 1, rays);
    const double exact = 0.5 * kL * kPi * point_to_polygon(x, kUp, kWindow);
    EXPECT_NEAR(e.B.x, exact, 4 * e.standard_error.x + 1e-12) << "at " << x.x << ", " << x.y;
  }
}

// An equirectangular map: its top row is the zenith, its middle row the horizon, column u = ½ + atan2(z, x)/2π
// with the zenith as +Y. A map of one value is the uniform sky over the whole sphere.
class SkyFile : public test::TempDirTest {};

TEST_F(SkyFile, AnEquirectangularMap) {
  constexpr int kW = 64, kH = 32;
  std::vector<float> rgb(kW * kH * 3);
  for (int r = 0; r < kH; ++r)
    for (int c = 0; c < kW; ++c) {
      float* p = &rgb[3 * (r * kW + c)];
      p[0] = r < kH / 2 ? 4.0f : 1.0f;         // sky above, ground below
      p[1] = float(c) / kW;                      // the column
      p[2] = 2.0f;
    }
  const std::string file = (dir_ / "sky.hdr").string();
  ASSERT_TRUE(stbi_write_hdr(file.c_str(), kW, kH, 3, rgb.data()));
  const Sky map = parse_sky(file, "--sky", file, {0, 1, 0}, {});
  EXPECT_EQ(map.kind, Sky::Kind::image);
  EXPECT_NEAR(map.at({0, 1, 0}).x, 4.0, 1e-6);
  EXPECT_NEAR(map.at({0, -1, 0}).x, 1.0, 1e-6);
  // −X: atan2(0, −1) = π, u = 1 (the right edge, wrapping to the left); +X: u = ½; +Z: u = ¾.
  // (RGBE keeps 8 bits of mantissa under the pixel's largest channel: columns to within 1/32.)
  EXPECT_NEAR(map.at(normalize(Vec3(1, 0.2, 0))).y, 0.5, 1.5 / kW);
  EXPECT_NEAR(map.at(normalize(Vec3(0, 0.2, 1))).y, 0.75, 1.5 / kW);
  EXPECT_NEAR(map.at(normalize(Vec3(0, 0.2, -1))).y, 0.25, 1.5 / kW);
  // z up: the same map turned, its top row now +Z.
  const Sky turned = parse_sky(file, "--sky", file, kUp, {});
  EXPECT_NEAR(turned.at(kUp).x, 4.0, 1e-6);
  EXPECT_NEAR(turned.at(-kUp).x, 1.0, 1e-6);
  // A refusal names the file: not an .hdr inside.
  const std::string fake = (dir_ / "fake.hdr").string();
  std::ofstream(fake) << "not an image";
  try {
    parse_sky(fake, "--sky", fake, kUp, {});
    FAIL() << "read a file that is no image";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), fake);
    EXPECT_NE(e.message().find("Radiance .hdr"), std::string::npos) << e.what();
  }
}

// Through a file: the sky in the scene's extras comes back from the glTF writer and reader, the plan
// names it, and the bake at its defaults shows every floor vertex within 2% of ρ L π F (the walls are
// black: nothing else reaches the floor), the same bytes from one thread as from two.
TEST_F(SkyFile, TheUniformSkyThroughAWindowInABake) {
  const Scene s = window_room();
  const std::string file = (dir_ / "room.glb").string();
  write_scene_gltf(s, file);
  const Scene back = read_gltf(file);
  ASSERT_EQ(back.lights.size(), 1u);
  ASSERT_EQ(back.lights[0].type, PunctualLight::Type::sky);
  EXPECT_EQ(back.lights[0].sky->spec, "uniform:1000");
  EXPECT_LT(length(back.lights[0].sky->up - kUp), 1e-12);

  BakeSettings b;
  b.scene = file;
  b.output = (dir_ / "room").string();
  b.progress = false;
  b.exposure = 1.0;
  bake(b);
  std::ifstream in(b.output + "/report.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_NE(r["effects"]["punctual"]["reason"].get<std::string>().find("a uniform sky"), std::string::npos);
  // A vertex shows the solution read a little way into each face around it: at the far corners, where the
  // floor's leaves are large, a few centimetres in (test::floor_range_near).
  int seen = 0;
  const double worst = test::expect_floor_within(
      read_bake_mesh(b.output), [](const Vec3& y) { return 0.5 * kL * kPi * point_to_polygon(y, kUp, kWindow); }, 0.02, seen);
  EXPECT_GT(seen, 20);
  std::printf("%d floor vertices, worst %.3f%%\n", seen, 100 * worst);
  BakeSettings one = b;
  one.output = (dir_ / "room-1").string();
  one.threads = 1;
  bake(one);
  test::expect_same_bake_files(b.output, one.output);
}

}  // namespace
}  // namespace walkrad
