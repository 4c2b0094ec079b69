// What a sweep does in a divided solve (sweeps.h, division.h, docs/scaling.md): each rank gathers the
// receivers whose links it keeps and sends every node's gather to the others; importance is shot in
// exact units so that its sums are the same whatever rank adds which link (Division::divisible).
#include "sweeps.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "walkrad/core/ranks.h"
#include "walkrad/hierarchical/hierarchy.h"

namespace walkrad::hierarchical_detail {

void Sweeps::share_gathered() {
  struct Gathered {
    Vec3 H, Hp;
    double Fsum, Fp;
  };
  share_element_values<Gathered>(
      h_, [&](uint32_t i) { const HNode& n = h_[i]; return Gathered{n.H, n.Hp, n.Fsum, n.Fp}; },
      [&](uint32_t i, const Gathered& g) {
        HNode& n = h_[i];
        n.H = g.H;
        n.Hp = g.Hp;
        n.Fsum = g.Fsum;
        n.Fp = g.Fp;
      });
}

void Sweeps::shoot_importance_exactly() {
  HNodes& nodes = h_.nodes();
  // Each link's importance ρ_i F_ij I_i to its source, in units of 2^-k of a bound on the total (the
  // sum of their sizes, node by node in order: the same bound on every rank), as integers.
  // Cluster receivers' links are on every rank: rank 0 adds them (counts_links).
  std::vector<double> size(nodes.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const HNode& n = nodes[i];
      double sum = 0;
      for (const Link& l : n.links) sum += std::fabs(luminance(n.rho) * l.F * n.I);
      size[i] = sum;
    }
  });
  share_element_values(h_, size);
  double bound = 0;
  for (double v : size) bound += v;
  std::vector<double>().swap(size);
  for (HNode& n : nodes) n.Ig = 0;
  if (!(bound > 0) || !std::isfinite(bound)) return;
  // |Σ| < 2^60 + a half-unit a link: far inside 64 bits.
  const double unit = std::ldexp(1.0, 60 - (std::ilogb(bound) + 1));
  std::vector<int64_t> sum(nodes.size(), 0);
  for (uint32_t i = 0; i < nodes.size(); ++i)  // sequential: no two threads add to one source
    if (counts_links(h_, i))
      for (const Link& l : nodes[i].links)
        for_each_part(h_, l, [&](uint32_t part, double w) {
          sum[part] += std::llround(luminance(nodes[i].rho) * l.F * nodes[i].I * w * unit);
        });
  if (division_.divided) all_sum(sum.data(), sum.size());
  const double back = 1.0 / unit;  // a power of 2: exact
  for (size_t k = 0; k < nodes.size(); ++k) nodes[k].Ig = double(sum[k]) * back;
}

}  // namespace walkrad::hierarchical_detail
