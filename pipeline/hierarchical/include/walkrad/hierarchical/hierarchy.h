// The hierarchy of hierarchical radiosity with clustering (Hanrahan, Salzman & Aupperle 1991; Smits,
// Arvo & Greenberg 1994; Sillion 1995; algorithms.md §5, §7): cluster nodes mirror the ClusterTree
// (one root cluster over the whole scene), each leaf cluster's polygons are element roots, and each
// element splits lazily into 4 (a quad by its bilinear midpoints, a triangle by its edge midpoints).
//
// A node carries the solution at its level: radiosity B (area-averaged over what is below), the
// irradiance H gathered along its links this iteration, and importance I (Smits, Arvo & Salesin
// 1992), which is extensive: a parent's importance is the sum of its children's.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "walkrad/core/byte_buffer.h"
#include "walkrad/core/huge_pages.h"
#include "walkrad/formats/scene.h"
#include "walkrad/scene/cluster_tree.h"

namespace walkrad {

// A transfer: the receiver gathers H += F · B_source. F is the form factor from the receiver to the
// source (visibility included), for clusters with the isotropic mean projected area A/4.
// share[k]·F is the form factor from the receiver's child k (an element's quadrants in split_element
// order, a cluster's children; at most 4) to the source: how unevenly the transfer falls on the
// receiver. The solve pushes each child its share (a cluster's books get the light their spines and
// tops face, not the cluster's mean), and the refinement measures how far the shares leave the
// children apart. Deviations from 1 that the link's samples cannot tell from noise (within 2 standard
// errors) are shrunk to 1; the shares' area mean over the children is 1 (the transfer's power is F).
struct Link {
  // The form factor, as a float: its Monte Carlo noise is 1e-3 and more, a float's rounding 6e-8, and
  // 4 bytes less a link took 55,080 kB off the 150-room level's peak (what F is summed into stays double).
  float F = 0;
  uint32_t source = 0;
  float sigma = 0;  // standard error of F from its visibility and Monte Carlo samples (0: exact)
  float open = 0;   // the unoccluded form factor: F / open is the fraction of the source the receiver sees
  std::array<float, 4> share = {1, 1, 1, 1};
  uint8_t rays = 0;  // 1: visibility by Embree rays (something can block), 2: through volumes (Pending's flags)
  // How unevenly the unoccluded kernel falls inside the receiver's children: the largest departure of
  // a quarter of a child from that child's mean, in 64ths of F (an element receiver's quadrature points
  // grouped by quarter, for an emitting source; else 0). The shares say how the children differ; a transfer
  // that peaks inside each child they miss (error_estimate.cpp).
  uint8_t inner = 0;
  uint16_t samples = 0;  // the rays (or Monte Carlo samples) it was evaluated with
  // Where the receiver sees part of the source: how much of what arrives comes from each of the
  // source's children (an element's quadrants in split_element order, a cluster's children; at most
  // 4), from the visible kernel of the link's rays, in 65535ths of the largest. All 0: the source's
  // area mean. The parts a receiver cannot see are mostly the parts in shadow, so the mean sends too
  // little (by it, office-floor's ceilings are 5.5% too dark, fed by floors half under desks).
  std::array<uint16_t, 4> seen = {0, 0, 0, 0};
};

inline bool has_seen(const Link& l) { return (l.seen[0] | l.seen[1] | l.seen[2] | l.seen[3]) != 0; }

// Whether a link carries anything. At F = 0 (every ray blocked, or its estimate clamped at 0) it is kept
// for its σ, which the refinement and the error estimate read; the passes that add F × what its source
// sends pass over it without reading the source (office-floor's 8 rooms: 40% of the links).
// Passing over it keeps the bits: each term it would add is a zero.
inline bool carries(const Link& l) { return l.F != 0; }

// A node's values: everything but its links, plain data (a checkpoint copies it whole). What a sweep
// reads of each link's source comes first, in the node's first cache line (Bt, cluster, center; HNode
// is aligned to one, and 640 bytes): read at random across the level for every link of every sweep,
// they lay 384 bytes apart in two lines. The flags sit together: no padding after each.
struct HNodeValues {
  Vec3 Bt;                // radiosity as links carry it away: leaves B × send, area-averaged up
  bool cluster = false;
  uint8_t depth = 0;      // element: 0 for an input polygon
  bool balanced = false;  // leaf: its factors make its row sum exactly 1 (balance_closed_transport)
  bool D_known = false;   // D computed (new elements get theirs before they are solved)
  uint32_t polygon = UINT32_MAX;  // element: its input polygon
  Vec3 center;            // of the bounds
  Bounds bounds;
  double radius = 0;      // half the bounds' diagonal
  double area = 0;        // one-sided area (element) or the total below (cluster)
  uint32_t tree_node = UINT32_MAX;  // cluster: its ClusterTree node
  int32_t parent = -1;
  uint32_t child_begin = 0, child_count = 0;  // into Hierarchy::children
  Polygon shape;          // element
  Vec3 normal;            // element
  Vec3 rho, emission;     // element; cluster: area averages (used by the refinement oracle)
  // Area facing each way: Σ A_k max(0, ±n_k·axis) over its surfaces, in the order +x −x +y −y +z −z.
  // projected_area() from it gives how much of the node a direction meets (a cluster's orientation).
  std::array<float, 6> facing = {};

