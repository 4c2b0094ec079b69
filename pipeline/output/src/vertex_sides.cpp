#include "walkrad/output/vertex_sides.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace walkrad {

std::vector<uint8_t> vertex_sides(const MeshFaces& faces, const std::vector<Vec3>& points, const uint32_t* boundary,
                                  const uint32_t* boundary_begin, const std::vector<uint32_t>& group, double tol) {
  const uint32_t entries = boundary_begin[faces.size()];
  std::vector<uint8_t> side(entries, 0);
  // Each point's boundary entries.
  std::vector<uint32_t> begin(points.size() + 1, 0), at(entries);
  for (uint32_t j = 0; j < entries; ++j) ++begin[boundary[j] + 1];
  for (size_t p = 0; p < points.size(); ++p) begin[p + 1] += begin[p];
  {
    std::vector<uint32_t> fill(begin.begin(), begin.end() - 1);
    for (uint32_t j = 0; j < entries; ++j) at[fill[boundary[j]]++] = j;
  }
  auto face_of = [&](uint32_t j) {
    return uint32_t(std::upper_bound(boundary_begin, boundary_begin + faces.size() + 1, j) - boundary_begin - 1);
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<uint32_t> face;
    std::vector<double> walls;
    for (size_t p = r.begin(); p != r.end(); ++p) {
      const uint32_t first = begin[p], last = begin[p + 1];
      if (last - first < 3) continue;  // two faces of one group and a wall at least
      face.clear();
      for (uint32_t k = first; k < last; ++k) face.push_back(face_of(at[k]));
      // Anything standing here at all: a face not parallel to the first.
      const Vec3& n0 = faces[face[0]].normal;
      bool crease = false;
      for (uint32_t f : face) crease = crease || std::fabs(dot(faces[f].normal, n0)) < 1 - 1e-9;
      if (!crease) continue;
      const Vec3& x = points[p];
      for (size_t a = 0; a < face.size(); ++a) {
        const uint32_t g = group[faces[face[a]].polygon];
        bool first_of_group = true, more = false;
        for (size_t b = 0; b < face.size(); ++b) {
          if (group[faces[face[b]].polygon] != g) continue;
          if (b < a) first_of_group = false;
          if (b != a) more = true;
        }
        if (!first_of_group || !more) continue;
        const Vec3& n = faces[face[a]].normal;
        const Vec3 helper = std::fabs(n.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        const Vec3 u = normalize(cross(n, helper)), v = cross(n, u);
        auto angle = [&](const Vec3& d) { return std::atan2(dot(d, v), dot(d, u)); };
        // The walls: edges from x, in the plane, of faces standing in front of it.
        walls.clear();
        for (size_t b = 0; b < face.size(); ++b) {
          const MeshFace& w = faces[face[b]];
          if (std::fabs(dot(w.normal, n)) >= 1 - 1e-9) continue;
          if (dot(polygon_centroid(w.shape) - x, n) <= tol) continue;  // behind, or lying in the plane
          const uint32_t j = at[first + b], fb = boundary_begin[face[b]], count = boundary_begin[face[b] + 1] - fb;
          for (const uint32_t q : {boundary[fb + (j - fb + count - 1) % count], boundary[fb + (j - fb + 1) % count]}) {
            const Vec3 d = points[q] - x;
            const double len = length(d);
            if (len > tol && std::fabs(dot(d, n)) <= 1e-6 * len) walls.push_back(angle(d));
          }
        }
        std::sort(walls.begin(), walls.end());
        walls.erase(std::unique(walls.begin(), walls.end(), [](double s, double t) { return t - s < 1e-9; }), walls.end());
        if (walls.size() >= 2 && walls.back() - walls.front() > 2 * kPi - 1e-9) walls.pop_back();  // ±π: one direction
        if (walls.size() < 2) continue;
        // Each face of the group: the sector its centre lies in, counted from the first wall.
        for (size_t b = 0; b < face.size(); ++b) {
          if (group[faces[face[b]].polygon] != g) continue;
          const double t = angle(polygon_centroid(faces[face[b]].shape) - x);
          const size_t k = size_t(std::upper_bound(walls.begin(), walls.end(), t) - walls.begin()) % walls.size();
          side[at[first + b]] = uint8_t(std::min<size_t>(k, 255));
        }
      }
    }
  });
  return side;
}

}  // namespace walkrad
