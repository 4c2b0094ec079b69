#include "walkrad/classic/form_factor_matrix.h"

#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/formfactor/form_factor.h"
#include "walkrad/formfactor/hemicube.h"
#include "walkrad/core/sampling.h"
#include "walkrad/visibility/shaft.h"
#include "walkrad/core/rounding.h"

namespace walkrad {

namespace {

struct Row {
  std::vector<uint32_t> column;
  std::vector<double> value;
  uint64_t pairs = 0, unoccluded = 0, rays = 0;
  std::vector<RayScene::Segment> recorded;  // only with FormFactorSettings::record
};

// True when some part of b lies strictly in front of a's plane (beyond rounding: coincident faces,
// a lamp flush with a ceiling, stay out of each other's view wherever the scene lies).
bool any_in_front(const Element& a, const Element& b) {
  const double tol = 1e-12 * std::sqrt(a.area) + rounding_at(a.centroid);
  for (int k = 0; k < b.shape.count; ++k)
    if (dot(b.shape.v[k] - a.centroid, a.normal) > tol) return true;
  return false;
}

double element_size(const Element& e) { return std::sqrt(e.area); }

class RowComputer {
 public:
  RowComputer(const Subdivision& sub, const RayScene* rays, const ClusterTree* tree, const FormFactorSettings& s)
      : sub_(sub), rays_(rays && s.visibility ? rays : nullptr), tree_(tree), s_(s) {}

  // Two passes: gather every pair's quadrature weights and visibility segments, cast the whole row's
  // rays in one stream (rtcOccluded1M on thousands of rays, not a handful per pair), then sum.
  Row compute(uint32_t i) {
    Row row;
    const Element& ri = sub_.elements[i];
    const size_t polygons = sub_.first_element.size() - 1;
    if (ri.polygon != cached_polygon_) {  // rows of one polygon are contiguous: share its lists
      polygon_candidates_.assign(polygons, {});
      polygon_known_.assign(polygons, false);
      cached_polygon_ = ri.polygon;
    }
    state_.assign(polygons, kUnknown);
    receiver_bounds_ = polygon_bounds(ri.shape);
    pairs_.clear();
    weights_.clear();
    segments_.clear();
    for (uint32_t j = 0; j < sub_.elements.size(); ++j) {
      const Element& sj = sub_.elements[j];
      if (sj.polygon == ri.polygon) continue;  // one planar polygon never sees itself
      if (!any_in_front(ri, sj) || !any_in_front(sj, ri)) continue;
      ++row.pairs;
      const bool need_rays = rays_ && may_be_occluded(ri, sj.polygon);
      if (rays_ && !need_rays) ++row.unoccluded;
      gather(i, j, need_rays);
    }

    blocked_.resize(segments_.size());
    if (!segments_.empty()) rays_->occluded(segments_.data(), segments_.size(), blocked_.data());
    row.rays += segments_.size();
    if (s_.record) row.recorded.insert(row.recorded.end(), segments_.begin(), segments_.end());

    const int k = std::max(1, s_.rays_per_point);
    for (const PairWork& p : pairs_) {
      double sum = 0;
      for (uint32_t q = 0; q < p.points; ++q) {
        double visible = 1.0;
        if (p.rays) {
          int open = 0;
          for (int r = 0; r < k; ++r) open += blocked_[p.first_segment + size_t(q) * k + r] ? 0 : 1;
          visible = double(open) / k;
        }
        sum += weights_[p.first_point + q] * visible;
      }
      if (sum > 0) {
        row.column.push_back(p.source);
        row.value.push_back(sum / ri.area);
      }
    }
    return row;
  }

 private:
  enum : uint8_t { kUnknown, kOpen, kMaybeBlocked };

