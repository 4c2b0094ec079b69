// IES luminaires (ies.h, punctual_lights.h): a type C profile above a large grey floor,
// written as a glTF EXT_lights_ies light and read back, baked by both methods and traced by the
// reference tracer. The floor sees nothing, so B = ρ · I(γ, C) · cos θ / r² at every point, with
// I the profile's own interpolation in the light's frame, computed here from the node's known
// rotation (not from light_frame).
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "walkrad/accuracy/reference_tracer.h"
#include "walkrad/bake/bake.h"
#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/ies.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/formfactor/punctual_lights.h"
#include "walkrad/testing/temp_dir_test.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

constexpr double kDeg = kPi / 180;

// The test's luminaire: a downlight with some side light, varying with C as the symmetry allows,
// smoothly through the nadir (sin γ cos C = x/r, sin²γ cos 2C = (x² − y²)/r²: one value at γ = 0).
double formula(double gamma_deg, double c_deg, double last_horizontal) {
  const double g = gamma_deg * kDeg, c = c_deg * kDeg, s = std::sin(g);
  const double down = 800 * std::pow(std::max(0.0, std::cos(g)), 1.5) + 60;
  double around = 1;
  if (last_horizontal >= 90) around += 0.25 * s * s * std::cos(2 * c);  // quadrant-symmetric
  if (last_horizontal >= 180) around += 0.2 * s * std::cos(c);          // bilateral about 0–180
  if (last_horizontal >= 360) around += 0.15 * s * std::sin(c);         // no symmetry
  return down * around;
}

// LM-63-2002 text of the formula: vertical 0..180 every 5°, horizontal 0..last every 15° (one
// plane for last = 0), candela multiplier 2.
std::string profile_text(double last_horizontal) {
  std::string t = "IESNA:LM-63-2002\r\n[TEST] walkrad ies_lights_test\r\n[MANUFAC] formula\r\nTILT=NONE\r\n";
  const int nv = 37, nh = last_horizontal > 0 ? int(last_horizontal / 15) + 1 : 1;
  t += "1 -1 2 " + std::to_string(nv) + " " + std::to_string(nh) + " 1 2 0 0 0\r\n1 1 100\r\n";
  for (int v = 0; v < nv; ++v) t += std::to_string(5 * v) + (v + 1 < nv ? " " : "\r\n");
  for (int h = 0; h < nh; ++h) t += std::to_string(15 * h) + (h + 1 < nh ? " " : "\r\n");
  char number[32];
  for (int h = 0; h < nh; ++h)
    for (int v = 0; v < nv; ++v) {
      std::snprintf(number, sizeof number, "%.4f", formula(5 * v, 15 * h, last_horizontal) / 2);
      t += std::string(number) + (v + 1 < nv ? " " : "\r\n");
    }
  return t;
}

// A 5 m grey floor (z = 0) and the luminaire 2 m above its centre, aimed down, turned 30° about
// the vertical: its +X (C = 0) points along (cos 30°, sin 30°, 0). A camera 6 m up sees the floor.
Scene floor_under(const std::shared_ptr<const IesProfile>& profile) {
  Scene s;
  s.source = "floor";
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.polygons.push_back(test::quad({-2.5, -2.5, 0}, {2.5, -2.5, 0}, {2.5, 2.5, 0}, {-2.5, 2.5, 0}));
  PunctualLight l;
  l.type = PunctualLight::Type::ies;
  l.name = "downlight";
  l.position = {0, 0, 2};
  l.direction = {0, 0, -1};
  l.up = {-std::sin(30 * kDeg), std::cos(30 * kDeg), 0};  // the node's +Y: +X turned by 30°, then 90°
  l.intensity = {0.01, 0.01, 0.01};                       // W/sr per candela (colour × multiplier)
  l.profile = profile;
  s.lights.push_back(l);
  Viewpoint v;
  v.name = "above";
  v.position = {0, 0, 6};
  v.forward = {0, 0, -1};
  v.up = {0, 1, 0};
  v.yfov = 1.2;
  s.cameras.push_back(v);
  return s;
}

// The floor's irradiance at x from the profile: the direction from the light, in its frame by the
// 30° turn (x' = (cos, sin)·d, y' = (−sin, cos)·d, z' = d.z); candela × 0.01 W/sr; cos θ / r².
double exact(const IesProfile& profile, const Vec3& x) {
  const Vec3 d = x - Vec3(0, 0, 2);
  const double r = length(d);
  const Vec3 w = d / r;
  const double c = std::cos(30 * kDeg), s = std::sin(30 * kDeg);
  const Vec3 local(c * w.x + s * w.y, -s * w.x + c * w.y, w.z);
  return 0.01 * profile.intensity(local) * (2 / r) / (r * r);
}

// The formula itself at x (candela × 2 × 0.01 W/sr, cos θ / r²): γ from the nadir, C from the
// light's +X, turned 30°. Checks the profile's mirroring against the formula, not against itself.
double formula_at(const Vec3& x, double last) {
  const Vec3 d = x - Vec3(0, 0, 2);
  const double r = length(d);
  const double gamma = std::acos(-d.z / r) / kDeg;
  double c = std::atan2(d.y, d.x) / kDeg - 30;
  if (c < 0) c += 360;
  return 0.01 * formula(gamma, c, last) * (2 / r) / (r * r);
}

