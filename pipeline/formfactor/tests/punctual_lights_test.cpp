// Punctual lights (punctual_lights.h): point and spot sources shot straight to elements,
// against the analytic irradiance I cos θ / r² (times the spot falloff), in the solvers and in a bake.
#include "walkrad/formfactor/punctual_lights.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

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

// A scene solved by the hierarchical method at its defaults, its punctual lights on.
struct Solved {
  explicit Solved(const Scene& s) : rays(s), tree(build_cluster_tree(s)), h(s, tree) {
    settings.lights = &s.lights;
    solve_hierarchical(h, rays, settings, stats);
  }
  RayScene rays;
  ClusterTree tree;
  Hierarchy h;
  HierarchicalSettings settings;
  HierarchicalStats stats;
};

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
  const Solved solved(s);
  const Hierarchy& h = solved.h;
  EXPECT_GT(solved.stats.light_refinements, 0u);
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

// A roof 3 m above the floor (z = 3, black, facing down) with a 1 m square opening over x, y ∈ [0, 1],
// walls around, and the sun 30° from the zenith towards +x: light arrives along −w, w = (sin θ, 0, cos θ).
constexpr double kSunTheta = 30 * kPi / 180, kRoof = 3;
Scene roof_with_opening() {
  Scene s;
  s.source = "roof";
  s.materials.push_back({"floor", {0.5, 0.5, 0.5}, {}});
  s.materials.push_back({"black", {0, 0, 0}, {}});
  auto down = [](double x0, double y0, double x1, double y1) {  // a ceiling piece, facing down
    return test::quad({x0, y0, kRoof}, {x0, y1, kRoof}, {x1, y1, kRoof}, {x1, y0, kRoof}, 1);
  };
  s.polygons.push_back(test::quad({-4, -3, 0}, {2, -3, 0}, {2, 3, 0}, {-4, 3, 0}, 0));  // the floor, facing up
  s.polygons.push_back(down(-4, -3, 0, 3));
  s.polygons.push_back(down(1, -3, 2, 3));
  s.polygons.push_back(down(0, -3, 1, 0));
  s.polygons.push_back(down(0, 1, 1, 3));
  // Walls facing in.
  s.polygons.push_back(test::quad({-4, -3, 0}, {-4, 3, 0}, {-4, 3, kRoof}, {-4, -3, kRoof}, 1));
  s.polygons.push_back(test::quad({2, -3, 0}, {2, -3, kRoof}, {2, 3, kRoof}, {2, 3, 0}, 1));
  s.polygons.push_back(test::quad({-4, -3, 0}, {-4, -3, kRoof}, {2, -3, kRoof}, {2, -3, 0}, 1));
  s.polygons.push_back(test::quad({-4, 3, 0}, {2, 3, 0}, {2, 3, kRoof}, {-4, 3, kRoof}, 1));
  PunctualLight sun;
  sun.name = "sun";
  sun.type = PunctualLight::Type::directional;
  sun.direction = {-std::sin(kSunTheta), 0, -std::cos(kSunTheta)};
  sun.intensity = {100, 100, 100};
  s.lights.push_back(sun);
  return s;
}

// The opening's image on the floor along w: x ∈ [−3 tan θ, 1 − 3 tan θ], y ∈ [0, 1]. Across its edges
// parallel to y the penumbra is 3 (tan(θ + α/2) − tan(θ − α/2)) wide (α the sun's angular diameter).
const double kLitX0 = -kRoof * std::tan(kSunTheta), kLitX1 = 1 - kRoof * std::tan(kSunTheta);
const double kPenumbra = kRoof * (std::tan(kSunTheta + kSunDiameter / 2) - std::tan(kSunTheta - kSunDiameter / 2));

// At points: the sun's full irradiance E⊥ cos θ in the patch, exactly nothing in the shadow, and the
// penumbra across the patch's edge as wide as the sun's disc makes it, no wider.
TEST(PunctualLights, TheSunThroughAnOpening) {
  const Scene s = roof_with_opening();
  const RayScene rays(s);
  const Vec3 up(0, 0, 1);
  uint64_t cast = 0;
  const double full = 100 * std::cos(kSunTheta);
  EXPECT_NEAR(point_irradiance({(kLitX0 + kLitX1) / 2, 0.5, 0}, up, s.lights, &rays, cast).x, full, 1e-9 * full);
  EXPECT_EQ(cast, uint64_t(kSunRays));
  EXPECT_EQ(point_irradiance({1.5, 0.5, 0}, up, s.lights, &rays, cast).x, 0.0);
  EXPECT_EQ(point_irradiance({kLitX0 - kPenumbra, 0.5, 0}, up, s.lights, &rays, cast).x, 0.0);
  // A scan across the edge x = kLitX1 (the opening's x = 1): partly lit only within the penumbra,
  // over most of it, and darker the further out.
  double first = INFINITY, last = -INFINITY, before = full;
  for (int k = -400; k <= 400; ++k) {
    const double x = kLitX1 + kPenumbra * k / 200.0;
    const double e = point_irradiance({x, 0.5, 0}, up, s.lights, &rays, cast).x;
    EXPECT_LE(e, before + 1e-9 * full) << "at " << x;
    before = e;
    if (e > 0 && e < full * (1 - 1e-9)) first = std::min(first, x), last = std::max(last, x);
  }
  EXPECT_GE(first, kLitX1 - kPenumbra / 2 - 1e-9);
  EXPECT_LE(last, kLitX1 + kPenumbra / 2 + 1e-9);
  EXPECT_GT(last - first, 0.75 * kPenumbra);  // 16 rays: the pattern's outermost points reach 0.98 of the radius
  // A point source of the same direction (angular diameter 0): a hard edge.
  Scene hard = s;
  hard.lights[0].angular_diameter = 0;
  EXPECT_EQ(point_irradiance({kLitX1 - 1e-3, 0.5, 0}, up, hard.lights, &rays, cast).x, full);
  EXPECT_EQ(point_irradiance({kLitX1 + 1e-3, 0.5, 0}, up, hard.lights, &rays, cast).x, 0.0);
}

