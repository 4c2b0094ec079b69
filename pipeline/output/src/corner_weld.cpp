#include "walkrad/output/corner_weld.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstring>

namespace walkrad {

CellIndex::CellIndex(const std::vector<Vec3>& points, double cell) : cell_(cell) {
  struct Entry {
    CellKey key;
    uint32_t id;
  };
  std::vector<Entry> entries(points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) entries[i] = {key(points[i]), uint32_t(i)};
  });
  // (cell, id) is a total order: the same array whatever the threads.
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.key == b.key ? a.id < b.id : a.key < b.key;
  });
  keys_.resize(entries.size());
  ids_.resize(entries.size());
  for (size_t i = 0; i < entries.size(); ++i) {
    keys_[i] = entries[i].key;
    ids_[i] = entries[i].id;
  }
}

std::pair<const uint32_t*, const uint32_t*> CellIndex::in(const CellKey& first, int64_t last_z) const {
  const auto lo = std::lower_bound(keys_.begin(), keys_.end(), first);
  const auto hi = std::upper_bound(lo, keys_.end(), CellKey{first.x, first.y, last_z});
  return {ids_.data() + (lo - keys_.begin()), ids_.data() + (hi - keys_.begin())};
}

namespace {

uint64_t bits_hash(const Vec3& p) {
  uint64_t b[3];
  std::memcpy(&b[0], &p.x, 8);
  std::memcpy(&b[1], &p.y, 8);
  std::memcpy(&b[2], &p.z, 8);
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (uint64_t v : b) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xff51afd7ed558ccdull;
  }
  return h ^ (h >> 33);
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

}  // namespace

WeldedCorners weld_corners(const std::vector<Vec3>& corners, double tol) {
  WeldedCorners out;
  const size_t count = corners.size();
  out.point_of.assign(count, UINT32_MAX);
  if (count == 0) return out;

  // 1. Bit-identical corners as one position u (numbered in the order of their first corner): sorted
  // by a hash of their bits and their number, each run split by the bits themselves.
  std::vector<uint32_t> position_of(count);  // by corner
  std::vector<uint32_t> first;               // by position: its first corner
  {
    std::vector<std::pair<uint64_t, uint32_t>> order(count);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t n = r.begin(); n != r.end(); ++n) order[n] = {bits_hash(corners[n]), uint32_t(n)};
    });
    tbb::parallel_sort(order.begin(), order.end());
    std::vector<uint32_t> head(count, UINT32_MAX);  // by corner: the first corner with its bits
    for (size_t s = 0; s < count;) {
      size_t e = s;
      while (e < count && order[e].first == order[s].first) ++e;
      for (size_t i = s; i < e; ++i) {  // a run is one position but for a hash collision
        const uint32_t n = order[i].second;
        for (size_t j = s; j < i && head[n] == UINT32_MAX; ++j)
          if (same_bits(corners[order[j].second], corners[n])) head[n] = head[order[j].second];
        if (head[n] == UINT32_MAX) head[n] = n;  // ascending n in a run: the first of its bits
      }
      s = e;
    }
    for (size_t n = 0; n < count; ++n) {  // positions numbered by first corner
      if (head[n] == n) {
        position_of[n] = uint32_t(first.size());
        first.push_back(uint32_t(n));
      } else {
        position_of[n] = position_of[head[n]];
      }
    }
  }
  const size_t positions = first.size();
  std::vector<Vec3> at(positions);
  for (size_t u = 0; u < positions; ++u) at[u] = corners[first[u]];

  // 2. Each position's neighbours within tol that the scan of its 27 cells of side tol would meet
  // (a rounding of p/tol can put a point within tol two cells away: the scan misses it, so must this),
  // with the rank of the neighbour's cell in the scan. Found in a coarser index (cells of 4 tol: a
  // box of ±2 tol spans at most two of them an axis) in parallel; almost every list is empty.
  struct Near {
    uint32_t u, v;  // v near u
    uint8_t rank;   // v's cell in u's scan: (dz + 1) · 9 + (dy + 1) · 3 + (dx + 1)
    bool operator<(const Near& o) const { return u != o.u ? u < o.u : v < o.v; }
  };
  std::vector<Near> near;
  {
    const CellIndex index(at, 4 * tol);
    tbb::enumerable_thread_specific<std::vector<Near>> found;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, positions, 1024), [&](const tbb::blocked_range<size_t>& r) {
      std::vector<Near>& mine = found.local();
      for (size_t u = r.begin(); u != r.end(); ++u) {
        const Vec3& p = at[u];
        const Vec3 reach(2 * tol, 2 * tol, 2 * tol);
        const CellKey lo = index.key(p - reach), hi = index.key(p + reach), c = cell_of(p, tol);
        for (int64_t x = lo.x; x <= hi.x; ++x)
          for (int64_t y = lo.y; y <= hi.y; ++y) {
            const auto [b, e] = index.in({x, y, lo.z}, hi.z);
            for (const uint32_t* v = b; v != e; ++v) {
              if (*v == u || length(at[*v] - p) > tol) continue;
              const CellKey d = cell_of(at[*v], tol);
              const int64_t dx = d.x - c.x, dy = d.y - c.y, dz = d.z - c.z;
              if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) > 1) continue;
              mine.push_back({uint32_t(u), *v, uint8_t((dz + 1) * 9 + (dy + 1) * 3 + (dx + 1))});
            }
          }
      }
    });
    for (std::vector<Near>& list : found) near.insert(near.end(), list.begin(), list.end());
    std::sort(near.begin(), near.end());
  }
  std::vector<uint32_t> near_begin(positions + 1, 0);
  for (const Near& e : near) ++near_begin[e.u + 1];
  for (size_t u = 0; u < positions; ++u) near_begin[u + 1] += near_begin[u];

  // 3. The choice in corner order. A position that made its point keeps it for its later corners
  // (a point made later within tol of it would have found it). Otherwise the first made point within
  // tol in scan order: least (cell rank, point number) among the neighbours whose first corner came
  // before this one; with none, this corner makes one.
  std::vector<uint32_t> point(positions, UINT32_MAX);
  for (size_t n = 0; n < count; ++n) {
    const uint32_t u = position_of[n];
    if (point[u] != UINT32_MAX) {
      out.point_of[n] = point[u];
      continue;
    }
    uint32_t best = UINT32_MAX, best_rank = 27;
    for (uint32_t k = near_begin[u]; k < near_begin[u + 1]; ++k) {
      const Near& e = near[k];
      const uint32_t q = point[e.v];
      if (q == UINT32_MAX || first[e.v] >= n) continue;
      if (e.rank < best_rank || (e.rank == best_rank && q < best)) {
        best = q;
        best_rank = e.rank;
      }
    }
    if (best != UINT32_MAX) {
      out.point_of[n] = best;
      continue;
    }
    point[u] = uint32_t(out.points.size());
    out.points.push_back(corners[n]);
    out.point_of[n] = point[u];
  }
  return out;
}

}  // namespace walkrad
