// From the hierarchy's solution to a displayable mesh: the leaves of every element quadtree are the
// faces of a crack-free Gouraud mesh (surface_mesher.h: T-vertices anchored, vertex radiosity averaged
// over the leaves around each vertex, within a smoothing group; or the solution evaluated at each vertex).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "walkrad/formats/chunk.h"
#include "walkrad/hierarchical/hierarchy.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/output/surface_mesher.h"

namespace walkrad {

// How vertices take the solution (point_radiosity.h). Off: the leaves' mean radiosity.
struct PointSolution {
  bool on = false;
  bool indirect = true;                         // sources send B (else their emission only)
  const std::vector<uint32_t>* twins = nullptr; // transmitting polygons (kNoTwin: none) keep their mean
  const std::vector<PunctualLight>* lights = nullptr;  // shot at every vertex (null: the leaves' mean)
  const RayScene* rays = nullptr;               // their occluders (null: none)
  // The final gather (final_gather.h) at the vertices of these input polygons (1: seen by the
  // walkthrough; null: every polygon), when on.
  bool gather = false;
  const std::vector<uint8_t>* seen = nullptr;
  // With the gather: the seen faces cut along their emitters' shadow boundaries (discontinuity_mesh.h);
  // counts, when given, receives how many boundaries were found and drawn, and how many faces they cut.
  bool discontinuities = false;
  double position_error = 1e-5;  // of the scene's diagonal: the chunks' position quantum (cut_faces' snap)
  struct Counts {
    uint64_t found = 0, hidden = 0, drawn = 0, faces_cut = 0;
    uint64_t contact_bands = 0;  // near-contact band segments cut along (contact_split.h)
  };
  Counts* counts = nullptr;
  // Called once the mesh has read the solution at its points (mesh_faces' read), before the vertices'
  // direct light is gathered and the mesh written: the hierarchy's links may be freed then.
  std::function<void()> read;
};

// exposure: display colour = B/π × exposure, clamped to [0, 1].
SurfaceMesh mesh_hierarchy(const Hierarchy& h, double exposure, const PointSolution& point = {});

}  // namespace walkrad
