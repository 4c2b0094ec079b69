#include "walkrad/hierarchical/hierarchy.h"

#include <algorithm>
#include <cmath>

#include "walkrad/core/sampling.h"
#include "walkrad/scene/texture_sampling.h"

namespace walkrad {

Hierarchy::Hierarchy(const Scene& scene, const ClusterTree& tree, bool sample_textures)
    : scene_(scene), tree_(tree), sample_textures_(sample_textures) {
  area_prefix_.resize(tree.polygons.size() + 1, 0.0);
  normals_.resize(tree.polygons.size());
  for (size_t k = 0; k < tree.polygons.size(); ++k) {
    area_prefix_[k + 1] = area_prefix_[k] + polygon_area(scene.polygons[tree.polygons[k]]);
    normals_[k] = polygon_normal(scene.polygons[tree.polygons[k]]);
  }
  nodes_.reserve(4 * tree.nodes.size() + scene.polygons.size());
  polygon_root_.assign(scene.polygons.size(), UINT32_MAX);
  if (!tree.nodes.empty()) add_cluster(0, -1);
  made_at_start_ = nodes_.size();
}

uint32_t Hierarchy::add_element(const Polygon& shape, uint32_t polygon, int32_t parent, uint8_t depth) {
  HNode n;
  n.shape = shape;
  n.polygon = polygon;
  n.parent = parent;
  n.depth = depth;
  for (int k = 0; k < shape.count; ++k) n.bounds.extend(shape.v[k]);
  n.center = n.bounds.center();
  n.radius = 0.5 * length(n.bounds.diagonal());
  n.area = polygon_area(shape);
  n.normal = polygon_normal(shape);
  for (int a = 0; a < 3; ++a) {
    n.facing[size_t(2 * a)] = float(n.area * std::max(0.0, n.normal[a]));
    n.facing[size_t(2 * a + 1)] = float(n.area * std::max(0.0, -n.normal[a]));
  }
  const Material& m = scene_.materials[shape.material];
  n.rho = m.reflectance;
  n.emission = m.emission;
  if (sample_textures_) {
    const SurfaceColour c = element_colour(scene_, shape);
    n.rho = c.reflectance;
    n.emission = c.emission;
  }
  n.B = n.Bt = n.emission;
  nodes_.push_back(n);
  ++element_count_;
  return uint32_t(nodes_.size() - 1);
}

uint32_t Hierarchy::add_cluster(uint32_t tree_node, int32_t parent) {
  const ClusterNode& t = tree_.nodes[tree_node];
  const uint32_t index = uint32_t(nodes_.size());
  HNode n;
  n.cluster = true;
  n.tree_node = tree_node;
  n.parent = parent;
  n.bounds = t.bounds;
  n.center = t.bounds.center();
  n.radius = 0.5 * length(t.bounds.diagonal());
  n.area = t.area;
  nodes_.push_back(n);

  std::vector<uint32_t> kids;
  if (t.leaf()) {
    for (uint32_t k = t.first; k < t.first + t.count; ++k) {
      const uint32_t p = tree_.polygons[k];
      kids.push_back(add_element(scene_.polygons[p], p, int32_t(index), 0));
      polygon_root_[p] = kids.back();
    }
  } else {
    for (int c = 0; c < 2; ++c) kids.push_back(add_cluster(uint32_t(t.child[c]), int32_t(index)));
  }
  // Area-averaged material, for the oracle's ρ and for B before the first push-pull.
  Vec3 rho, e;
  std::array<float, 6> facing = {};
  for (uint32_t k : kids) {
    rho += nodes_[k].rho * nodes_[k].area;
    e += nodes_[k].emission * nodes_[k].area;
    for (size_t a = 0; a < 6; ++a) facing[a] += nodes_[k].facing[a];
  }
  HNode& me = nodes_[index];
  me.facing = facing;
  if (me.area > 0) {
    me.rho = rho / me.area;
    me.emission = e / me.area;
    me.B = me.Bt = me.emission;
  }
  me.child_begin = uint32_t(children_.size());
  me.child_count = uint32_t(kids.size());
  children_.insert(children_.end(), kids.begin(), kids.end());
  return index;
}

uint32_t quadrant_of(const std::array<Polygon, 4>& quadrants, const Vec3& normal, const Vec3& p) {
  for (uint32_t c = 0; c < 3; ++c) {
    const Polygon& q = quadrants[c];
    bool inside = true;
    for (int k = 0; k < q.count && inside; ++k)
      inside = dot(cross(q.v[(k + 1) % q.count] - q.v[k], p - q.v[k]), normal) >= 0;
    if (inside) return c;
  }
  return 3;
}

namespace {

// How a quad splits: where one pair of opposite sides is kStripAspect times as long as the other (by
// their means), into 4 strips across the long sides, else in quarters by the bilinear midpoints.
// Quarters keep the parent's aspect: a corridor's 320 × 2 m floor made 1.25 m × 8 mm slivers at depth 8,
// each near every vertex along it (the mesher's near sources); in strips it goes 80 × 2, 20 × 2, 5 × 2,
// then in quarters, and no element is more elongated than 4 to 1 but its input polygon.
constexpr double kStripAspect = 4.0;
enum class Split { kQuarters, kAlongU, kAlongV };  // strips along u (sample_polygon's v0 → v1) or v (v0 → v3)

Split split_of(const Polygon& s) {
  if (s.count != 4) return Split::kQuarters;
  const double lu = length(s.v[1] - s.v[0]) + length(s.v[2] - s.v[3]), lv = length(s.v[3] - s.v[0]) + length(s.v[2] - s.v[1]);
  if (lu >= kStripAspect * lv) return Split::kAlongU;
  if (lv >= kStripAspect * lu) return Split::kAlongV;
  return Split::kQuarters;
}

}  // namespace

uint32_t sample_quadrant(const Polygon& shape, double u, double v) {
  const Split split = split_of(shape);
  if (split == Split::kAlongU) return std::min(3u, uint32_t(4 * u));
  if (split == Split::kAlongV) return std::min(3u, uint32_t(4 * v));
  if (shape.count == 4) return u < 0.5 ? (v < 0.5 ? 0 : 3) : (v < 0.5 ? 1 : 2);
  const double su = std::sqrt(u);  // sample_polygon's barycentric weights: 1 − su, su (1 − v), su v
  if (su < 0.5) return 0;
  if (su * (1 - v) > 0.5) return 1;
  if (su * v > 0.5) return 2;
  return 3;
}

std::array<Polygon, 4> split_element(const Polygon& s) {
  auto piece = [&](std::initializer_list<Vec3> v) {
    Polygon p = s;
    p.count = uint8_t(v.size());
    std::copy(v.begin(), v.end(), p.v.begin());
    return p;
  };
  const Split split = split_of(s);
  if (split != Split::kQuarters) {
    // Strips between the bilinear points at u (or v) = k/4 on the two long sides, in the parent's winding.
    auto at = [&](double u, double v) { return s.v[0] * ((1 - u) * (1 - v)) + s.v[1] * (u * (1 - v)) + s.v[2] * (u * v) + s.v[3] * ((1 - u) * v); };
    std::array<Polygon, 4> out;
    for (int k = 0; k < 4; ++k) {
      const double a = 0.25 * k, b = 0.25 * (k + 1);
      out[size_t(k)] = split == Split::kAlongU ? piece({at(a, 0), at(b, 0), at(b, 1), at(a, 1)})
                                               : piece({at(0, a), at(1, a), at(1, b), at(0, b)});
    }
    return out;
  }
  if (s.count == 4) {
    const Vec3 m01 = (s.v[0] + s.v[1]) * 0.5, m12 = (s.v[1] + s.v[2]) * 0.5, m23 = (s.v[2] + s.v[3]) * 0.5,
               m30 = (s.v[3] + s.v[0]) * 0.5, c = (m01 + m23) * 0.5;
    return {piece({s.v[0], m01, c, m30}), piece({m01, s.v[1], m12, c}), piece({c, m12, s.v[2], m23}),
            piece({m30, c, m23, s.v[3]})};
  }
  const Vec3 m01 = (s.v[0] + s.v[1]) * 0.5, m12 = (s.v[1] + s.v[2]) * 0.5, m20 = (s.v[2] + s.v[0]) * 0.5;
  return {piece({s.v[0], m01, m20}), piece({m01, s.v[1], m12}), piece({m20, m12, s.v[2]}), piece({m01, m12, m20})};
}

bool Hierarchy::subdivide(uint32_t e) {
  if (nodes_[e].cluster) return false;
  if (nodes_[e].child_count) return true;
  const uint32_t polygon = nodes_[e].polygon;
  const uint8_t depth = uint8_t(nodes_[e].depth + 1);
  const std::array<Polygon, 4> kids = split_element(nodes_[e].shape);
  std::vector<uint32_t> idx;
  for (const Polygon& k : kids) idx.push_back(add_element(k, polygon, int32_t(e), depth));
  HNode& me = nodes_[e];
  me.child_begin = uint32_t(children_.size());
  me.child_count = 4;
  children_.insert(children_.end(), idx.begin(), idx.end());
  for (uint32_t k : idx) {  // start from the parent's value, not from zero
    nodes_[k].B = me.B;
    nodes_[k].Bt = me.Bt;
  }

  // Hand the parent's view hits to the children that contain them (ties to the first child).
  const uint32_t hb = me.hit_begin, he = me.hit_end;
  uint32_t at = hb;
  for (uint32_t c = 0; c < 4; ++c) {
    HNode& child = nodes_[idx[c]];
    child.hit_begin = at;
    if (c == 3) {
      at = he;  // whatever rounding left over goes to the last child
    } else {
      const Polygon& cp = child.shape;
      auto inside = [&](const ViewHit& h) {
        for (int k = 0; k < cp.count; ++k)
          if (dot(cross(cp.v[(k + 1) % cp.count] - cp.v[k], h.point - cp.v[k]), child.normal) < 0) return false;
        return true;
      };
      at = uint32_t(std::stable_partition(hits_.begin() + at, hits_.begin() + he, inside) - hits_.begin());
    }
    child.hit_end = at;
    child.R = 0;
    for (uint32_t h = child.hit_begin; h < child.hit_end; ++h) child.R += hits_[h].weight;
  }
  return true;
}

void Hierarchy::set_view_hits(std::vector<ViewHit> hits) {
  std::stable_sort(hits.begin(), hits.end(), [](const ViewHit& a, const ViewHit& b) { return a.polygon < b.polygon; });
  hits_ = std::move(hits);
  // Element roots, one per input polygon: find each polygon's range.
  std::vector<uint32_t> begin(scene_.polygons.size() + 1, 0);
  for (const ViewHit& h : hits_) ++begin[h.polygon + 1];
  for (size_t p = 0; p < scene_.polygons.size(); ++p) begin[p + 1] += begin[p];
  for (HNode& n : nodes_) n.R = 0;
  for (size_t i = nodes_.size(); i-- > 0;) {  // children come after their parents: sum bottom up
    HNode& n = nodes_[i];
    if (!n.cluster && n.depth == 0) {
      n.hit_begin = begin[n.polygon];
      n.hit_end = begin[n.polygon + 1];
      for (uint32_t h = n.hit_begin; h < n.hit_end; ++h) n.R += hits_[h].weight;
    }
    if (n.parent >= 0) nodes_[n.parent].R += n.R;
  }
}

void Hierarchy::scale_view_hits(double s) {
  for (ViewHit& h : hits_) h.weight *= s;
  for (HNode& n : nodes_) n.R *= s;
}

void Hierarchy::sample(const HNode& n, double u, double v, double w, Vec3& point, Vec3& normal, uint32_t* child) const {
  if (child) *child = 0;
  if (!n.cluster) {
    point = sample_polygon(n.shape, u, v);
    normal = n.normal;
    return;
  }
  const ClusterNode& t = tree_.nodes[n.tree_node];
  const double lo = area_prefix_[t.first], hi = area_prefix_[t.first + t.count];
  const double target = lo + w * (hi - lo);
  auto it = std::upper_bound(area_prefix_.begin() + t.first + 1, area_prefix_.begin() + t.first + t.count + 1, target);
  const size_t k = std::min<size_t>(size_t(it - area_prefix_.begin()) - 1, t.first + t.count - 1);
  const Polygon& p = scene_.polygons[tree_.polygons[k]];
  point = sample_polygon(p, u, v);
  normal = normals_[k];
  // The child holding slot k, from the tree's layout (add_cluster): a leaf cluster's elements are its
  // slots in order, and a tree node's child 0 holds the first half of its slots (build_cluster_tree).
  // Read from the children's nodes, it would be two cache misses a sample.
  if (child) *child = t.leaf() ? uint32_t(k - t.first) : uint32_t(k - t.first >= t.count / 2);
}

uint32_t share_areas(const Hierarchy& h, uint32_t receiver, std::array<double, 4>& areas) {
  const HNode& n = h[receiver];
  areas = {};
  if (n.cluster || n.child_count) {
    const uint32_t count = std::min<uint32_t>(n.child_count, 4);
    for (uint32_t c = 0; c < count; ++c) areas[c] = h[h.child(n, c)].area;
    return count;
  }
  const std::array<Polygon, 4> kids = split_element(n.shape);
  for (size_t c = 0; c < 4; ++c) areas[c] = polygon_area(kids[c]);
  return 4;
}

void normalize_shares(const Hierarchy& h, uint32_t receiver, std::array<float, 4>& share) {
  std::array<double, 4> areas;
  const uint32_t count = share_areas(h, receiver, areas);
  double total = 0, weighted = 0;
  for (uint32_t c = 0; c < count; ++c) {
    total += areas[c];
    weighted += areas[c] * std::max(0.0f, share[c]);
  }
  if (count == 0 || weighted <= 0) {
    share = {1, 1, 1, 1};
    return;
  }
  for (uint32_t c = 0; c < count; ++c) share[c] = float(std::max(0.0f, share[c]) * total / weighted);
}

// A link's size is the solve's memory per link, and the links are most of a large bake's memory.
static_assert(sizeof(Link) == 44, "a link's size changed");

std::array<uint16_t, 4> seen_weights(const double* visible_kernel, const double* area_share, uint32_t count, double within) {
  std::array<uint16_t, 4> out = {0, 0, 0, 0};
  double largest = 0, total = 0;
  for (uint32_t c = 0; c < count; ++c) {
    largest = std::max(largest, visible_kernel[c]);
    total += visible_kernel[c];
  }
  if (!(largest > 0)) return out;
  double apart = 0;
  for (uint32_t c = 0; c < count; ++c) apart += std::fabs(visible_kernel[c] / total - area_share[c]);
  if (apart < within) return out;
  for (uint32_t c = 0; c < count; ++c) out[c] = uint16_t(std::lround(65535.0 * visible_kernel[c] / largest));
  return out;
}

uint32_t child_slot(const Hierarchy& h, uint32_t node) {
  const int32_t parent = h[node].parent;
  if (parent < 0) return 0;
  const HNode& p = h[uint32_t(parent)];
  for (uint32_t c = 0; c < p.child_count; ++c)
    if (h.child(p, c) == node) return c;
  return 0;
}

namespace {

bool contains(const HNode& e, const Vec3& p) {
  const Polygon& s = e.shape;
  for (int k = 0; k < s.count; ++k)
    if (dot(cross(s.v[(k + 1) % s.count] - s.v[k], p - s.v[k]), e.normal) < -1e-12) return false;
  return true;
}
}  // namespace

uint32_t leaf_at(const Hierarchy& h, uint32_t node, const Vec3& p, int max_depth) {
  while (h[node].child_count && h[node].depth < max_depth) {
    uint32_t next = h.child(h[node], 0);
    for (uint32_t k = 0; k < h[node].child_count; ++k)
      if (contains(h[h.child(h[node], k)], p)) {
        next = h.child(h[node], k);
        break;
      }
    node = next;
  }
  return node;
}

}  // namespace walkrad
