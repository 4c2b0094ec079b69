// A large level's bake against its rays: bakes a scene as `walkrad bake` does, keeping a
// sample of the hierarchical solve's Embree rays (RaySample: the links of one (receiver, source) hash
// bucket in `every`), then casts the same sampled rays in a bare loop of rtcOccluded1 calls on as many
// threads (the machine's reference rate), against which the solve's rays per second (all its rays over
// its wall time) are read; and again as the solve casts them, each link's rays in one stream call
// (RayScene::occluded: rtcOccluded1M, coherent), which runs about twice as fast: the machine's limit
// for the solve's rays. Prints one JSON object: the report's phases (seconds,
// peak memory, rays where report.json counts them), the links, the three rates, and each solve round's
// rays per second against the bare loop. bench/large_level.py runs it over office-floor levels and
// prints the tables in docs/performance.md.
//
// walkrad_level_rays_bench SCENE OUT [--views W] [--view-independent] [--threads T] [--every N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_reduce.h>

#include "walkrad/bake/bake.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/hierarchical/hierarchical_solver.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/visibility/ray_scene.h"

namespace {

using namespace walkrad;

// Seconds for one pass of rtcOccluded1 over every segment, on the threads tbb is allowed.
double bare_pass(const RayScene& rays, const std::vector<RayScene::Segment>& segments, size_t& blocked) {
  const auto start = std::chrono::steady_clock::now();
  blocked = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, segments.size(), 4096), size_t(0),
      [&](const tbb::blocked_range<size_t>& r, size_t n) {
        for (size_t k = r.begin(); k != r.end(); ++k) n += rays.occluded(segments[k].from, segments[k].to) ? 1 : 0;
        return n;
      },
      [](size_t a, size_t b) { return a + b; });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The same rays as the solve casts them: each sampled link's segments in one RayScene::occluded call
// (rtcOccluded1M, coherent), the links in parallel.
double batched_pass(const RayScene& rays, const RaySample& sample, size_t& blocked) {
  const std::vector<RayScene::Segment>& segments = sample.segments;
  const std::vector<size_t>& begin = sample.link_begin;
  const auto start = std::chrono::steady_clock::now();
  blocked = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, begin.size(), 64), size_t(0),
      [&](const tbb::blocked_range<size_t>& r, size_t n) {
        std::vector<uint8_t> hit;
        for (size_t k = r.begin(); k != r.end(); ++k) {
          const size_t first = begin[k], last = k + 1 < begin.size() ? begin[k + 1] : segments.size();
          hit.assign(last - first, 0);
          rays.occluded(segments.data() + first, last - first, hit.data());
          for (uint8_t b : hit) n += b;
        }
        return n;
      },
      [](size_t a, size_t b) { return a + b; });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE OUT [--views W] [--view-independent] [--threads T] [--every N]\n", argv[0]);
    return 2;
  }
  BakeSettings s;
  s.scene = argv[1];
  s.output = argv[2];
  s.threads = 2;
  s.progress = false;
  RaySample sample;
  for (int k = 3; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--views" && k + 1 < argc) s.views = argv[++k];
    else if (a == "--view-independent") s.view_independent = true;
    else if (a == "--threads" && k + 1 < argc) s.threads = std::atoi(argv[++k]);
    else if (a == "--every" && k + 1 < argc) sample.every = uint32_t(std::atoi(argv[++k]));
    else {
      std::fprintf(stderr, "unknown argument: %s\n", a.c_str());
      return 2;
    }
  }
  s.ray_sample = &sample;
  try {
    bake(s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walkrad_level_rays_bench: %s\n", e.what());
    return 1;
  }

  nlohmann::json report;
  std::ifstream(s.output + "/report.json") >> report;
  const nlohmann::json& counts = report["counts"];
  // Rays by phase, where report.json counts them.
  const std::pair<const char*, const char*> phase_rays[] = {{"importance", "importance_rays"}, {"exposure", "exposure_rays"},
                                                            {"solve", "visibility_rays"},      {"gather", "gather_test_rays"},
                                                            {"chunks", "chunk_importance_rays"}};
  nlohmann::json phases = nlohmann::json::array();
  double solve_seconds = 0;
  for (const nlohmann::json& p : report["phases"]) {
    nlohmann::json out = {{"name", p["name"]}, {"seconds", p["seconds"]}, {"peak_mb", p["peak_mb"]}};
    for (const auto& [phase, key] : phase_rays)
      if (p["name"] == phase && counts.contains(key)) out["rays"] = counts[key];
    if (p["name"] == "solve") solve_seconds = p["seconds"].get<double>();
    phases.push_back(out);
  }
  const double solve_rays = counts["visibility_rays"].get<double>();

  // The same geometry as the bake's ray scene (bake.cpp: the contact split; office-floor has no
  // transmitting surface, whose twins the bake would add).
  ContactSplitStats split;
  const Scene scene = split_contacts(read_scene(s.scene), split);
  const RayScene rays(scene);
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(std::max(1, s.threads)));
  // Rays per second over the sample, the median of three passes.
  auto rate = [&](auto pass) {
    double seconds[3];
    for (double& t : seconds) t = pass();
    std::sort(seconds, seconds + 3);
    return sample.segments.empty() ? 0.0 : double(sample.segments.size()) / seconds[1];
  };
  size_t blocked = 0, batched_blocked = 0;
  const double bare = rate([&] { return bare_pass(rays, sample.segments, blocked); });
  const double batched = rate([&] { return batched_pass(rays, sample, batched_blocked); });
  const double solve = solve_seconds > 0 ? solve_rays / solve_seconds : 0.0;
  // Each round of the solve against the same bare loop: where its own work outweighs its rays. A round
  // without a time (read back from a checkpoint), or a loop without a rate, gives null, not 0.
  nlohmann::json rounds = nlohmann::json::array();
  for (const nlohmann::json& r : report["solver"]["rounds"]) {
    nlohmann::json per_s, over_bare;
    if (r["seconds"].is_number() && r["seconds"].get<double>() > 0) {
      per_s = r["rays"].get<double>() / r["seconds"].get<double>();
      if (bare > 0) over_bare = per_s.get<double>() / bare;
    }
    rounds.push_back({{"new_links", r["new_links"]}, {"rays", r["rays"]}, {"sweeps", r["sweeps"]}, {"seconds", r["seconds"]},
                      {"rays_per_s", per_s}, {"over_bare", over_bare}});
  }

  const nlohmann::json out = {{"scene", s.scene},
                              {"view_independent", s.view_independent},
                              {"threads", s.threads},
                              {"links", counts["links"]},
                              {"elements", counts["elements"]},
                              {"total_seconds", report["total_seconds"]},
                              {"phases", phases},
                              {"solve_rays", solve_rays},
                              {"solve_rays_per_s", solve},
                              {"sampled_rays", sample.segments.size()},
                              {"sampled_blocked", blocked},
                              {"bare_rays_per_s", bare},
                              {"solve_over_bare", bare > 0 ? solve / bare : 0.0},
                              {"batched_blocked", batched_blocked},
                              {"batched_rays_per_s", batched},
                              {"solve_over_batched", batched > 0 ? solve / batched : 0.0},
                              {"rounds", rounds}};
  std::printf("%s\n", out.dump().c_str());
  return 0;
}