// 20 points on a spiral out to 2 m from the centre (γ up to 45°).
std::vector<Vec3> floor_points() {
  std::vector<Vec3> p;
  for (int k = 0; k < 20; ++k) {
    const double r = 2.0 * (k + 0.5) / 20, a = k * 2.39996;  // the golden angle
    p.push_back({r * std::cos(a), r * std::sin(a), 0});
  }
  return p;
}

class IesLuminaire : public test::TempDirTest, public ::testing::WithParamInterface<double> {};

TEST_P(IesLuminaire, FloorIrradianceMatchesTheProfile) {
  const double last = GetParam();
  auto profile = std::make_shared<IesProfile>(parse_ies(profile_text(last), "formula.ies"));
  profile->text = profile_text(last);
  // The profile interpolates the formula (candela × the multiplier 2) at its own angles.
  EXPECT_NEAR(profile->candela_at(45, 30), formula(45, 30, last), 1e-3);
  const Scene s = floor_under(profile);

  // Through a file: EXT_lights_ies written (profile in a bufferView) and read back.
  const std::string file = (dir_ / "floor.glb").string();
  write_scene_gltf(s, file);
  const Scene back = read_gltf(file);
  ASSERT_EQ(back.lights.size(), 1u);
  const PunctualLight& l = back.lights[0];
  ASSERT_EQ(l.type, PunctualLight::Type::ies);
  EXPECT_EQ(l.profile->text, profile->text);
  EXPECT_NEAR(l.intensity.x, 0.01, 1e-9);
  EXPECT_LT(length(l.up - s.lights[0].up), 1e-9);
  EXPECT_LT(length(l.direction - Vec3(0, 0, -1)), 1e-9);

  // The reference tracer: exact (no bounce, one shadow ray per light).
  const RayScene rays(back);
  const ReferenceTracer tracer(back, rays);
  std::vector<SurfacePoint> points;
  for (const Vec3& x : floor_points()) points.push_back({0, x});
  ReferenceSettings rs;
  rs.samples = 4;
  uint64_t cast = 0;
  const std::vector<RadiosityEstimate> traced = tracer.estimate(points, rs, cast);
  for (size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR(traced[k].B.x, 0.5 * exact(*profile, points[k].position), 1e-9 * traced[k].B.x) << "traced point " << k;
    // The profile's interpolation (5° × 15° web, quadrants mirrored) against the formula: within 1%.
    const double f = formula_at(points[k].position, last);
    EXPECT_NEAR(exact(*profile, points[k].position), f, 0.01 * f) << "point " << k;
  }

  // Both methods: the output vertex nearest each point (the hierarchical bake gathers at the
  // vertices the camera sees; the classic one averages 12.5 cm elements around them).
  for (const std::string method : {"hierarchical", "classic"}) {
    BakeSettings b;
    b.scene = file;
    b.output = (dir_ / method).string();
    b.method = parse_method(method);
    b.element_size = 0.125;
    b.progress = false;
    b.exposure = 1.0;
    bake(b);
    const ChunkMesh mesh = read_bake_mesh(b.output);
    for (const Vec3& x : floor_points()) {
      size_t best = 0;
      double nearest = INFINITY;
      for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Vec3 p(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
        if (mesh.normals[3 * v + 2] > 0.9 && length(p - x) < nearest) nearest = length(p - x), best = v;
      }
      ASSERT_LT(nearest, 0.2) << method;
      const Vec3 p(mesh.positions[3 * best], mesh.positions[3 * best + 1], 0);
      const double want = 0.5 * exact(*profile, p);
      EXPECT_NEAR(mesh.radiosity[3 * best], want, 0.01 * want) << method << " at " << p.x << ", " << p.y;
    }
  }
}

// One quadrant (0–90, mirrored into four), two (0–180, mirrored about the 0–180 plane), four (0–360),
// and a rotationally symmetric profile (one plane).
INSTANTIATE_TEST_SUITE_P(Symmetries, IesLuminaire, ::testing::Values(0.0, 90.0, 180.0, 360.0));

TEST(IesPower, PowerIsTheProfilesFluxTimesTheIntensity) {
  auto profile = std::make_shared<IesProfile>(parse_ies(profile_text(0), "formula.ies"));
  PunctualLight l;
  l.type = PunctualLight::Type::ies;
  l.profile = profile;
  l.intensity = {0.5, 0.25, 0.0};
  const Vec3 power = punctual_power(l);
  EXPECT_NEAR(power.x, 0.5 * profile->flux(), 1e-9 * power.x);
  EXPECT_NEAR(power.y, 0.25 * profile->flux(), 1e-9 * power.x);
  // The flux of the formula's rotationally symmetric part, ∫ (800 cos^1.5 γ + 60) dΩ over the
  // sphere (the cosine term below the horizon only): 2π (800 / 2.5 + 60 · 2).
  EXPECT_NEAR(profile->flux(), 2 * kPi * (800 / 2.5 + 120), 0.01 * profile->flux());
}

}  // namespace
}  // namespace walkrad
