#include "walkrad/pipeline/form_factor_matrix.h"

#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/pipeline/formfactor.h"
#include "walkrad/pipeline/sampling.h"
#include "walkrad/pipeline/shaft.h"

namespace walkrad {

namespace {

struct Row {
  std::vector<uint32_t> column;
  std::vector<double> value;
  uint64_t pairs = 0, unoccluded = 0, rays = 0;
};

// True when some part of b lies strictly in front of a's plane.
bool any_in_front(const Element& a, const Element& b) {
  for (int k = 0; k < b.shape.count; ++k)
    if (dot(b.shape.v[k] - a.centroid, a.normal) > 1e-12 * std::sqrt(a.area)) return true;
  return false;
}

double element_size(const Element& e) { return std::sqrt(e.area); }

class RowComputer {
 public:
  RowComputer(const Subdivision& sub, const RayScene* rays, const ClusterTree* tree, const FormFactorSettings& s)
      : sub_(sub), rays_(rays && s.visibility ? rays : nullptr), tree_(tree), s_(s) {}

  Row compute(uint32_t i) {
    Row row;
    const Element& ri = sub_.elements[i];
    polygon_candidates_.assign(sub_.first_element.size() - 1, {});
    known_.assign(sub_.first_element.size() - 1, false);
    for (uint32_t j = 0; j < sub_.elements.size(); ++j) {
      const Element& sj = sub_.elements[j];
      if (sj.polygon == ri.polygon) continue;  // one planar polygon never sees itself
      if (!any_in_front(ri, sj) || !any_in_front(sj, ri)) continue;
      ++row.pairs;
      const bool need_rays = rays_ && may_be_occluded(ri, sj);
      if (rays_ && !need_rays) ++row.unoccluded;
      const double sum = integrate(i, j, need_rays, row.rays);
      if (sum > 0) {
        row.column.push_back(j);
        row.value.push_back(sum / ri.area);
      }
    }
    return row;
  }

 private:
  // Shaft culling: the candidates between the two input polygons (computed once per row and
  // source polygon), filtered by the two elements' own shaft.
  bool may_be_occluded(const Element& ri, const Element& sj) {
    if (!tree_) return true;
    const uint32_t pi = ri.polygon, pj = sj.polygon;
    if (!known_[pj]) {
      polygon_candidates_[pj] = shaft_candidates(*tree_, Shaft(tree_->polygon_bounds[pi], tree_->polygon_bounds[pj]), pi, pj);
      known_[pj] = true;
    }
    const std::vector<uint32_t>& parent = polygon_candidates_[pj];
    if (parent.empty()) return false;
    const Shaft shaft(polygon_bounds(ri.shape), polygon_bounds(sj.shape));
    for (uint32_t p : parent)
      if (shaft.overlaps(tree_->polygon_bounds[p])) return true;
    return false;
  }

  // Σ_q w_q F_{dA_q → j} V_q over the receiver's quadrature points (× A_i).
  double integrate(uint32_t i, uint32_t j, bool need_rays, uint64_t& ray_count) {
    const Element& ri = sub_.elements[i];
    const Element& sj = sub_.elements[j];
    const int order = quadrature_order(length(ri.centroid - sj.centroid), element_size(ri), element_size(sj));
    Rng rng(i, j);
    const int k = std::max(1, s_.rays_per_point);
    points_.clear();
    segments_.clear();
    for (const QuadraturePoint& q : quadrature_points(ri.shape, order)) {
      if (dot(q.position - sj.centroid, sj.normal) <= 0) continue;  // sees the source's back
      const double f = point_to_polygon(q.position, ri.normal, sj.shape);
      if (f <= 0) continue;
      points_.push_back(q.weight * f);
      if (!need_rays) continue;
      const Vec3 from = q.position + ri.normal * rays_->offset();
      for (int r = 0; r < k; ++r)
        segments_.push_back({from, sample_polygon(sj.shape, rng.uniform(), rng.uniform()) + sj.normal * rays_->offset()});
    }
    if (!need_rays) {
      double sum = 0;
      for (double w : points_) sum += w;
      return sum;
    }
    blocked_.resize(segments_.size());
    rays_->occluded(segments_.data(), segments_.size(), blocked_.data());
    ray_count += segments_.size();
    double sum = 0;
    for (size_t p = 0; p < points_.size(); ++p) {
      int open = 0;
      for (int r = 0; r < k; ++r) open += blocked_[p * k + r] ? 0 : 1;
      sum += points_[p] * open / k;
    }
    return sum;
  }

  const Subdivision& sub_;
  const RayScene* rays_;
  const ClusterTree* tree_;
  const FormFactorSettings& s_;
  std::vector<std::vector<uint32_t>> polygon_candidates_;
  std::vector<bool> known_;
  std::vector<double> points_;
  std::vector<RayScene::Segment> segments_;
  std::vector<uint8_t> blocked_;
};

}  // namespace

double FormFactorMatrix::row_sum(size_t i) const {
  double sum = 0;
  for (uint64_t k = row_start[i]; k < row_start[i + 1]; ++k) sum += value[k];
  return sum;
}

FormFactorMatrix compute_form_factors(const Subdivision& sub, const RayScene* rays, const ClusterTree* tree,
                                      const FormFactorSettings& settings, FormFactorCounts& counts,
                                      const std::function<void(size_t)>& progress) {
  const size_t n = sub.elements.size();
  std::vector<Row> rows(n);
  std::atomic<size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16), [&](const tbb::blocked_range<size_t>& r) {
    RowComputer computer(sub, rays, tree, settings);
    for (size_t i = r.begin(); i != r.end(); ++i) rows[i] = computer.compute(uint32_t(i));
    const size_t d = done += r.size();
    if (progress) progress(d);
  });

  // Concatenate in row order: the result is the same whatever the thread count.
  FormFactorMatrix m;
  m.row_start.reserve(n + 1);
  m.row_start.push_back(0);
  for (Row& row : rows) {
    m.column.insert(m.column.end(), row.column.begin(), row.column.end());
    m.value.insert(m.value.end(), row.value.begin(), row.value.end());
    m.row_start.push_back(m.column.size());
    counts.pairs += row.pairs;
    counts.unoccluded += row.unoccluded;
    counts.rays += row.rays;
    row = Row{};
  }
  counts.nonzero = m.column.size();
  return m;
}

}  // namespace walkrad
