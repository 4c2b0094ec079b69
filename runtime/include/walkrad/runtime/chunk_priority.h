// Chunk priority: which chunks of a bake the camera needs now and which it will need soon, from the
// manifest alone (no GL, no files), so that the streaming policy can be tested on its own.
//
// On the walkthrough (the manifest's viewpoints, frame by frame), a chunk's importance for a
// viewpoint is the fraction of that viewpoint's image it covers (manifest.h), here widened to the
// largest over the frames just before and after (the bake's ray grid can miss a sliver). At frame i, looking L
// frames ahead, let k be the first k = 0..L with importance[c][i + k] > 0: the chunk is needed k
// frames from now, and the sooner the more useful (like Belady's rule for caches: what is needed
// last is evicted first); among chunks needed at the same frame, the larger part of the image first:
//   p(c) = (L + 1 − k + importance[c][i + k] / 2) / (L + 1)  +  w_d / (1 + d(c))
// and p(c) = w_d / (1 + d(c)) when no frame ahead sees it, where d(c) is the distance from the camera
// to the chunk's bounds and w_d = 1e-7 only orders those chunks (what a person leaving the path
// would meet first). Off the path (free flight) there is no importance:
//   p(c) = (in the view frustum ? 1 : 1/4) / (1 + d(c)).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "walkrad/formats/manifest.h"

namespace walkrad {

struct CameraPlace {
  Viewpoint view;
  std::optional<size_t> path_frame;  // index into manifest.viewpoints when the camera is on the path
  bool loop = false;                 // the path wraps around (window playback) rather than ends
};

// One priority per manifest chunk, larger first (see above). lookahead = L in frames.
std::vector<double> chunk_priorities(const Manifest& manifest, const CameraPlace& camera, size_t lookahead);

// The chunks a frame cannot do without: on the path, those the current viewpoint or its neighbours
// see (widened importance > 0); off it, those whose bounds meet the view frustum. Ascending chunk order.
std::vector<uint32_t> chunks_needed(const Manifest& manifest, const CameraPlace& camera);

// Distance from a point to an axis-aligned box (0 inside).
double distance_to_bounds(const Vec3& point, const Bounds& bounds);

// Whether the box may be seen by the viewpoint (a conservative test against the frustum's planes,
// with the scene's clip planes): false only when it is entirely outside one plane.
bool bounds_in_frustum(const Viewpoint& view, const Bounds& scene_bounds, const Bounds& box);

}  // namespace walkrad
