// The weld against its rule stated plainly: corners in order, each scanning the 27 cells of side tol
// around it for the first made point within tol.
#include "walkrad/output/corner_weld.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <map>
#include <random>

namespace walkrad {
namespace {

WeldedCorners weld_by_scan(const std::vector<Vec3>& corners, double tol) {
  auto cell = [tol](const Vec3& p) {
    return CellKey{int64_t(std::floor(p.x / tol)), int64_t(std::floor(p.y / tol)), int64_t(std::floor(p.z / tol))};
  };
  std::map<CellKey, std::vector<uint32_t>> cells;
  WeldedCorners out;
  for (const Vec3& p : corners) {
    const CellKey c = cell(p);
    uint32_t found = UINT32_MAX;
    for (int64_t dz = -1; dz <= 1 && found == UINT32_MAX; ++dz)
      for (int64_t dy = -1; dy <= 1 && found == UINT32_MAX; ++dy)
        for (int64_t dx = -1; dx <= 1 && found == UINT32_MAX; ++dx) {
          const auto it = cells.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells.end()) continue;
          for (uint32_t id : it->second)
            if (length(out.points[id] - p) <= tol) {
              found = id;
              break;
            }
        }
    if (found == UINT32_MAX) {
      found = uint32_t(out.points.size());
      out.points.push_back(p);
      cells[c].push_back(found);
    }
    out.point_of.push_back(found);
  }
  return out;
}

void expect_same(const WeldedCorners& a, const WeldedCorners& b) {
  ASSERT_EQ(a.point_of, b.point_of);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].x, b.points[i].x);
    EXPECT_EQ(a.points[i].y, b.points[i].y);
    EXPECT_EQ(a.points[i].z, b.points[i].z);
  }
}

// Corners crowded within a few tol of each other (chains of near points, whose choice depends on the
// order they come in), with exact repeats, ±0 and points exactly tol apart.
std::vector<Vec3> crowded_corners(uint32_t seed, double tol) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> centre(-20 * tol, 20 * tol), jitter(-1.5 * tol, 1.5 * tol);
  std::uniform_int_distribution<int> pick(0, 9);
  std::vector<Vec3> out;
  for (int i = 0; i < 4000; ++i) {
    const int kind = pick(rng);
    if (kind < 3 && !out.empty()) {
      out.push_back(out[std::uniform_int_distribution<size_t>(0, out.size() - 1)(rng)]);  // a repeat
    } else if (kind < 6 && !out.empty()) {
      const Vec3 p = out[std::uniform_int_distribution<size_t>(0, out.size() - 1)(rng)];
      out.push_back(p + Vec3(jitter(rng), jitter(rng), jitter(rng)));
    } else if (kind == 6 && !out.empty()) {
      out.push_back(out.back() + Vec3(tol, 0, 0));
    } else if (kind == 7) {
      out.push_back(Vec3(pick(rng) < 5 ? 0.0 : -0.0, centre(rng), 0.0));
    } else {
      out.push_back(Vec3(centre(rng), centre(rng), centre(rng)));
    }
  }
  return out;
}

TEST(CornerWeld, EqualsTheCornerByCornerScan) {
  for (const double tol : {1e-6, 0.37, 3.0}) {
    for (uint32_t seed = 1; seed <= 6; ++seed) {
      const std::vector<Vec3> corners = crowded_corners(seed, tol);
      const WeldedCorners scan = weld_by_scan(corners, tol);
      ASSERT_LT(scan.points.size(), corners.size() * 9 / 10);  // the case is crowded
      expect_same(weld_corners(corners, tol), scan);
    }
  }
}

TEST(CornerWeld, SameWhateverTheThreads) {
  const std::vector<Vec3> corners = crowded_corners(7, 0.01);
  const WeldedCorners many = weld_corners(corners, 0.01);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  expect_same(weld_corners(corners, 0.01), many);
}

TEST(CornerWeld, EmptyAndApart) {
  EXPECT_TRUE(weld_corners({}, 1e-3).points.empty());
  const WeldedCorners w = weld_corners({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0.0005)}, 1e-3);
  EXPECT_EQ(w.points.size(), 2u);
  EXPECT_EQ(w.point_of, (std::vector<uint32_t>{0, 1, 0, 1}));
}

TEST(CellIndex, CellsHoldTheirPointsInOrder) {
  const std::vector<Vec3> points = {Vec3(0.5, 0.5, 0.5), Vec3(2.5, 0.5, 0.5), Vec3(0.1, 0.9, 0.2), Vec3(0.5, 0.5, 1.5)};
  const CellIndex index(points, 1.0);
  auto ids = [](std::pair<const uint32_t*, const uint32_t*> r) { return std::vector<uint32_t>(r.first, r.second); };
  EXPECT_EQ(ids(index.in({0, 0, 0})), (std::vector<uint32_t>{0, 2}));
  EXPECT_EQ(ids(index.in({0, 0, 0}, 1)), (std::vector<uint32_t>{0, 2, 3}));
  EXPECT_EQ(ids(index.in({2, 0, 0})), (std::vector<uint32_t>{1}));
  EXPECT_TRUE(ids(index.in({1, 0, 0})).empty());
}

}  // namespace
}  // namespace walkrad
