// Volume clusters (Sillion 1995; Sillion & Drettakis 1995; algorithms.md §7): a cluster of many small,
// separate objects (leaves, books on a shelf, chair legs) blocks light like a participating medium.
// Its objects, randomly placed and oriented, have a mean projected area of a quarter of their area,
// so a segment of length s through it is attenuated by exp(−κ s) with extinction
//
//     κ = A / (4 V)        (A: the blocking area inside, V: the cluster's volume).
//
// A is the one-sided polygon area, except that an open sheet (a leaf made of a few triangles) counts
// both of its faces: a flat plate of area a blocks a/2 on average, a closed convex surface of area a
// blocks a/4. Per connected object: blocking area = a + |Σ a n| (closed: a; flat: 2a).
//
// Which clusters are volumes: the small objects (a connected piece of geometry: polygons sharing a
// corner; at most small_object × the scene's diagonal) get a cluster tree of their own, so that a
// wall or a lamp beside them does not stretch its boxes; its clusters holding at least min_polygons
// polygons whose every object is at most feature_ratio of the cluster's smallest side, and whose
// objects are spread over its box as if at random (their count over a 4 × 4 × 4 lattice of the box has
// an index of dispersion, variance / mean, of at most max_dispersion; 1 for a Poisson process), are
// volumes. A finely tessellated wall is one big object, never a
// volume; books on a shelf at the side of a room are not the room's medium. The finest volumes (whose children are
// not both volumes) define the extinction field; their polygons are "in a volume".
#pragma once

#include <cstdint>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {

struct VolumeSettings {
  uint32_t min_polygons = 64;   // polygons in a volume, at least
  double feature_ratio = 0.25;  // its largest object, at most this fraction of its smallest side
  double small_object = 1.0 / 32;  // objects larger than this × the scene's diagonal are never in a volume
  double max_dispersion = 2.0;  // its objects' index of dispersion over a 4 × 4 × 4 lattice, at most (1: random)
  // The multi-resolution rule (volume_visibility.h): a link sees through a volume when its objects are
  // smaller than penumbra_ratio × the link's penumbra width there; exact rays otherwise.
  double penumbra_ratio = 1.0;
};

struct VolumeBox {
  Bounds bounds;
  double kappa = 0;  // 1/m
};

struct VolumeClusters {
  std::vector<VolumeBox> boxes;           // the finest volumes' bounds and κ, in their tree's order
  std::vector<double> object_size;        // per polygon: the diagonal of its object's bounds (membership)
  // per polygon: its object's width, the diameter of the disc with the object's mean projected area
  // (blocking area / 4): what its shadow is as wide as, whatever the object's orientation (the rule)
  std::vector<double> object_width;
  std::vector<uint8_t> polygon_in_volume; // per polygon: 1 if in a finest volume
  // Per node of the scene's ClusterTree (the one links and shafts use): every polygon below is in a
  // volume, and the widest object below.
  std::vector<uint8_t> node_in_volume;
  std::vector<double> node_feature;
  uint64_t volume_polygons = 0;
  bool empty() const { return boxes.empty(); }
};

// tree: the scene's cluster tree (node_in_volume and node_feature are per its nodes).
VolumeClusters find_volume_clusters(const Scene& scene, const ClusterTree& tree, const VolumeSettings& settings);

// Per polygon: its blocking area (see above), from its connected object's closure; optionally its
// object's bounds diagonal and width (VolumeClusters), its object (an index) and its object's bounds
// centre.
std::vector<double> blocking_areas(const Scene& scene, std::vector<double>* object_size = nullptr,
                                   std::vector<double>* object_width = nullptr, std::vector<uint32_t>* object_id = nullptr,
                                   std::vector<Vec3>* object_centre = nullptr);

}  // namespace walkrad