  // Shaft culling at two levels: the candidates between the two input polygons (once per receiver
  // polygon and source polygon), filtered by the shaft from this receiver element to the source
  // polygon (once per row and source polygon). Element-to-element shafts would cull a little more
  // but cost more than the rays they save.
  bool may_be_occluded(const Element& ri, uint32_t pj) {
    if (!tree_) return true;
    if (state_[pj] == kUnknown) {
      const uint32_t pi = ri.polygon;
      if (!polygon_known_[pj]) {
        polygon_candidates_[pj] = shaft_candidates(*tree_, Shaft(tree_->polygon_bounds[pi], tree_->polygon_bounds[pj]), pi, pj);
        polygon_known_[pj] = true;
      }
      bool blocked = false;
      if (!polygon_candidates_[pj].empty()) {
        const Shaft shaft(receiver_bounds_, tree_->polygon_bounds[pj]);
        for (uint32_t p : polygon_candidates_[pj])
          if ((blocked = shaft.overlaps(tree_->polygon_bounds[p]))) break;
      }
      state_[pj] = blocked ? kMaybeBlocked : kOpen;
    }
    return state_[pj] == kMaybeBlocked;
  }

  // One pair's quadrature points (weight w_q F_{dA_q → j}) and, if needed, k segments from each
  // point to stratified points of the source, offset off both surfaces.
  void gather(uint32_t i, uint32_t j, bool need_rays) {
    const Element& ri = sub_.elements[i];
    const Element& sj = sub_.elements[j];
    const int order = quadrature_order(length(ri.centroid - sj.centroid), element_size(ri), element_size(sj));
    Rng rng(i, j);
    const int k = std::max(1, s_.rays_per_point);
    PairWork p{j, weights_.size(), segments_.size(), 0, need_rays};
    for (const QuadraturePoint& q : quadrature_points(ri.shape, order)) {
      if (dot(q.position - sj.centroid, sj.normal) <= 0) continue;  // sees the source's back
      const double f = point_to_polygon(q.position, ri.normal, sj.shape);
      if (f <= 0) continue;
      weights_.push_back(q.weight * f);
      ++p.points;
      if (!need_rays) continue;
      const Vec3 from = q.position + ri.normal * rays_->offset();
      for (int r = 0; r < k; ++r) {
        const double v = rng.uniform(), u = rng.uniform();  // named: argument order is unspecified (GCC's kept)
        segments_.push_back({from, sample_polygon(sj.shape, u, v) + sj.normal * rays_->offset()});
      }
    }
    if (p.points) pairs_.push_back(p);
  }

  struct PairWork {
    uint32_t source;
    size_t first_point, first_segment;
    uint32_t points;
    bool rays;
  };

  const Subdivision& sub_;
  const RayScene* rays_;
  const ClusterTree* tree_;
  const FormFactorSettings& s_;
  std::vector<std::vector<uint32_t>> polygon_candidates_;  // for cached_polygon_ as receiver
  std::vector<bool> polygon_known_;
  uint32_t cached_polygon_ = UINT32_MAX;
  std::vector<uint8_t> state_;  // per source polygon, for the current row
  Bounds receiver_bounds_;
  std::vector<PairWork> pairs_;
  std::vector<double> weights_;
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
  std::vector<Polygon> shapes;
  if (settings.hemicube > 0)
    for (const Element& e : sub.elements) shapes.push_back(e.shape);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16), [&](const tbb::blocked_range<size_t>& r) {
    RowComputer computer(sub, rays, tree, settings);
    for (size_t i = r.begin(); i != r.end(); ++i) {
      if (settings.hemicube > 0) {
        // From the centroid, every element at once; its own plane's elements are edge-on (0).
        const Element& e = sub.elements[i];
        const std::vector<double> f = hemicube_form_factors(e.centroid, e.normal, shapes, settings.hemicube);
        for (uint32_t j = 0; j < n; ++j)
          if (j != i && f[j] > 0) {
            rows[i].column.push_back(j);
            rows[i].value.push_back(f[j]);
          }
        rows[i].pairs = rows[i].column.size();
        continue;
      }
      rows[i] = computer.compute(uint32_t(i));
    }
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
    if (settings.record) settings.record->insert(settings.record->end(), row.recorded.begin(), row.recorded.end());
    row = Row{};
  }
  counts.nonzero = m.column.size();
  return m;
}

}  // namespace walkrad
