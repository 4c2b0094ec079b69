// Uniform subdivision of the input polygons into elements no larger than a target size: the mesh of
// the classic (non-hierarchical) method (algorithms.md §2). A quad becomes an nu×nv grid of quads
// (bilinear parameterisation, planar for a planar quad), a triangle n² triangles. Elements of one
// polygon share their grid vertices, so vertex values can be averaged without cracks inside it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

struct Element {
  Polygon shape;                   // the element's own corners (material and source from its polygon)
  std::array<uint32_t, 4> corner;  // indices into Subdivision::vertices (count = shape.count)
  Vec3 normal;
  Vec3 centroid;
  double area = 0;
  uint32_t polygon = 0;
};

struct Subdivision {
  std::vector<Vec3> vertices;           // grid vertices, per polygon (not shared between polygons)
  std::vector<Element> elements;        // grouped by polygon, in polygon order
  std::vector<uint32_t> first_element;  // polygon p owns elements [first_element[p], first_element[p+1])
};

// target_size > 0: each element's edges are at most about target_size long.
Subdivision subdivide_uniform(const Scene& scene, double target_size);

}  // namespace walkrad
