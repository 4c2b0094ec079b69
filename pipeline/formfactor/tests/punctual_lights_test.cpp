// Punctual lights (punctual_lights.h): point and spot sources shot straight to elements,
// against the analytic irradiance I cos θ / r² (times the spot falloff), in the solvers and in a bake.
#include "walkrad/formfactor/punctual_lights.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "walkrad/testing/temp_dir_test.h"
#include "walkrad/testing/test_scenes.h"
#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/bake/bake.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/hierarchical/hierarchical_solver.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;

PunctualLight spot(Vec3 position, Vec3 direction, double intensity, double inner, double outer) {
  PunctualLight l;
  l.type = PunctualLight::Type::spot;
  l.position = position;
  l.direction = normalize(direction);
  l.intensity = Vec3(intensity, intensity, intensity);
  l.inner_cone = inner;
  l.outer_cone = outer;
  return l;
}

PunctualLight point(Vec3 position, double intensity) {
  PunctualLight l;
  l.position = position;
  l.intensity = Vec3(intensity, intensity, intensity);
  return l;
}

// The analytic irradiance on the floor (z = 0, normal +z) at (x, y), averaged over a polygon by a
// 64 × 64 midpoint rule on its bounding rectangle (axis-aligned floor squares only).
double exact_mean(const PunctualLight& l, const Polygon& p) {
  Bounds b;
  for (int k = 0; k < p.count; ++k) b.extend(p.v[k]);
  constexpr int kN = 64;
  double sum = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const Vec3 x(b.lo.x + (b.hi.x - b.lo.x) * (i + 0.5) / kN, b.lo.y + (b.hi.y - b.lo.y) * (j + 0.5) / kN, 0);
      const Vec3 d = l.position - x;
      const double r2 = dot(d, d), r = std::sqrt(r2);
      sum += l.intensity.x * (d.z / r) / r2 * light_distribution(l, -(d / r));
    }
  return sum / (kN * kN);
}

TEST(PunctualLights, PowerOfPointAndSpot) {
  EXPECT_NEAR(punctual_power(point({0, 0, 0}, 2.0)).x, 8 * kPi, 1e-12);
  // Full intensity inside the inner cone, the falloff's (ramp)² between the cones: a third of the ring.
  const PunctualLight ring = spot({0, 0, 0}, {0, 0, -1}, 1.0, 0.4, 0.5);
  EXPECT_NEAR(punctual_power(ring).x, 2 * kPi * ((1 - std::cos(0.4)) + (std::cos(0.4) - std::cos(0.5)) / 3), 1e-7);
  // Inner cone 0: the falloff ((cos θ − cos outer) / (1 − cos outer))² integrates to a third of the cone.
  const PunctualLight soft = spot({0, 0, 0}, {0, 0, -1}, 1.0, 0.0, 0.5);
  EXPECT_NEAR(punctual_power(soft).x, 2 * kPi * (1 - std::cos(0.5)) / 3, 1e-6);
}

TEST(PunctualLights, ElementIrradianceMatchesTheAnalyticMean) {
  const PunctualLight l = point({0.3, 0.2, 1.0}, 5.0);
  const Polygon p = test::quad({0, 0, 0}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0});
  uint64_t rays = 0;
  const DirectIrradiance d = direct_irradiance(p, {l}, nullptr, 4, rays);
  EXPECT_NEAR(d.mean.x, exact_mean(l, p), 5e-3 * exact_mean(l, p));  // 4 × 4 midpoint rule: measured 0.34%
  EXPECT_GT(d.spread, 0.0);
  EXPECT_EQ(rays, 0u);  // no occluders given: no shadow rays
}

