// Textured reflectance per element (texture_sampling.h): elements take the texture's mean over
// their own area, the material keeps its average, and the effect plan samples only when there are
// textured surfaces with texture coordinates.
#include "walkrad/scene/texture_sampling.h"

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/plan/effect_plan.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {
namespace {

// A 2 × 1 m floor, u = x / 2: a 64 × 1 texture, white (1.0) on its left half and 0.25 on its right,
// mean 0.625; base colour factor 0.8, so the material's average reflectance is 0.5.
Scene textured_floor() {
  Scene s;
  s.source = "textured floor";
  Texture t;
  t.width = 64;
  t.height = 1;
  for (uint32_t i = 0; i < 64; ++i)
    for (int c = 0; c < 3; ++c) t.rgb.push_back(i < 32 ? 1.0f : 0.25f);
  t.mean = Vec3(0.625, 0.625, 0.625);
  s.textures.push_back(t);
  Material m{"tiles", Vec3(0.5, 0.5, 0.5), {}};
  m.reflectance_texture = 0;
  s.materials.push_back(m);
  s.materials.push_back({"lamp", {}, {10, 10, 10}});
  Polygon floor = test::quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0});
  floor.uv.valid = true;
  floor.uv.a_u = {0.5, 0, 0};
  floor.uv.b_v = 0.5;
  s.polygons.push_back(floor);
  s.polygons.push_back(test::quad({0, 0, 2}, {0, 1, 2}, {2, 1, 2}, {2, 0, 2}, 1));  // a lamp above, facing down
  return s;
}

TEST(TextureSampling, ElementsTakeTheirOwnPartOfTheTexture) {
  const Scene s = textured_floor();
  EXPECT_TRUE(has_textures(s));
  const ClusterTree tree = build_cluster_tree(s);
  Hierarchy h(s, tree, /*sample_textures=*/true);
  const uint32_t root = h.polygon_root(0);
  EXPECT_NEAR(h[root].rho.x, 0.5, 1e-12);  // the whole floor: the material's average
  ASSERT_TRUE(h.subdivide(root));
  for (uint32_t k = 0; k < 4; ++k) {
    const HNode& c = h[h.child(h[root], k)];
    // 8 × 8 samples inside either half read pure texels: 0.5 × 1.0 / 0.625 and 0.5 × 0.25 / 0.625.
    EXPECT_NEAR(c.rho.x, c.center.x < 1 ? 0.8 : 0.2, 1e-6) << "child at x = " << c.center.x;
  }
  // Without sampling, every element keeps the material's average.
  Hierarchy flat(s, tree);
  ASSERT_TRUE(flat.subdivide(flat.polygon_root(0)));
  for (uint32_t k = 0; k < 4; ++k) EXPECT_EQ(flat[flat.child(flat[flat.polygon_root(0)], k)].rho.x, 0.5);
}

TEST(TextureSampling, EffectPlanSamplesOnlyTexturedSurfaces) {
  Scene s = textured_floor();
  const RayScene rays(s);
  EXPECT_TRUE(plan_effects(s, rays, {}, false, Method::hierarchical, {}).textures.on);
  EXPECT_FALSE(plan_effects(s, rays, {}, false, Method::hierarchical, {{"textures", "off"}}).textures.on);
  s.polygons[0].uv.valid = false;  // a texture but no coordinates: the average
  const RayScene rays2(s);
  EXPECT_FALSE(plan_effects(s, rays2, {}, false, Method::hierarchical, {}).textures.on);
}

}  // namespace
}  // namespace walkrad
