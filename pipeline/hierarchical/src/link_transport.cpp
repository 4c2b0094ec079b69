#include "walkrad/hierarchical/link_transport.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "walkrad/core/huge_pages.h"
#include "walkrad/hierarchical/cluster_radiosity.h"
#include "walkrad/hierarchical/directional_irradiance.h"
#include "walkrad/hierarchical/hierarchy_walk.h"
#include "walkrad/hierarchical/link_owners.h"

namespace walkrad {

namespace {

constexpr double kMinFactor = 0.25, kMaxFactor = 4.0;
constexpr double kMinRaw = 0.25, kMaxRaw = 4.0;  // unscaled sums of the leaves that are balanced

Vec3 abs3(const Vec3& v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

// Area mean over each node's leaf elements of value(leaf) (clusters without elements: 0), each node
// after its children (hierarchy_walk.h: in parallel, the bits of one pass in reverse node order).
template <class Vector, class F>
void area_means(const Hierarchy& h, Vector& mean, F value) {
  using T = typename Vector::value_type;
  const HNodes& nodes = h.nodes();
  mean.assign(nodes.size(), T{});
  nodes_bottom_up(h, [&](uint32_t k) {
    const HNode& n = nodes[k];
    if (n.child_count == 0) {
      if (!n.cluster) mean[k] = value(n, k);
      return;
    }
    T sum{};
    for (uint32_t c = 0; c < n.child_count; ++c) {
      const uint32_t child = h.child(n, c);
      sum = sum + mean[child] * nodes[child].area;
    }
    mean[k] = n.area > 0 ? sum * (1.0 / n.area) : T{};
  });
}

// Sums along each node's path from the root of per-node values (parents come first).
std::vector<double> path_sums(const Hierarchy& h, const std::vector<double>& per_node) {
  std::vector<double> path(per_node.size(), 0.0);
  for (size_t k = 0; k < per_node.size(); ++k) {
    const int32_t parent = h.nodes()[k].parent;
    path[k] = per_node[k] + (parent >= 0 ? path[size_t(parent)] : 0.0);
  }
  return path;
}

// What reaches every element along its ancestors' links, as the solve pushes it (solve_sweep.cpp):
// a cluster's transfers by direction (directional_irradiance.h), taken by the first element below it
// by its normal; an element's split among its children by their shares (Link::share); a leaf element
// adds its own links'. H: Σ F · value(source, receiver), for N quantities at once (value returns N of them:
// one walk over the links for all; each sum in the order a single one would take); row: Σ F.
// Parents come first in the node array.
// (On huge pages: made afresh every round, core/huge_pages.h.)
template <size_t N>
struct Delivery {
  HugeVector<std::array<Vec3, N>> H;
  HugeVector<double> row;
};

// What a link with Link::seen takes from its source's parts, as the solve takes it.
template <size_t N, class V>
std::array<Vec3, N> seen_value(const Hierarchy& h, const Link& l, const HNode& receiver, V& value) {
  std::array<Vec3, N> out{};
  for_each_part(h, l, [&](uint32_t node, double w) {
    const std::array<Vec3, N> v = value(node, receiver);
    for (size_t m = 0; m < N; ++m) out[m] += v[m] * w;
  });
  return out;
}

// Into d, whose memory is kept (aggregation_correction's callers keep it between calls).
template <size_t N, class V>
void delivered(const Hierarchy& h, V value, Delivery<N>& d) {
  const HNodes& nodes = h.nodes();
  d.H.assign(nodes.size(), std::array<Vec3, N>{});
  d.row.assign(nodes.size(), 0.0);
  // Each element root takes what the clusters above it deliver to its normal (a cube kept for every
  // cluster would be one more array of fresh pages each call).
  gather_down_clusters<N>(
      h, [&](const Link& l, const HNode& n) { return has_seen(l) ? seen_value<N>(h, l, n, value) : value(l.source, n); },
      [&](uint32_t root, const std::array<DirectionalIrradiance, N>& cubes) {
        for (size_t m = 0; m < N; ++m) d.H[root][m] = cubes[m].at(nodes[root].normal);
        d.row[root] = cubes[0].row(nodes[root].normal);
      });
  // Each input polygon's element tree depends only on the clusters above it: the trees in parallel,
  // each node after its parent. A parent's links are walked once for its four children (each child's
  // sum takes them in the same order as a walk per child would: the same bits).
  struct Item {
    uint32_t node;
    std::array<Vec3, N> H;
    double row;
  };
  const size_t polygons = h.scene().polygons.size();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, polygons, 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<Item> stack;
    for (size_t p = r.begin(); p != r.end(); ++p) {
      if (!h.owners().holds_polygon(uint32_t(p))) continue;  // its rank's (link_owners.h)
      const uint32_t root = h.polygon_root(uint32_t(p));
      stack.assign(1, Item{root, d.H[root], d.row[root]});  // what the clusters above deliver (set above)
      while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        const HNode& n = nodes[it.node];
        if (n.child_count == 0)
          for (const Link& l : n.links) {
            if (!carries(l)) continue;
            const std::array<Vec3, N> v = has_seen(l) ? seen_value<N>(h, l, n, value) : value(l.source, n);
            for (size_t m = 0; m < N; ++m) it.H[m] += v[m] * l.F;
            it.row += l.F;
          }
        d.H[it.node] = it.H;
        d.row[it.node] = it.row;
        if (n.child_count == 0) continue;
        const uint32_t kids = std::min<uint32_t>(n.child_count, 4);
        std::array<Item, 4> child;
        for (uint32_t c = 0; c < kids; ++c) child[c] = {h.child(n, c), it.H, it.row};
        for (const Link& l : n.links) {
          if (!carries(l)) continue;
          const std::array<Vec3, N> v = has_seen(l) ? seen_value<N>(h, l, n, value) : value(l.source, n);
          for (uint32_t c = 0; c < kids; ++c) {
            const double f = l.F * double(l.share[c]);
            for (size_t m = 0; m < N; ++m) child[c].H[m] += v[m] * f;
            child[c].row += f;
          }
        }
        for (uint32_t c = 0; c < kids; ++c) stack.push_back(child[c]);
      }
    }
  });
  struct Delivered {
    std::array<Vec3, N> H;
    double row;
  };
  share_element_values<Delivered>(
      h, [&](uint32_t k) { return Delivered{d.H[k], d.row[k]}; },
      [&](uint32_t k, const Delivered& v) {
        d.H[k] = v.H;
        d.row[k] = v.row;
      });
}