// A spot light 2 m above a floor, pointing down, cones of 20° and 30°: the hierarchical solver lights
// only the floor inside the outer cone (r < 2 tan 30° = 1.155 m); inside the inner cone each leaf
// has B = ρ × the analytic mean irradiance. The floor alone has no links (nothing it can see).
TEST(PunctualLights, SpotLightLightsOnlyItsCone) {
  Scene s;
  s.source = "floor";
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.polygons.push_back(test::quad({-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}));
  s.lights.push_back(spot({0, 0, 2}, {0, 0, -1}, 20.0, 20 * kPi / 180, 30 * kPi / 180));
  const RayScene rays(s);
  const ClusterTree tree = build_cluster_tree(s);
  Hierarchy h(s, tree);
  HierarchicalSettings settings;
  settings.lights = &s.lights;
  HierarchicalStats stats;
  solve_hierarchical(h, rays, settings, stats);
  EXPECT_GT(stats.light_refinements, 0u);
  const double edge = 2 * std::tan(30 * kPi / 180), inner = 2 * std::tan(20 * kPi / 180);
  int outside = 0, within = 0;
  for (const HNode& n : h.nodes()) {
    if (n.cluster || n.child_count) continue;
    double nearest = INFINITY, farthest = 0;
    for (int k = 0; k < n.shape.count; ++k) {
      nearest = std::min(nearest, std::hypot(n.shape.v[k].x, n.shape.v[k].y));
      farthest = std::max(farthest, std::hypot(n.shape.v[k].x, n.shape.v[k].y));
    }
    // The leaf's nearest point may still be outside while an edge crosses the cone: use its corners'
    // distance only when the whole leaf lies beyond the cone's circle (the square's corners bound it).
    const bool beyond = nearest > edge + 1e-9 && !(std::fabs(n.center.x) < n.radius || std::fabs(n.center.y) < n.radius);
    if (beyond) {
      ++outside;
      EXPECT_EQ(n.B.x, 0.0) << "leaf at " << n.center.x << ", " << n.center.y;
    } else if (farthest < inner) {
      ++within;
      EXPECT_NEAR(n.B.x, 0.5 * exact_mean(s.lights[0], n.shape), 5e-3 * n.B.x) << "leaf at " << n.center.x << ", " << n.center.y;
    }
  }
  EXPECT_GT(outside, 0);
  EXPECT_GT(within, 4);
}

class PunctualBake : public test::TempDirTest {
 protected:
};

// Through a file: the glTF writer and reader keep the light (KHR_lights_punctual), the effect plan
// says so, and both methods light the floor under a point light as ρ I / h² predicts. Black walls
// and a grey floor (which cannot see itself): no indirect light reaches the floor. The light hangs
// inside a convex enclosure, so no shadow ray is needed (effect plan: visibility off).
TEST_F(PunctualBake, PointLightInARoomThroughAFile) {
  Scene s = test::closed_box(2.0, {0.0, 0.0, 0.0}, {});
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  for (Polygon& p : s.polygons)
    if (polygon_centroid(p).z < 1e-9) p.material = 1;
  s.lights.push_back(point({1, 1, 1.5}, 10.0));
  s.lights[0].name = "bulb";
  const std::string file = (dir_ / "room.glb").string();
  write_scene_gltf(s, file);
  const Scene back = read_gltf(file);
  ASSERT_EQ(back.lights.size(), 1u);
  EXPECT_EQ(back.lights[0].name, "bulb");
  EXPECT_LT(length(back.lights[0].position - Vec3(1, 1, 1.5)), 1e-6);
  EXPECT_NEAR(back.lights[0].intensity.x, 10.0, 1e-6);

  for (const std::string method : {"hierarchical", "classic"}) {
    BakeSettings b;
    b.scene = file;
    b.output = (dir_ / method).string();
    b.method = parse_method(method);
    b.element_size = 0.1;
    b.progress = false;
    b.exposure = 1.0;
    bake(b);
    std::ifstream in(b.output + "/report.json");
    const nlohmann::json r = nlohmann::json::parse(in);
    EXPECT_TRUE(r["effects"]["punctual"]["on"].get<bool>()) << method;
    EXPECT_FALSE(r["effects"]["visibility"]["on"].get<bool>()) << method;
    EXPECT_EQ(r["counts"]["light_rays"].get<uint64_t>(), 0u) << method;
    // The floor right under the light (vertices within 5 cm, so the mean over the elements there).
    const ChunkMesh mesh = read_bake_mesh(b.output);
    double under = 0;
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      if (std::fabs(mesh.positions[3 * v] - 1) < 0.051 && std::fabs(mesh.positions[3 * v + 1] - 1) < 0.051 &&
          std::fabs(mesh.positions[3 * v + 2]) < 1e-6 && mesh.normals[3 * v + 2] > 0.9)
        under = std::max(under, double(mesh.radiosity[3 * v]));
    const double direct = 0.5 * 10.0 / (1.5 * 1.5);
    EXPECT_NEAR(under, direct, 0.02 * direct) << method;
    // Closed: the audit balances (the lights' power counted where it lands).
    EXPECT_LE(r["energy_audit"]["imbalance"].get<double>(), 1e-4) << method;
  }
}

TEST_F(PunctualBake, NoEmitterAtAllIsAnError) {
  Scene s = test::closed_box(2.0, {0.5, 0.5, 0.5}, {});
  const std::string file = (dir_ / "dark.glb").string();
  write_scene_gltf(s, file);
  BakeSettings b;
  b.scene = file;
  b.output = (dir_ / "dark").string();
  b.progress = false;
  try {
    bake(b);
    ADD_FAILURE() << "baked a scene without any emitter";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), kExitBadInput);
    EXPECT_NE(std::string(e.what()).find("no emitter"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "dark"));
}

}  // namespace
}  // namespace walkrad
