#include "walkrad/output/discontinuity_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/scene/convex_loop.h"
#include "walkrad/visibility/shaft.h"

namespace walkrad {

namespace {

constexpr double kShortest = 2e-3;  // of the receiver's size
constexpr double kFaintShare = 1.0 / 64;  // of the light a seen part could get: its faintest emitters' share

struct Ranked {
  double contrast;
  uint32_t polygon, order, emitter;
  uint64_t crossings;  // faces of the polygon it is expected to cross
  BoundarySegment segment;
};

// Whether segment [a, b] (in the loop's plane) has a part longer than a thousandth of it inside the
// convex loop (normal: the loop's).
bool passes_through(const Loop& l, const Vec3& normal, const Vec3& a, const Vec3& b) {
  double t0, t1;
  return clip_segment(l.data(), l.size(), normal, a, b, t0, t1) && t1 - t0 > 1e-3;
}

// A convex loop's thickness: twice its area over its longest edge (a sliver's width).
double thickness(const Loop& l) {
  double longest = 0;
  for (size_t k = 0; k < l.size(); ++k) longest = std::max(longest, length(l[(k + 1) % l.size()] - l[k]));
  return longest > 0 ? 2 * loop_area(l) / longest : 0.0;
}

// Whether g.flips is seen from one side of g's middle and hidden from the other (points a thousandth of
// their distance to it off the middle, in the receiver's plane; the emitter point moved a thousandth
// of the way to the emitter's centre, so that the ray does not graze the emitter's own edge).
bool changes_across(const RayScene& rays, const BoundarySegment& g, const Vec3& normal, const DirectGather::Emitter& e,
                    const Vec3& centre) {
  const Vec3 middle = (g.a + g.b) * 0.5;
  const Vec3 side = normalize(cross(g.b - g.a, normal));
  const double step = 1e-3 * length(g.flips - middle);
  const Vec3 target = g.flips + (centre - g.flips) * 1e-3 + e.normal * rays.offset();
  RayScene::Segment s[2] = {{middle + side * step + normal * rays.offset(), target},
                            {middle - side * step + normal * rays.offset(), target}};
  uint8_t blocked[2] = {0, 0};
  rays.occluded(s, 2, blocked);
  return blocked[0] != blocked[1];
}

}  // namespace

BoundarySelection select_boundaries(const Hierarchy& h, const DirectGather& direct, const MeshFaces& faces,
                                    const std::vector<uint8_t>& seen, const std::vector<EmitterRanges>& emitters,
                                    uint64_t budget, const RayScene* rays) {
  const Scene& scene = h.scene();
  const size_t polygons = scene.polygons.size();
  BoundarySelection out;
  out.by_polygon.resize(polygons);
  out.emitter.resize(polygons);
  // Per polygon: its seen faces' emitters, the box around them, their mean area and reflectance. Only
  // the boundaries crossing that box are looked for: a corridor's floor along a 150-room level, seen
  // near two rooms, has the occluders of the whole level between it and the lamps its doorways let in.
  std::vector<EmitterRanges> from(polygons);
  std::vector<Bounds> region(polygons);
  std::vector<double> area(polygons, 0.0), count(polygons, 0.0);
  std::vector<Vec3> rho(polygons);  // the brightest seen face's
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!seen[f]) continue;
    const uint32_t p = faces[f].polygon;
    merge_ranges(from[p], emitters[f]);
    region[p].extend(polygon_bounds(faces[f].shape));
    area[p] += faces[f].area;
    count[p] += 1;
    if (luminance(faces[f].rho) > luminance(rho[p])) rho[p] = faces[f].rho;
  }
  const double tol = 1e-6 * std::max(length(scene.bounds().diagonal()), 1e-30);
  std::vector<std::vector<Ranked>> found(polygons);
  std::vector<uint64_t> hidden(polygons, 0);
  tbb::parallel_for(size_t(0), polygons, [&](size_t p) {
    if (from[p].empty() || luminance(rho[p]) <= 0) return;
    const Polygon& receiver = scene.polygons[p];
    const Vec3 normal = polygon_normal(receiver);
    const Bounds& rb = region[p];
    const double side = std::sqrt(area[p] / count[p]);
    // Shorter boundaries are left out: the corner of a box a hair above the floor casts its bottom
    // edges' shadows a tenth of a millimetre long, slivers for nothing.
    const double shortest = kShortest * std::sqrt(polygon_area(receiver));
    // The emitters that light the seen part, less the faintest: those whose light there together stays
    // below kFaintShare of all the light they could give (unoccluded, at the box's corners and centre)
    // draw boundaries of no contrast, from a shaft across the level.
    std::array<Vec3, 9> points{rb.center()};
    for (int c = 0; c < 8; ++c) points[size_t(c + 1)] = {c & 1 ? rb.hi.x : rb.lo.x, c & 2 ? rb.hi.y : rb.lo.y, c & 4 ? rb.hi.z : rb.lo.z};
    const auto bound = direct.bounds(from[p], points.data(), points.size(), normal, rho[p]);
    double total = 0;
    for (const auto& b : bound) total += b.first;
    std::vector<Polygon> occluders;
    for (const auto& [lo, hi] : without_faintest(bound, kFaintShare * total))
      for (uint32_t e = lo; e < hi; ++e) {
        const DirectGather::Emitter& emitter = direct.emitter(e);
        if (emitter.polygon == p) continue;
        occluders.clear();
        for (uint32_t o : shaft_candidates(h.tree(), Shaft(polygon_bounds(emitter.shape), rb), emitter.polygon, uint32_t(p)))
          occluders.push_back(scene.polygons[o]);
        if (occluders.empty()) continue;
        const Vec3 centre = polygon_centroid(emitter.shape);
        for (const BoundarySegment& g : shadow_boundaries(emitter.shape, receiver, occluders, tol, &rb)) {
          if (length(g.b - g.a) < shortest) continue;
          if (rays && !changes_across(*rays, g, normal, emitter, centre)) {
            ++hidden[p];
            continue;
          }
          const Vec3 middle = (g.a + g.b) * 0.5;
          const double contrast = luminance(rho[p]) * luminance(emitter.emission) * point_to_polygon(middle, normal, emitter.shape);
          if (contrast <= 0) continue;
          found[p].push_back({contrast, uint32_t(p), uint32_t(found[p].size()), e, 1 + uint64_t(length(g.b - g.a) / side), g});
        }
      }
  });
  std::vector<Ranked> all;
  for (auto& list : found) all.insert(all.end(), list.begin(), list.end());
  out.found = all.size();
  for (uint64_t n : hidden) out.hidden += n;
  // (contrast, polygon, order) is a total order: the same list whatever the threads.
  tbb::parallel_sort(all.begin(), all.end(), [](const Ranked& a, const Ranked& b) {
    if (a.contrast != b.contrast) return a.contrast > b.contrast;
    return a.polygon != b.polygon ? a.polygon < b.polygon : a.order < b.order;
  });
  uint64_t used = 0;
  for (const Ranked& r : all) {
    if (used + r.crossings > budget) continue;
    used += r.crossings;
    out.by_polygon[r.polygon].push_back(r.segment);
    out.emitter[r.polygon].push_back(r.emitter);
    ++out.segments;
  }
  return out;
}

