// What a link's unoccluded form factor costs: the contour formula at a point, and a cluster
// link's polygon pairs integrated pair by pair from scratch (element_to_element on two polygons)
// against the same pairs with each polygon prepared once (ElementEnd, ReceiverPoints), as
// exact_unoccluded runs them. One thread; the sums are the same bits either way (ContourBits tests).
//
//   build/bench/walkrad_form_factor_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <vector>

#include "walkrad/core/sampling.h"
#include "walkrad/formfactor/form_factor.h"

namespace {

using namespace walkrad;

Polygon square(const Vec3& o, double side, bool facing_down) {
  Polygon p;
  p.count = 4;
  p.v[0] = o;
  p.v[1] = o + Vec3{side, 0, 0};
  p.v[2] = o + Vec3{side, side, 0};
  p.v[3] = o + Vec3{0, side, 0};
  if (facing_down) std::swap(p.v[1], p.v[3]);
  return p;
}

// 4,096 unit-ish squares above points of the floor, facing down: the contour formula's common case.
void BM_PointToPolygon(benchmark::State& state) {
  Rng rng(1, 2);
  std::vector<Polygon> polys;
  std::vector<Vec3> points;
  for (int i = 0; i < 4096; ++i) {
    polys.push_back(square({rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, 2 + rng.uniform()}, 0.5, true));
    points.push_back({rng.uniform(), rng.uniform(), 0});
  }
  std::vector<ContourSource> sources(polys.begin(), polys.end());
  const Vec3 up{0, 0, 1};
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(point_to_polygon(points[k & 4095], up, sources[k & 4095]));
    ++k;
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}

// Two clusters of 8 small squares each, a floor's and a ceiling's 0.3 to 1.3 apart, all 64 pairs.
struct ClusterPair {
  std::vector<Polygon> receivers, sources;
  ClusterPair() {
    Rng rng(5, 6);
    for (int i = 0; i < 8; ++i) {
      receivers.push_back(square({rng.uniform() * 2, rng.uniform() * 2, 0}, 0.2, false));
      sources.push_back(square({rng.uniform() * 2, rng.uniform() * 2, 0.3 + rng.uniform()}, 0.2, true));
    }
  }
};

void BM_ClusterPairFromScratch(benchmark::State& state) {
  const ClusterPair c;
  for (auto _ : state) {
    double sum = 0;
    for (const Polygon& r : c.receivers) {
      const double area = polygon_area(r);
      for (const Polygon& s : c.sources) sum += area * element_to_element(r, s);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * 64);  // pairs
}

void BM_ClusterPairPrepared(benchmark::State& state) {
  const ClusterPair c;
  for (auto _ : state) {
    std::vector<ElementEnd> ends;
    for (const Polygon& s : c.sources) ends.emplace_back(s);
    double sum = 0;
    for (const Polygon& r : c.receivers) {
      const ElementEnd receiver(r);
      ReceiverPoints points(r);
      for (size_t k = 0; k < c.sources.size(); ++k)
        sum += receiver.area * element_to_element(receiver, ends[k], points);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * 64);
}

}  // namespace

BENCHMARK(BM_PointToPolygon);
BENCHMARK(BM_ClusterPairFromScratch)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ClusterPairPrepared)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
