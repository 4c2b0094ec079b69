// Volume clusters and their extinction grid: κ = A/4V read back from the written .vdb,
// OpenVDB's own vdb_print opens the file, transmittance through a homogeneous box is exp(−κ s).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/visibility/extinction_grid.h"
#include "walkrad/core/sampling.h"
#include "walkrad/visibility/volume_clusters.h"
#include "walkrad/testing/temp_dir_test.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad {
namespace {

// n closed cubes of side a in [0,1]³, eight of them in its corners so that the cluster's bounds are
// exactly the unit cube: A = 6 n a², V = 1. The others at random, in x ≤ x_max.
Scene cube_cloud(int n, double a, uint64_t seed, double x_max = 1.0) {
  Scene scene;
  scene.materials.push_back({"grey", Vec3(0.5, 0.5, 0.5), Vec3{}});
  Rng rng(seed);
  for (int i = 0; i < n; ++i) {
    Vec3 c;
    if (i < 8) {
      c = Vec3(i & 1 ? 1 - a / 2 : a / 2, i & 2 ? 1 - a / 2 : a / 2, i & 4 ? 1 - a / 2 : a / 2);
    } else {
      c = Vec3(a + (x_max - 2 * a) * rng.uniform(), a + (1 - 2 * a) * rng.uniform(), a + (1 - 2 * a) * rng.uniform());
    }
    test::add_cube(scene, c, a);
  }
  return scene;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

using ExtinctionGridTest = test::TempDirTest;

TEST_F(ExtinctionGridTest, KappaOfAClusterOfKnownAreaAndVolumeReadsBackFromTheVdb) {
  const int n = 200;
  const double a = 0.02;
  const Scene scene = cube_cloud(n, a, 7);
  const ClusterTree tree = build_cluster_tree(scene);
  VolumeSettings vs;
  vs.min_polygons = 6 * n;  // only the root holds enough: it is the one volume
  const VolumeClusters volumes = find_volume_clusters(scene, tree, vs);
  ASSERT_EQ(volumes.boxes.size(), 1u);
  EXPECT_EQ(volumes.volume_polygons, uint64_t(6 * n));
  EXPECT_TRUE(volumes.node_in_volume[0]);
  const double kappa = 6.0 * n * a * a / 4.0;  // A / 4V, V = 1 m³
  EXPECT_NEAR(volumes.boxes[0].kappa, kappa, 1e-12 * kappa);

  const double voxel = ExtinctionGrid::choose_voxel_size(volumes.boxes);
  EXPECT_DOUBLE_EQ(voxel, 0.5);
  const std::string path = (dir_ / "extinction.vdb").string();
  ExtinctionGrid::build(volumes.boxes, voxel).write(path, {{"test", "known A and V"}});
  const ExtinctionGrid back = ExtinctionGrid::read(path);
  EXPECT_EQ(back.metadata("test"), "known A and V");
  EXPECT_EQ(back.metadata("kappa_units"), "1/m");
  const ExtinctionGrid::Stats s = back.stats();
  EXPECT_EQ(s.active_voxels, 8u);  // 2 × 2 × 2 voxels of 0.5 m
  EXPECT_NEAR(s.kappa_min, kappa, 1e-6 * kappa);
  EXPECT_NEAR(s.kappa_max, kappa, 1e-6 * kappa);
  for (const Vec3& p : {Vec3(0.5, 0.5, 0.5), Vec3(0.01, 0.99, 0.3)}) EXPECT_NEAR(back.value_at(p), kappa, 1e-6 * kappa);
  EXPECT_EQ(back.value_at(Vec3(1.5, 0.5, 0.5)), 0.0);
  EXPECT_NEAR(s.bounds.lo.x, 0.0, 1e-12);
  EXPECT_NEAR(s.bounds.hi.z, 1.0, 1e-12);
}

TEST_F(ExtinctionGridTest, OpenVdbsOwnVdbPrintOpensTheFile) {
  const std::string path = (dir_ / "extinction.vdb").string();
  ExtinctionGrid::build({{Bounds{Vec3(0, 0, 0), Vec3(1, 2, 1)}, 0.75}}, 0.125).write(path, {});
  FILE* pipe = popen(("vdb_print -l '" + path + "' 2>&1").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[512];
  while (size_t got = fread(buf, 1, sizeof buf, pipe)) out.append(buf, got);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("extinction"), std::string::npos) << out;
  EXPECT_NE(out.find("walkrad:kappa_units"), std::string::npos) << out;
  EXPECT_NE(out.find("1/m"), std::string::npos) << out;
}

TEST_F(ExtinctionGridTest, WritingTwiceGivesTheSameBytes) {
  const ExtinctionGrid grid = ExtinctionGrid::build({{Bounds{Vec3(0.1, 0, 0), Vec3(1, 0.7, 0.3)}, 2.5}}, 0.05);
  const std::string a = (dir_ / "a.vdb").string(), b = (dir_ / "b.vdb").string();
  grid.write(a, {{"k", "v"}});
  grid.write(b, {{"k", "v"}});
  EXPECT_EQ(slurp(a), slurp(b));
  EXPECT_GT(slurp(a).size(), 100u);
}

TEST_F(ExtinctionGridTest, UnreadableFileIsAnInputErrorNamingIt) {
  const std::string path = (dir_ / "bad.vdb").string();
  std::ofstream(path) << "not a vdb";
  try {
    ExtinctionGrid::read(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
  }
}

// Length of the segment's part inside the box (slab clipping).
double chord(const Bounds& box, const Vec3& a, const Vec3& b) {
  double t0 = 0, t1 = 1;
  const Vec3 d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return 0;
      continue;
    }
    double ta = (box.lo[k] - a[k]) / d[k], tb = (box.hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 ? (t1 - t0) * length(d) : 0.0;
}

TEST(Transmittance, ThroughAHomogeneousBoxIsExpMinusKappaS) {
  const Bounds box{Vec3(-0.5, 2, 10), Vec3(1.5, 3, 11)};
  const double kappa = 1.7;
  const ExtinctionGrid grid = ExtinctionGrid::build({{box, kappa}}, ExtinctionGrid::choose_voxel_size({{box, kappa}}));
  Rng rng(11);
  double worst = 0;
  int crossing = 0;
  for (int k = 0; k < 2000; ++k) {
    // End points in a region 3 times the box: through it, into it, out of it, or past it.
    auto point = [&] {
      const Vec3 c = box.center(), d = box.diagonal();
      return c + Vec3((rng.uniform() - 0.5) * 3 * d.x, (rng.uniform() - 0.5) * 3 * d.y, (rng.uniform() - 0.5) * 3 * d.z);
    };
    const Vec3 a = point(), b = point();
    const double s = chord(box, a, b);
    crossing += s > 0;
    worst = std::max(worst, std::fabs(grid.transmittance(a, b) - std::exp(-kappa * s)));
  }
  EXPECT_GT(crossing, 500);
  EXPECT_LT(worst, 1e-4);
  // Along an axis, through the whole box, and the reverse direction.
  EXPECT_NEAR(grid.transmittance(Vec3(-5, 2.5, 10.5), Vec3(5, 2.5, 10.5)), std::exp(-kappa * 2.0), 1e-7);  // κ stored as a float
  EXPECT_NEAR(grid.transmittance(Vec3(5, 2.5, 10.5), Vec3(-5, 2.5, 10.5)), std::exp(-kappa * 2.0), 1e-7);
  EXPECT_EQ(grid.transmittance(Vec3(-5, 0, 0), Vec3(5, 0, 0)), 1.0);
}

TEST(Transmittance, UnalignedBoxesKeepTheirIntegralOfKappa) {
  // A box not aligned with the voxels: the voxels it partly covers hold κ × coverage, so κ V is kept,
  // and a segment through its middle (away from the partly covered voxels) still sees κ exactly.
  const Bounds box{Vec3(0.03, 0.11, -0.27), Vec3(0.91, 0.53, 0.4)};
  const double kappa = 3.0, voxel = 0.05;
  const ExtinctionGrid grid = ExtinctionGrid::build({{box, kappa}}, voxel);
  const Vec3 a(0.2, 0.3, -1), b(0.2, 0.3, 1);
  EXPECT_NEAR(grid.optical_depth(a, b), kappa * chord(box, a, b), 1e-5);
  double integral = 0;
  const ExtinctionGrid::Stats s = grid.stats();
  for (double x = s.bounds.lo.x + voxel / 2; x < s.bounds.hi.x; x += voxel)
    for (double y = s.bounds.lo.y + voxel / 2; y < s.bounds.hi.y; y += voxel)
      for (double z = s.bounds.lo.z + voxel / 2; z < s.bounds.hi.z; z += voxel) integral += grid.value_at(Vec3(x, y, z));
  const Vec3 d = box.diagonal();
  EXPECT_NEAR(integral * voxel * voxel * voxel, kappa * d.x * d.y * d.z, 1e-5);
}

TEST(VolumeClusters, AnOpenSheetBlocksWithBothFacesAClosedCubeWithOne) {
  Scene scene;
  scene.materials.push_back({"grey", Vec3(0.5, 0.5, 0.5), Vec3{}});
  test::add_cube(scene, Vec3(0, 0, 0), 1.0);
  scene.polygons.push_back(test::quad(Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(6, 1, 0), Vec3(5, 1, 0)));
  const std::vector<double> blocking = blocking_areas(scene);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(blocking[size_t(k)], 1.0, 1e-12);
  EXPECT_NEAR(blocking[6], 2.0, 1e-12);
}

TEST(VolumeClusters, ObjectsPackedIntoASideOfTheBoxAreNotItsMedium) {
  // κ = A/4V assumes objects spread at random. The same 400 cubes in the box's first quarter (books
  // along a wall, the office floor's failure) are not the box's medium; spread over it, they are.
  VolumeSettings vs;
  vs.min_polygons = 6 * 400;  // only the root could be a volume
  const Scene packed = cube_cloud(400, 0.02, 11, 0.25);
  EXPECT_TRUE(find_volume_clusters(packed, build_cluster_tree(packed), vs).empty());
  const Scene spread = cube_cloud(400, 0.02, 11);
  EXPECT_EQ(find_volume_clusters(spread, build_cluster_tree(spread), vs).boxes.size(), 1u);
  vs.max_dispersion = 1e9;  // the rule off: the packed cubes pass
  EXPECT_EQ(find_volume_clusters(packed, build_cluster_tree(packed), vs).boxes.size(), 1u);
}

TEST(VolumeClusters, ATessellatedBoxIsOneBigObjectNotAVolume) {
  // A 2 m box whose faces are cut into 32 × 32 quads each (6,144 polygons): small polygons, but one
  // connected object as large as the cluster: it blocks like a surface.
  Scene scene;
  scene.materials.push_back({"grey", Vec3(0.5, 0.5, 0.5), Vec3{}});
  const int n = 32;
  const double s = 2.0 / n;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int a, int b) {
            Vec3 p;
            p[axis] = side * 2.0;
            p[(axis + 1) % 3] = a * s;
            p[(axis + 2) % 3] = b * s;
            return p;
          };
          scene.polygons.push_back(test::quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)));
        }
  const VolumeClusters v = find_volume_clusters(scene, build_cluster_tree(scene), VolumeSettings{});
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.volume_polygons, 0u);
  // The same polygon count as separate small cubes: a volume.
  const Scene cloud = cube_cloud(1024, 0.02, 3);
  const VolumeClusters c = find_volume_clusters(cloud, build_cluster_tree(cloud), VolumeSettings{});
  EXPECT_FALSE(c.empty());
  EXPECT_EQ(c.volume_polygons, cloud.polygons.size());
}

}  // namespace
}  // namespace walkrad
