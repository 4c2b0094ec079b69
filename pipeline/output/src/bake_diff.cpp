#include "walkrad/output/bake_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/manifest.h"

namespace walkrad {

namespace {

std::string format(const char* fmt, double a, double b) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

Vec3 at(const std::vector<float>& v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

void diff_manifests(const Manifest& a, const Manifest& b, const DiffSettings& s, BakeDiff& d) {
  uint64_t ta = 0, tb = 0;
  for (const ChunkInfo& c : a.chunks) ta += c.triangles;
  for (const ChunkInfo& c : b.chunks) tb += c.triangles;
  if (a.chunks.size() != b.chunks.size())
    d.differences.push_back(format("chunks: %.0f in A, %.0f in B", double(a.chunks.size()), double(b.chunks.size())));
  if (ta != tb) d.differences.push_back(format("triangles: %.0f in A, %.0f in B", double(ta), double(tb)));
  if (a.viewpoints.size() != b.viewpoints.size())
    d.differences.push_back(format("viewpoints: %.0f in A, %.0f in B", double(a.viewpoints.size()), double(b.viewpoints.size())));
  if (std::fabs(a.exposure - b.exposure) > s.tolerance * std::fabs(a.exposure))
    d.differences.push_back(format("exposure: %.6g in A, %.6g in B", a.exposure, b.exposure));
  if (a.scene_hash != b.scene_hash) d.differences.push_back("scene: the input files differ (hash " + a.scene_hash + " / " + b.scene_hash + ")");
  if (a.scene_file != b.scene_file) d.notes.push_back("scene path: " + a.scene_file + " / " + b.scene_file);
  if (a.tool != b.tool) d.notes.push_back("tool: " + a.tool + " / " + b.tool);
  for (const auto& [key, value] : a.settings.items())
    if (!b.settings.contains(key) || b.settings[key] != value)
      d.differences.push_back("setting " + key + ": " + value.dump() + " in A, " +
                              (b.settings.contains(key) ? b.settings[key].dump() : "absent") + " in B");
  for (const auto& [key, value] : b.settings.items())
    if (!a.settings.contains(key)) d.differences.push_back("setting " + key + ": absent in A, " + value.dump() + " in B");
}

}  // namespace

BakeDiff diff_bakes(const std::string& a_dir, const std::string& b_dir, const DiffSettings& s) {
  BakeDiff d;
  diff_manifests(read_manifest(a_dir + "/manifest.json"), read_manifest(b_dir + "/manifest.json"), s, d);
  const ChunkMesh a = read_bake_mesh(a_dir), b = read_bake_mesh(b_dir);
  d.vertices_a = a.vertex_count();
  d.vertices_b = b.vertex_count();
  if (d.vertices_a != d.vertices_b)
    d.differences.push_back(format("vertices: %.0f in A, %.0f in B", double(d.vertices_a), double(d.vertices_b)));

  // B's vertices in cells of the position tolerance; a match is within it, in one of 27 cells.
  const double tol = s.position_tolerance * std::max(length(a.bounds().diagonal()), 1e-30);
  using Key = std::tuple<int64_t, int64_t, int64_t>;
  auto key = [&](const Vec3& p) { return Key(int64_t(std::floor(p.x / tol)), int64_t(std::floor(p.y / tol)), int64_t(std::floor(p.z / tol))); };
  std::map<Key, std::vector<size_t>> cells;
  for (size_t v = 0; v < b.vertex_count(); ++v) cells[key(at(b.positions, v))].push_back(v);
  double num = 0, den = 0, largest = 0, a_max = 0;
  for (size_t v = 0; v < a.vertex_count(); ++v) a_max = std::max(a_max, luminance(at(a.radiosity, v)));
  for (size_t v = 0; v < a.vertex_count(); ++v) {
    const Vec3 p = at(a.positions, v), n = at(a.normals, v);
    const auto [cx, cy, cz] = key(p);
    // The nearest vertex facing the same way; among equally near ones (two materials meeting in one
    // plane have a vertex each at the same place), the one with the nearest radiosity.
    size_t match = SIZE_MAX;
    double best = tol, best_b = INFINITY;
    for (int64_t dz = -1; dz <= 1; ++dz)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find(Key(cx + dx, cy + dy, cz + dz));
          if (it == cells.end()) continue;
          for (size_t w : it->second) {
            const double dist = length(at(b.positions, w) - p);
            if (dist > best || dot(at(b.normals, w), n) <= 0.99) continue;
            const double db = length(at(b.radiosity, w) - at(a.radiosity, v));
            if (dist < best || db < best_b) {
              best = dist;
              best_b = db;
              match = w;
            }
          }
        }
    if (match == SIZE_MAX) {
      ++d.unmatched;
      continue;
    }
    const Vec3 diff = at(a.radiosity, v) - at(b.radiosity, match);
    num += dot(diff, diff);
    den += dot(at(a.radiosity, v), at(a.radiosity, v));
    largest = std::max({largest, std::fabs(diff.x), std::fabs(diff.y), std::fabs(diff.z)});
  }
  d.radiosity_rms = den > 0 ? std::sqrt(num / den) : 0;
  d.radiosity_max = a_max > 0 ? largest / a_max : largest;
  if (d.unmatched)
    d.differences.push_back(format("geometry: %.0f of %.0f vertices of A have no vertex of B at their place", double(d.unmatched),
                                   double(d.vertices_a)));
  if (d.radiosity_rms > s.tolerance)
    d.differences.push_back(format("radiosity: relative RMS difference %.3g (tolerance %.3g)", d.radiosity_rms, s.tolerance));
  if (d.radiosity_max > 10 * s.tolerance)
    d.differences.push_back(format("radiosity: largest difference %.3g of the largest radiosity (tolerance %.3g)", d.radiosity_max,
                                   10 * s.tolerance));
  return d;
}

}  // namespace walkrad