  Vec3 B, H;              // radiosity, irradiance gathered this iteration along its own links
  Vec3 Hp;                // irradiance its parent's links push to it this iteration (their shares of it)
  double Fp = 0;          // and their form factors, so weighted (its share of the parent's row sum)
  double send = 1.0;      // leaf: factor on what it sends (closed scenes: link_transport.h)
  double receive = 1.0;   // leaf: factor on what it gathers (closed scenes: link_transport.h)
  Vec3 D;                 // element: irradiance from punctual lights (punctual_lights.h), its area mean
  Vec3 Hl;                // leaf element: the irradiance its links and its ancestors' gave, last solved
  double Fsum = 0;        // Σ F over this node's links (its share of a leaf's row sum)
  float error = 0;        // the error its own links leave in its radiosity (luminance, W/m²; error_estimate.cpp)
  double R = 0;           // direct importance (leaf elements; summed up in clusters)
  double I = 0, Ig = 0;   // importance, importance gathered this iteration
  uint32_t hit_begin = 0, hit_end = 0;  // element: its view hits, Hierarchy::hits()[begin, end)
};

struct alignas(64) HNode : HNodeValues {
  std::vector<Link> links;  // links where this node receives
};

// A large level's nodes are a gigabyte, reserved at the start and read at random by every link: on
// huge pages, a fault for each 2 MiB as they are made (not each 4 KiB: the hierarchy's constructor
// spent a second of one thread in page faults at 150 rooms) and one TLB entry for 3,000 nodes.
using HNodes = GrowingHugeVector<HNode>;

// A primary-ray hit from a viewpoint: where a walkthrough looks, and how much (its share of the
// views' solid angle). Summed over an element, the hits give its direct importance R.
struct ViewHit {
  uint32_t polygon;
  Vec3 point;
  double weight;
  uint32_t view = 0;  // index of the viewpoint it came from
};

// Which rank holds the links of each input polygon's elements (link_owners.h): a divided solve.
struct LinkOwners {
  std::vector<uint16_t> rank;  // by input polygon; empty: every link on this rank
  uint16_t me = 0;
  bool divided() const { return !rank.empty(); }
  bool holds_polygon(uint32_t polygon) const { return rank.empty() || rank[polygon] == me; }
};

class Hierarchy {
 public:
  // sample_textures: elements take their textures' mean over their own area (texture_sampling.h).
  Hierarchy(const Scene& scene, const ClusterTree& tree, bool sample_textures = false);

  const Scene& scene() const { return scene_; }
  const ClusterTree& tree() const { return tree_; }
  HNodes& nodes() { return nodes_; }
  const HNodes& nodes() const { return nodes_; }
  HNode& operator[](uint32_t i) { return nodes_[i]; }
  const HNode& operator[](uint32_t i) const { return nodes_[i]; }
  uint32_t root() const { return 0; }
  // Clusters are numbered 0 .. cluster_count() − 1 by HNode::tree_node (every ClusterTree node is one):
  // arrays kept for clusters alone are indexed so, not by node.
  size_t cluster_count() const { return tree_.nodes.size(); }
  // The nodes the constructor made, [0, made_at_start()): every cluster and each input polygon's root
  // element, in preorder of the cluster tree (a cluster, its element roots, then its children's
  // subtrees). Split elements come after; these never move (load_state checks them).
  size_t made_at_start() const { return made_at_start_; }
  uint32_t child(const HNode& n, uint32_t k) const { return children_[n.child_begin + k]; }

  // Splits an element into 4 children (no-op when it already has them). Returns false for a cluster
  // (its children always exist).
  bool subdivide(uint32_t element);

  // The input polygons under a cluster node, as a range of ClusterTree::polygons.
  uint32_t polygon_begin(const HNode& cluster) const { return tree_.nodes[cluster.tree_node].first; }
  uint32_t polygon_count(const HNode& cluster) const { return tree_.nodes[cluster.tree_node].count; }
  // The normal (polygon_normal) of the polygon at ClusterTree::polygons[k], kept for clusters' samples.
  const Vec3& tree_polygon_normal(uint32_t k) const { return normals_[k]; }

  // A point of the node for visibility and Monte Carlo transfers, from (u, v, w) ∈ [0,1)³: on an
  // element, by area; in a cluster, on one of its polygons chosen by area. normal: that surface's.
  // child: set to which of a cluster's children holds the point (0 for an element).
  void sample(const HNode& n, double u, double v, double w, Vec3& point, Vec3& normal, uint32_t* child = nullptr) const;

  size_t element_count() const { return element_count_; }
  // The element root of an input polygon.
  uint32_t polygon_root(uint32_t polygon) const { return polygon_root_[polygon]; }

