// Visibility throughput: rays per second of the form factor stage's visibility against a bare
// loop of rtcOccluded1 calls on the very same rays (the machine's limit), and against Embree's stream
// interface alone. One thread throughout, so the figures compare like with like.
//
// Stage cost = time(form factors with visibility) − time(form factors without): what visibility adds,
// sample generation, shaft culling and batching included. bench/visibility.sh turns the medians into
// the table in docs/performance.md.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "walkrad/formats/gltf_reader.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/classic/form_factor_matrix.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/classic/subdivision.h"

namespace {

using namespace walkrad;

struct Fixture {
  Scene scene;
  Subdivision sub;
  std::unique_ptr<RayScene> rays;
  ClusterTree tree;
  std::vector<RayScene::Segment> segments;

  Fixture() {
    ContactSplitStats split;
    scene = split_contacts(read_scene(WALKRAD_SOURCE_DIR "/examples/cornell-box/cornell-box.gltf"), split);
    sub = subdivide_uniform(scene, 0.04);
    rays = std::make_unique<RayScene>(scene);
    tree = build_cluster_tree(scene);
    FormFactorSettings s;
    s.record = &segments;
    FormFactorCounts counts;
    compute_form_factors(sub, rays.get(), &tree, s, counts);
  }
};

Fixture& fixture() {
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  static Fixture f;
  return f;
}

void BM_BareOccluded1Loop(benchmark::State& state) {
  Fixture& f = fixture();
  size_t blocked = 0;
  for (auto _ : state)
    for (const RayScene::Segment& s : f.segments) blocked += f.rays->occluded(s.from, s.to) ? 1 : 0;
  benchmark::DoNotOptimize(blocked);
  state.SetItemsProcessed(int64_t(state.iterations() * f.segments.size()));
  state.counters["rays"] = double(f.segments.size());
}

void BM_StreamOccluded1M(benchmark::State& state) {
  Fixture& f = fixture();
  std::vector<uint8_t> blocked(f.segments.size());
  for (auto _ : state) f.rays->occluded(f.segments.data(), f.segments.size(), blocked.data());
  benchmark::DoNotOptimize(blocked.data());
  state.SetItemsProcessed(int64_t(state.iterations() * f.segments.size()));
}

void BM_FormFactors(benchmark::State& state) {
  Fixture& f = fixture();
  FormFactorSettings s;
  s.visibility = state.range(0) != 0;
  uint64_t rays = 0;
  for (auto _ : state) {
    FormFactorCounts counts;
    benchmark::DoNotOptimize(compute_form_factors(f.sub, f.rays.get(), &f.tree, s, counts));
    rays = counts.rays;
  }
  state.counters["rays"] = double(rays);
  state.counters["elements"] = double(f.sub.elements.size());
}

BENCHMARK(BM_BareOccluded1Loop)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StreamOccluded1M)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FormFactors)->Arg(0)->Arg(1)->ArgName("visibility")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
