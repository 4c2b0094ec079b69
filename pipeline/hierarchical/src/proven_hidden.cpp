// Links whose every ray was blocked, and whether their occlusion is proven (occlusion_proof.h): the
// planes to try are those of the first surfaces a few of their segments meet.
#include "link_evaluator.h"

#include <algorithm>

namespace walkrad::hierarchical_detail {

bool LinkEvaluator::proven_hidden(const Pending& p, const std::vector<RayScene::Segment>& segments) const {
  if (p.volume || segments.empty()) return false;
  // The first surfaces met by a few segments spread over the list (their planes are the walls to try).
  std::array<uint32_t, kProofHints> planes;
  size_t count = 0;
  for (int k = 0; k < kProofHints; ++k) {
    const RayScene::Segment& s = segments[size_t(k) * (segments.size() - 1) / (kProofHints - 1)];
    const RayScene::Hit hit = rays_.intersect(s.from, s.to - s.from);
    if (hit.hit && std::find(planes.begin(), planes.begin() + count, hit.polygon) == planes.begin() + count) planes[count++] = hit.polygon;
  }
  Vec3 ri_box[8], sj_box[8];
  auto end = [&](const HNode& n, Vec3 (&box)[8]) {
    return n.cluster ? OcclusionProof::box(n.bounds, n.tree_node, box) : OcclusionProof::element(n.shape);
  };
  return proof_.blocked(end(h_[p.receiver], ri_box), end(h_[p.source], sj_box), planes.data(), count);
}

}  // namespace walkrad::hierarchical_detail