  // Direct importance: every element's R is the weight of the hits inside it, clusters' R the sum
  // below. Hits follow elements as they split.
  void set_view_hits(std::vector<ViewHit> hits);
  const std::vector<ViewHit>& hits() const { return hits_; }
  // Every hit's weight and every node's R times s: a unit chosen once applies to the elements made
  // later as well (subdivide sums the hits' weights).
  void scale_view_hits(double s);

  // What refinement and the solve change (every node, its links, the children, the view hits), for
  // a checkpoint; load_state restores it into a hierarchy built from the same scene and tree.
  void save_state(ByteWriter& out) const;
  void load_state(ByteReader& in);

  // Which links this rank holds (a divided solve, link_owners.h); by default all of them.
  const LinkOwners& owners() const { return owners_; }
  LinkOwners& owners() { return owners_; }

 private:
  uint32_t add_element(const Polygon& shape, uint32_t polygon, int32_t parent, uint8_t depth);
  uint32_t add_cluster(uint32_t tree_node, int32_t parent);

  const Scene& scene_;
  const ClusterTree& tree_;
  bool sample_textures_ = false;
  HNodes nodes_;
  std::vector<uint32_t> children_;
  std::vector<double> area_prefix_;  // prefix sums of polygon areas in ClusterTree::polygons order
  // Polygon normals in the same order, for a cluster's samples. Each equals its polygon's root
  // element's normal, but read here beside area_prefix_: through polygon_root_ office3 bakes 3% slower.
  std::vector<Vec3> normals_;
  std::vector<ViewHit> hits_;
  std::vector<uint32_t> polygon_root_;        // grouped by element, each element's hits contiguous
  size_t element_count_ = 0;
  size_t made_at_start_ = 0;
  LinkOwners owners_;
};

// Σ A_k max(0, n_k·d) over a node's surfaces for a unit direction d, from HNode::facing (exact where the
// surfaces face along the axes, close otherwise).
inline double projected_area(const HNode& n, const Vec3& d) {
  return std::fabs(d.x) * n.facing[d.x > 0 ? 0 : 1] + std::fabs(d.y) * n.facing[d.y > 0 ? 2 : 3] +
         std::fabs(d.z) * n.facing[d.z > 0 ? 4 : 5];
}

// The four children of an element as Hierarchy::subdivide makes them: a quad by its bilinear
// midpoints, or, where one pair of its opposite sides is 4 times as long as the other, in 4 strips
// across its long sides; a triangle by its edge midpoints (the fourth child the middle one).
std::array<Polygon, 4> split_element(const Polygon& shape);

// Which of split_element's four children holds sample_polygon(shape, u, v): a quad's bilinear
// midpoint lines are its (u, v) = 0.5 lines, its strips' borders u (or v) = k/4; a triangle's corner children hold barycentric weights
// above 1/2. (quadrant_of from the point, without its three polygon tests.)
uint32_t sample_quadrant(const Polygon& shape, double u, double v);

// Which of split_element's four children holds p (on the element's plane; normal: the element's):
// the first of the three outer ones whose edges all have p on their inner side, else the fourth.
uint32_t quadrant_of(const std::array<Polygon, 4>& quadrants, const Vec3& normal, const Vec3& p);

// The areas of the receiver's children that Link::share refers to (an element not yet split: its
// quadrants); returns their count (0 for a leaf cluster without children).
uint32_t share_areas(const Hierarchy& h, uint32_t receiver, std::array<double, 4>& areas);

// Scales a link's shares (Link::share) so that their area mean over the receiver's children is 1.
void normalize_shares(const Hierarchy& h, uint32_t receiver, std::array<float, 4>& share);

// Calls part(node, weight) for the nodes a link takes its source's radiosity from, the weights
// summing to 1: the source itself, or where Link::seen is set and the source has been split, its
// children weighed by it. Inline: the solve's sweeps call it for every link.
template <class F>
inline void for_each_part(const Hierarchy& h, const Link& link, F part) {
  const HNode& s = h[link.source];
  if (!has_seen(link) || s.child_count < 2 || s.child_count > 4) {
    part(link.source, 1.0);
    return;
  }
  const double scale = 1.0 / (double(link.seen[0]) + link.seen[1] + link.seen[2] + link.seen[3]);  // 0 past the children
  for (uint32_t c = 0; c < s.child_count; ++c) part(h.child(s, c), link.seen[c] * scale);
}

// Link::seen from the visible kernel that fell on each of the source's parts (count of them), or none
// (all 0) where the parts' shares of it differ from their shares of the source's area by less than
// `within` in all (Σ |share − area share|): the mean then errs by at most within / 2 of the
// parts' spread of radiosity, and every sweep is spared reading the parts.
std::array<uint16_t, 4> seen_weights(const double* visible_kernel, const double* area_share, uint32_t count, double within);

// Which child of its parent a node is (0 for the root).
uint32_t child_slot(const Hierarchy& h, uint32_t node);

// The leaf element containing a point of an input polygon (the gather at a point, transmission, tests).
// (max_depth: stop at that quadtree depth even if the node there has children.)
uint32_t leaf_at(const Hierarchy& h, uint32_t polygon_root, const Vec3& p, int max_depth = 255);

}  // namespace walkrad