// The hierarchical solver at its defaults: every leaf wholly inside the sunlit patch (past the
// penumbra) shows ρ E⊥ cos θ, every leaf wholly outside it nothing (all else is black).
TEST(PunctualLights, TheSunLightsTheFloorThroughAnOpeningExactly) {
  const Scene s = roof_with_opening();
  const Solved solved(s);
  const Hierarchy& h = solved.h;
  const double lit = 0.5 * 100 * std::cos(kSunTheta), margin = kPenumbra / 2 + 1e-9;
  int inside = 0, outside = 0;
  for (const HNode& n : h.nodes()) {
    if (n.cluster || n.child_count || n.polygon != 0) continue;
    Bounds b;
    for (int k = 0; k < n.shape.count; ++k) b.extend(n.shape.v[k]);
    if (b.lo.x >= kLitX0 + margin && b.hi.x <= kLitX1 - margin && b.lo.y >= margin && b.hi.y <= 1 - margin) {
      ++inside;
      EXPECT_NEAR(n.B.x, lit, 0.01 * lit) << "leaf at " << n.center.x << ", " << n.center.y;
    } else if (b.hi.x <= kLitX0 - margin || b.lo.x >= kLitX1 + margin || b.hi.y <= -margin || b.lo.y >= 1 + margin) {
      ++outside;
      EXPECT_EQ(n.B.x, 0.0) << "leaf at " << n.center.x << ", " << n.center.y;
    }
  }
  EXPECT_GT(inside, 0);
  EXPECT_GT(outside, 0);
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

// The sun through a file: the glTF writer and reader keep it (KHR_lights_punctual "directional", its
// angular size in extras where not the sun's), the plan names it, and the bake's floor in the sunlit
// patch shows ρ E⊥ cos θ.
TEST_F(PunctualBake, TheSunThroughAFile) {
  Scene s = roof_with_opening();
  const std::string file = (dir_ / "roof.glb").string();
  write_scene_gltf(s, file);
  const Scene back = read_gltf(file);
  ASSERT_EQ(back.lights.size(), 1u);
  EXPECT_EQ(back.lights[0].type, PunctualLight::Type::directional);
  EXPECT_LT(length(back.lights[0].direction - s.lights[0].direction), 1e-6);
  EXPECT_NEAR(back.lights[0].intensity.x, 100.0, 1e-6);
  EXPECT_EQ(back.lights[0].angular_diameter, kSunDiameter);
  s.lights[0].angular_diameter = 0.01;
  const std::string wider = (dir_ / "wider.glb").string();
  write_scene_gltf(s, wider);
  EXPECT_NEAR(read_gltf(wider).lights[0].angular_diameter, 0.01, 1e-12);

  BakeSettings b;
  b.scene = file;
  b.output = (dir_ / "roof").string();
  b.progress = false;
  b.exposure = 1.0;
  bake(b);
  std::ifstream in(b.output + "/report.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_NE(r["effects"]["punctual"]["reason"].get<std::string>().find("1 directional"), std::string::npos);
  EXPECT_TRUE(r["effects"]["visibility"]["on"].get<bool>());
  const ChunkMesh mesh = read_bake_mesh(b.output);
  const double lit = 0.5 * 100 * std::cos(kSunTheta);
  int seen = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.positions[3 * v], y = mesh.positions[3 * v + 1], z = mesh.positions[3 * v + 2];
    if (std::fabs(z) > 1e-6 || mesh.normals[3 * v + 2] < 0.9) continue;
    if (x > kLitX0 + 0.2 && x < kLitX1 - 0.2 && y > 0.2 && y < 0.8) {
      ++seen;
      EXPECT_NEAR(mesh.radiosity[3 * v], lit, 0.01 * lit) << "at " << x << ", " << y;
    } else if (x > kLitX1 + 0.5 || y > 1.5 || y < -0.5) {
      EXPECT_EQ(mesh.radiosity[3 * v], 0.0f) << "at " << x << ", " << y;
    }
  }
  EXPECT_GT(seen, 0);
  // The spots' grid and their probes run on every thread: the same bytes from one.
  BakeSettings one = b;
  one.output = (dir_ / "roof-1").string();
  one.threads = 1;
  bake(one);
  test::expect_same_bake_files(b.output, one.output);
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
