// Proven occlusion (occlusion_proof.h): a wall of several coplanar quads proves two rooms apart, a
// doorway or a narrow gap in it proves nothing, and every proof holds against Embree rays between
// random points of the two ends (a proof that a ray could refute would settle light as dark).
#include <gtest/gtest.h>

#include "walkrad/core/sampling.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/testing/test_scenes.h"
#include "walkrad/visibility/occlusion_proof.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {
namespace {

using test::quad;

// The wall x = 0 between two rooms, y in [0, 3], z in [0, 4], as coplanar quads: back to back (one
// facing each room), with an opening [z0, z1] × [0, top] left out of both sides (none where z0 == z1).
void add_wall(Scene& s, double z0, double z1, double top) {
  auto side = [&](double za, double zb, double ya, double yb) {
    if (zb - za <= 0 || yb - ya <= 0) return;
    const Polygon p = quad({0, ya, za}, {0, ya, zb}, {0, yb, zb}, {0, yb, za});  // faces +x
    s.polygons.push_back(p);
    Polygon back = p;
    std::swap(back.v[1], back.v[3]);  // faces −x
    s.polygons.push_back(back);
  };
  side(0, z0, 0, 3);
  side(z1, 4, 0, 3);
  side(z0, z1, top, 3);
}

Polygon floor_patch(double x0, double x1, double z0, double z1) { return quad({x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}); }
Polygon ceiling_patch(double x0, double x1, double z0, double z1) {
  return quad({x0, 3, z0}, {x1, 3, z0}, {x1, 3, z1}, {x0, 3, z1});
}

// Rays between random points of a and b that arrive (from just off each surface).
int rays_through(const RayScene& rays, const Polygon& a, const Polygon& b, int n) {
  Rng rng(5);
  int through = 0;
  const Vec3 na = polygon_normal(a), nb = polygon_normal(b);
  for (int k = 0; k < n; ++k) {
    const Vec3 x = sample_polygon(a, rng.uniform(), rng.uniform()), y = sample_polygon(b, rng.uniform(), rng.uniform());
    through += !rays.occluded(x + na * rays.offset(), y + nb * rays.offset());
  }
  return through;
}

struct Level {
  Scene scene;
  ClusterTree tree;
  Level(double z0, double z1, double top) {
    scene.materials.push_back({"wall", {0.5, 0.5, 0.5}, {0, 0, 0}});
    add_wall(scene, z0, z1, top);
    tree = build_cluster_tree(scene);
  }
  std::vector<uint32_t> all() const {
    std::vector<uint32_t> k(scene.polygons.size());
    for (uint32_t i = 0; i < k.size(); ++i) k[i] = i;
    return k;
  }
};

TEST(OcclusionProof, ASolidWallOfSeveralQuadsProvesTheRoomsApart) {
  // The wall with a "doorway" of zero width: still five quads a side meeting at their edges.
  Level l(1.5, 1.5, 2.1);
  const OcclusionProof proof(l.scene, l.tree);
  const RayScene rays(l.scene);
  const Polygon a = floor_patch(-3, -1, 0.5, 3.5), b = ceiling_patch(1, 4, 0, 4);
  const std::vector<uint32_t> planes = l.all();
  EXPECT_TRUE(proof.blocked(OcclusionProof::element(a), OcclusionProof::element(b), planes.data(), planes.size()));
  EXPECT_TRUE(proof.blocked(OcclusionProof::element(b), OcclusionProof::element(a), planes.data(), planes.size()));
  EXPECT_EQ(rays_through(rays, a, b, 20000), 0);
  // An element touching the wall's foot is still behind it (the touching edge is measure zero).
  const Polygon touching = floor_patch(-2, 0, 1, 2);
  EXPECT_TRUE(proof.blocked(OcclusionProof::element(touching), OcclusionProof::element(b), planes.data(), planes.size()));
}

TEST(OcclusionProof, ADoorwayOrANarrowGapProvesNothing) {
  const Polygon a = floor_patch(-3, -1, 0.5, 3.5), b = floor_patch(1, 4, 0, 4);
  for (const double width : {1.0, 0.05}) {
    Level l(1.5, 1.5 + width, 2.1);
    const OcclusionProof proof(l.scene, l.tree);
    const RayScene rays(l.scene);
    const std::vector<uint32_t> planes = l.all();
    EXPECT_FALSE(proof.blocked(OcclusionProof::element(a), OcclusionProof::element(b), planes.data(), planes.size()))
        << "opening " << width << " m";
    EXPECT_GT(rays_through(rays, a, b, 200000), 0) << "opening " << width << " m";
  }
  // Elements whose segments all cross the wall beside the doorway are proven apart.
  Level l(1.5, 2.5, 2.1);
  const OcclusionProof proof(l.scene, l.tree);
  const RayScene rays(l.scene);
  const std::vector<uint32_t> planes = l.all();
  const Polygon left = floor_patch(-2, -1, 0, 0.5), right = ceiling_patch(1, 2, 0, 0.5);
  EXPECT_TRUE(proof.blocked(OcclusionProof::element(left), OcclusionProof::element(right), planes.data(), planes.size()));
  EXPECT_EQ(rays_through(rays, left, right, 20000), 0);
}

TEST(OcclusionProof, AClusterWithASurfaceFacingTheOtherEndIsNotBlocked) {
  Level l(1.5, 1.5, 2.1);
  const OcclusionProof proof(l.scene, l.tree);
  const std::vector<uint32_t> planes = l.all();
  const Polygon b = floor_patch(1, 4, 0, 4);
  // The whole wall's cluster (the root): its +x faces face b.
  Vec3 corners[8];
  Bounds box = l.tree.nodes[0].bounds;
  box.extend(Vec3(-2, 0, 0));  // reaching into the −x room
  EXPECT_FALSE(proof.blocked(OcclusionProof::box(box, 0, corners), OcclusionProof::element(b), planes.data(), planes.size()));
  // Not separated: an end on both sides of every plane.
  const Polygon across = floor_patch(-1, 1, 0, 4);
  EXPECT_FALSE(proof.blocked(OcclusionProof::element(across), OcclusionProof::element(b), planes.data(), planes.size()));
}

TEST(OcclusionProof, ProofsHoldAgainstRaysAtRandom) {
  // Random patch pairs across a wall with a doorway: every proven pair lets no ray through.
  Level l(1.5, 2.5, 2.1);
  const OcclusionProof proof(l.scene, l.tree);
  const RayScene rays(l.scene);
  const std::vector<uint32_t> planes = l.all();
  Rng rng(9);
  int proven = 0, open = 0;
  for (int k = 0; k < 200; ++k) {
    const double ax = -3 * rng.uniform() - 0.01, az = 3.5 * rng.uniform(), bx = 3 * rng.uniform() + 0.01, bz = 3.5 * rng.uniform();
    const Polygon a = floor_patch(ax - 0.3, ax, az, az + 0.5), b = ceiling_patch(bx, bx + 0.3, bz, bz + 0.5);
    if (proof.blocked(OcclusionProof::element(a), OcclusionProof::element(b), planes.data(), planes.size())) {
      ++proven;
      ASSERT_EQ(rays_through(rays, a, b, 2000), 0) << "pair " << k;
    } else {
      open += rays_through(rays, a, b, 2000) > 0;
    }
  }
  EXPECT_GT(proven, 50);
  EXPECT_GT(open, 20);
}

}  // namespace
}  // namespace walkrad