// N values of a node side by side, so that a link reads its source's in one place.
template <size_t N>
struct Values {
  std::array<Vec3, N> v{};
  Values operator+(const Values& o) const {
    Values r;
    for (size_t m = 0; m < N; ++m) r.v[m] = v[m] + o.v[m];
    return r;
  }
  Values operator*(double s) const {
    Values r;
    for (size_t m = 0; m < N; ++m) r.v[m] = v[m] * s;
    return r;
  }
};

// What transport fills; kept between calls by aggregation_correction's callers.
template <size_t N>
struct TransportBuffers {
  HugeVector<Values<N>> sent;
  std::array<HugeVector<std::array<Vec3, 6>>, N> facing;  // by cluster
  Delivery<N> delivery;
};

// T x for N vectors x at once, x(leaf) the N values at a leaf element (zero elsewhere). Returns the
// delivery: leaf_irradiance(leaf, H[k][m], row[k]) is (T x_m) at leaf k. Only the node-sized arrays
// the walk needs are held (each fresh page a fault).
template <size_t N, class X>
const Delivery<N>& transport(const Hierarchy& h, X x, TransportBuffers<N>& t) {
  const HNodes& nodes = h.nodes();
  HugeVector<Values<N>>& sent = t.sent;
  area_means(h, sent, [&](const HNode& n, size_t) {
    const std::array<Vec3, N> at = x(n);
    Values<N> r;
    for (size_t m = 0; m < N; ++m) r.v[m] = at[m] * n.send;
    return r;
  });
  // A cluster sends by direction (cluster_radiosity.h), as the solve's gather takes it.
  std::array<HugeVector<std::array<Vec3, 6>>, N>& facing = t.facing;
  for (size_t m = 0; m < N; ++m) facing_radiosity(h, [&](uint32_t k) { return sent[k].v[m]; }, facing[m]);
  Delivery<N>& d = t.delivery;
  delivered<N>(h, [&](uint32_t source, const HNode& receiver) {
    const HNode& s = nodes[source];
    if (!s.cluster) return sent[source].v;
    const Vec3 u = normalize(receiver.center - s.center);
    std::array<Vec3, N> v;
    for (size_t m = 0; m < N; ++m) v[m] = radiosity_towards(s, facing[m][s.tree_node], u, sent[source].v[m]);
    return v;
  }, d);
  return d;
}

// Row sums of every leaf, Σ F s̄ along its path as the solve pushes it, with send factors send(node).
template <class F>
std::vector<double> row_sums(const Hierarchy& h, F send) {
  HugeVector<double> mean;
  area_means(h, mean, [&](const HNode& n, size_t) { return send(n); });
  Delivery<1> d;
  delivered<1>(h, [&](uint32_t source, const HNode&) {
    return std::array<Vec3, 1>{Vec3(mean[source], mean[source], mean[source])};
  }, d);
  std::vector<double> out(d.H.size());
  for (size_t k = 0; k < out.size(); ++k) out[k] = d.H[k][0].x;
  return out;
}

