#include "walkrad/pipeline/form_factor_matrix.h"

#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>

#include "walkrad/pipeline/formfactor.h"
#include "walkrad/pipeline/sampling.h"

namespace walkrad {

namespace {

struct Row {
  std::vector<uint32_t> column;
  std::vector<double> value;
  uint64_t pairs = 0, rays = 0;
};

// True when some part of b lies strictly in front of a's plane.
bool any_in_front(const Element& a, const Element& b) {
  for (int k = 0; k < b.shape.count; ++k)
    if (dot(b.shape.v[k] - a.centroid, a.normal) > 1e-12 * std::sqrt(a.area)) return true;
  return false;
}

double element_size(const Element& e) { return std::sqrt(e.area); }

Row compute_row(const Subdivision& sub, uint32_t i, const RayScene* rays, const FormFactorSettings& s) {
  Row row;
  const Element& ri = sub.elements[i];
  for (uint32_t j = 0; j < sub.elements.size(); ++j) {
    const Element& sj = sub.elements[j];
    if (sj.polygon == ri.polygon) continue;  // one planar polygon never sees itself
    if (!any_in_front(ri, sj) || !any_in_front(sj, ri)) continue;
    ++row.pairs;
    const int order = quadrature_order(length(ri.centroid - sj.centroid), element_size(ri), element_size(sj));
    Rng rng(i, j);
    double sum = 0.0;
    for (const QuadraturePoint& q : quadrature_points(ri.shape, order)) {
      if (dot(q.position - sj.centroid, sj.normal) <= 0) continue;  // sees the source's back
      const double f = point_to_polygon(q.position, ri.normal, sj.shape);
      if (f <= 0) continue;
      double visible = 1.0;
      if (rays && s.visibility) {
        const Vec3 from = q.position + ri.normal * rays->offset();
        int open = 0;
        for (int k = 0; k < s.rays_per_point; ++k) {
          const Vec3 to = sample_polygon(sj.shape, rng.uniform(), rng.uniform()) + sj.normal * rays->offset();
          open += rays->occluded(from, to) ? 0 : 1;
        }
        row.rays += uint64_t(s.rays_per_point);
        visible = double(open) / s.rays_per_point;
      }
      sum += q.weight * f * visible;
    }
    if (sum > 0) {
      row.column.push_back(j);
      row.value.push_back(sum / ri.area);
    }
  }
  return row;
}

}  // namespace

double FormFactorMatrix::row_sum(size_t i) const {
  double sum = 0;
  for (uint64_t k = row_start[i]; k < row_start[i + 1]; ++k) sum += value[k];
  return sum;
}

FormFactorMatrix compute_form_factors(const Subdivision& sub, const RayScene* rays, const FormFactorSettings& settings,
                                      FormFactorCounts& counts, const std::function<void(size_t)>& progress) {
  const size_t n = sub.elements.size();
  std::vector<Row> rows(n);
  std::atomic<size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) rows[i] = compute_row(sub, uint32_t(i), rays, settings);
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
    counts.rays += row.rays;
    row = Row{};
  }
  counts.nonzero = m.column.size();
  return m;
}

}  // namespace walkrad