CutFaces cut_faces(const MeshFaces& faces, const std::vector<std::vector<BoundarySegment>>& by_polygon,
                   double snap, double min_share) {
  std::vector<std::vector<Polygon>> pieces(faces.size());
  CutFaces out;
  out.applied.resize(faces.size());
  tbb::parallel_for(size_t(0), faces.size(), [&](size_t f) {
    const MeshFace& face = faces[f];
    if (face.polygon >= by_polygon.size() || by_polygon[face.polygon].empty()) return;
    std::vector<Loop> loops = {Loop(face.shape.v.begin(), face.shape.v.begin() + face.shape.count)}, next;
    Loop below, above;
    const double min_area = min_share * face.area;
    bool cut = false;
    const std::vector<BoundarySegment>& segments = by_polygon[face.polygon];
    for (uint32_t k = 0; k < segments.size(); ++k) {
      const BoundarySegment& g = segments[k];
      const Vec3 d = g.b - g.a;
      const Vec3 n = normalize(cross(d, face.normal));
      const double offset = dot(n, g.a);
      next.clear();
      for (const Loop& l : loops) {
        // Cut where the segment passes through the piece (the part of it inside is longer than a
        // thousandth of the segment), by its whole line: a segment ending inside a piece cuts it whole.
        if (passes_through(l, face.normal, g.a, g.b)) {
          split_loop(l, n, offset, below, above, snap);
          if (below.size() >= 3 && above.size() >= 3 && loop_area(below) > min_area && loop_area(above) > min_area &&
              thickness(below) > 4 * snap && thickness(above) > 4 * snap) {
            next.push_back(below);
            next.push_back(above);
            if (out.applied[f].empty() || out.applied[f].back() != k) out.applied[f].push_back(k);
            cut = true;
            continue;
          }
        }
        next.push_back(l);
      }
      loops.swap(next);
    }
    if (!cut) return;
    for (const Loop& l : loops) emit_loop(l, face.shape, pieces[f]);
  });
  // Each face's pieces where a prefix sum of their counts puts them: the arrays made to their sizes
  // and filled in parallel (pushed back one by one, a large level's array of faces is copied and faulted
  // in twice over).
  std::vector<size_t> begin(faces.size() + 1, 0);
  for (size_t f = 0; f < faces.size(); ++f) begin[f + 1] = begin[f] + std::max<size_t>(pieces[f].size(), 1);
  out.faces.resize(begin.back());
  out.from.resize(begin.back());
  tbb::parallel_for(size_t(0), faces.size(), [&](size_t f) {
    size_t at = begin[f];
    if (pieces[f].empty()) {
      out.faces[at] = faces[f];
      out.from[at] = uint32_t(f);
      return;
    }
    for (const Polygon& shape : pieces[f]) {
      MeshFace& piece = out.faces[at];
      piece = faces[f];
      piece.shape = shape;
      piece.area = polygon_area(shape);
      out.from[at++] = uint32_t(f);
    }
  });
  return out;
}

}  // namespace walkrad