// The area a link's receiver takes its transfer over, each part weighed by its share and by
// weight(part): Σ_c A_c share_c w_c over its children (a leaf: A w).
template <class W>
double received_area(const Hierarchy& h, uint32_t receiver, const Link& l, W weight) {
  const HNode& p = h[receiver];
  if (p.child_count == 0 || p.cluster) return p.area * weight(receiver);  // a cluster: by direction, taken as even
  double sum = 0;
  for (uint32_t c = 0; c < p.child_count && c < 4; ++c) {
    const uint32_t child = h.child(p, c);
    sum += h[child].area * double(l.share[c]) * weight(child);
  }
  return sum;
}

// What every leaf's unit radiosity delivers per unit area, Σ F A_p ā_p / A_q along its path over the
// links (p ← q) leaving q, with receive factors receive(node).
template <class F>
std::vector<double> column_sums(const Hierarchy& h, F receive) {
  const HNodes& nodes = h.nodes();
  std::vector<double> mean;
  area_means(h, mean, [&](const HNode& n, size_t) { return receive(n); });
  std::vector<double> per_node(nodes.size(), 0.0);
  for (size_t k = 0; k < nodes.size(); ++k)  // sequential: a fixed order of sums
    for (const Link& l : nodes[k].links) {
      const double power = l.F * received_area(h, uint32_t(k), l, [&](uint32_t c) { return mean[c]; });
      for_each_part(h, l, [&](uint32_t node, double w) { per_node[node] += power * w / nodes[node].area; });  // Link::seen
    }
  return path_sums(h, per_node);
}

// Sets every balanced leaf's factor to 1 / its sum. Returns the largest change of a factor.
double set_factors(Hierarchy& h, const std::vector<double>& sums, bool receive) {
  double change = 0;
  for (size_t k = 0; k < sums.size(); ++k) {
    HNode& n = h.nodes()[k];
    if (!n.balanced) continue;
    const double f = std::clamp(1.0 / sums[k], kMinFactor, kMaxFactor);
    double& slot = receive ? n.receive : n.send;
    change = std::max(change, std::fabs(f - slot));
    slot = f;
  }
  return change;
}

}  // namespace

std::vector<double> mean_receive(const Hierarchy& h) {
  std::vector<double> mean;
  area_means(h, mean, [](const HNode& n, size_t) { return n.receive; });
  return mean;
}

Vec3 leaf_irradiance(const HNode& leaf, const Vec3& H, double row_sum, bool* clamped) {
  const double s = row_sum * leaf.receive;
  if (s > kMaxRowSum && !leaf.balanced) {
    if (clamped) *clamped = true;
    return H * (leaf.receive / s);
  }
  return H * leaf.receive;
}

std::vector<Vec3> emitted_as_sent(const Hierarchy& h) {
  std::vector<Vec3> mean;
  area_means(h, mean, [](const HNode& n, size_t) { return n.emission * n.send; });
  return mean;
}

void pull_up_radiosity(Hierarchy& h) {
  HNodes& nodes = h.nodes();
  nodes_bottom_up(h, [&](uint32_t k) {
    HNode& n = nodes[k];
    if (n.child_count == 0) {
      if (!n.cluster) n.Bt = n.B * n.send;
      return;
    }
    Vec3 b, bt;
    for (uint32_t c = 0; c < n.child_count; ++c) {
      const HNode& child = nodes[h.child(n, c)];
      b += child.B * child.area;
      bt += child.Bt * child.area;
    }
    n.B = n.area > 0 ? b / n.area : Vec3{};
    n.Bt = n.area > 0 ? bt / n.area : Vec3{};
  });
}

BalanceStats balance_closed_transport(Hierarchy& h, double tolerance, int max_iterations) {
  BalanceStats stats;
  const HNodes& nodes = h.nodes();
  // Leaves whose unscaled row or column sum is far from 1 are not a matter of distribution: a piece
  // hidden under furniture (no link reaches it) or coincident surfaces. They keep factors of 1, so
  // that the rest converges (their bounded factors would fight the others' and never settle).
  const auto one = [](const HNode&) { return 1.0; };
  const std::vector<double> raw_rows = row_sums(h, one), raw_columns = column_sums(h, one);
  for (size_t k = 0; k < nodes.size(); ++k) {
    HNode& n = h.nodes()[k];
    n.balanced = false;  // also on nodes that were leaves in an earlier round
    if (!is_leaf_element(n)) continue;
    n.balanced = scalable_row(raw_rows[k]) && scalable_row(raw_columns[k]);
    if (!n.balanced) {
      n.send = n.receive = 1.0;
      ++stats.unbalanced;
    }
  }
  const auto send = [](const HNode& n) { return n.send; };
  const auto receive = [](const HNode& n) { return n.receive; };
  for (stats.iterations = 1; stats.iterations <= max_iterations; ++stats.iterations) {
    const double columns = set_factors(h, column_sums(h, receive), false);
    const double rows = set_factors(h, row_sums(h, send), true);
    if (std::max(columns, rows) <= tolerance) break;
  }
  stats.iterations = std::min(stats.iterations, max_iterations);
  // What is left, over the balanced leaves: rows are exact after the last row update (but for bounded
  // factors); the columns are off by what one more column update would change.
  const std::vector<double> rows = row_sums(h, send), columns = column_sums(h, receive);
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (!nodes[k].balanced) continue;
    stats.row_error = std::max(stats.row_error, std::fabs(rows[k] * nodes[k].receive - 1.0));
    stats.column_error = std::max(stats.column_error, std::fabs(columns[k] * nodes[k].send - 1.0));
  }
  return stats;
}

bool scalable_row(double raw_row) { return raw_row >= kMinRaw && raw_row <= kMaxRaw; }

uint64_t normalise_closed_rows(Hierarchy& h, double* mean_row, const std::vector<uint8_t>* unscaled) {
  const auto one = [](const HNode&) { return 1.0; };
  const std::vector<double> raw = row_sums(h, one);
  uint64_t left = 0;
  double area = 0, weighted = 0;
  for (size_t k = 0; k < raw.size(); ++k) {  // sequential: a fixed order of sums
    HNode& n = h.nodes()[k];
    n.balanced = false;  // also on nodes that were leaves in an earlier round
    if (!is_leaf_element(n)) continue;
    n.send = 1.0;
    n.balanced = scalable_row(raw[k]) && !(unscaled && (*unscaled)[k]);
    n.receive = n.balanced ? std::clamp(1.0 / raw[k], kMinFactor, kMaxFactor) : 1.0;
    left += !n.balanced;
    area += n.area;
    weighted += n.area * raw[k];
  }
  if (mean_row) *mean_row = area > 0 ? weighted / area : 1.0;
  return left;
}

struct CorrectionBuffers::Held {
  TransportBuffers<2> t;
  // Per node: what a leaf adds to the correction's three sums (0 elsewhere), made in parallel and
  // summed in node order: the sums of one pass over the nodes, bit for bit (a running sum from +0
  // never is −0, so the zeros change nothing).
  HugeVector<std::array<Vec3, 3>> terms;
};

CorrectionBuffers::CorrectionBuffers() : held(std::make_unique<Held>()) {}
CorrectionBuffers::~CorrectionBuffers() = default;

double aggregation_correction(Hierarchy& h, double floor, double* level, CorrectionBuffers* buffers) {
  std::optional<CorrectionBuffers> own;
  CorrectionBuffers::Held& held = *(buffers ? buffers : &own.emplace())->held;
  HNodes& nodes = h.nodes();
  // At a leaf, b = B and v = B − E − ρD (what the sweeps reflected), read from the node where needed
  // (v from its B before this call changes it): two node-sized arrays fewer.
  const auto reflected = [](const HNode& n) { return n.B - n.emission - mul(n.rho, n.D); };
  const Delivery<2>& d = transport<2>(h, [&](const HNode& n) { return std::array<Vec3, 2>{n.B, reflected(n)}; }, held.t);
  HugeVector<std::array<Vec3, 3>>& terms = held.terms;
  terms.resize(nodes.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) {
      const HNode& n = nodes[k];
      if (!is_leaf_element(n)) {
        terms[k] = {};
        continue;
      }
      const Vec3 tb = leaf_irradiance(n, d.H[k][0], d.row[k]), tv = leaf_irradiance(n, d.H[k][1], d.row[k]);
      const Vec3 v = reflected(n);
      terms[k] = {(n.emission + mul(n.rho, tb + n.D) - n.B) * n.area, (v - mul(n.rho, tv)) * n.area, v * n.area};
    }
  });
  Vec3 num, den, total;
  for (size_t k = 0; k < nodes.size(); ++k) {  // sequential: a fixed order of sums
    num += terms[k][0];
    den += terms[k][1];
    total += terms[k][2];
  }
  Vec3 c;
  for (int k = 0; k < 3; ++k)
    if (den[k] > 1e-12 * total[k] && total[k] > 0) c[k] = std::max(-0.5, num[k] / den[k]);
  if (level) *level = max_component(abs3(c));
  // The largest change, a maximum: the same whichever thread finds it.
  const double largest = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, nodes.size(), 4096), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double most) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
          HNode& n = nodes[k];
          if (!is_leaf_element(n)) continue;
          const Vec3 next = n.B + mul(c, reflected(n));
          const double scale = std::max(max_component(next), floor);
          if (scale > 0) most = std::max(most, max_component(abs3(next - n.B)) / scale);
          n.B = next;
        }
        return most;
      },
      [](double a, double b) { return std::max(a, b); });
  pull_up_radiosity(h);
  return largest;
}

}  // namespace walkrad
