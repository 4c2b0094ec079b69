#include "walkrad/output/bake_inspect.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "walkrad/formats/bake_folder.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/visibility/extinction_grid.h"

namespace walkrad {

void inspect_bake(const std::string& folder, const std::string& mesh_json) {
  const Manifest m = read_manifest(folder + "/manifest.json");
  uint64_t triangles = 0, bytes = 0;
  for (const ChunkInfo& c : m.chunks) {
    triangles += c.triangles;
    bytes += c.bytes;
  }
  std::printf("%s: %s, scene %s (hash %s)\n", folder.c_str(), m.tool.c_str(), m.scene_file.c_str(), m.scene_hash.c_str());
  std::printf("  %zu chunks, %llu triangles, %llu bytes, %s, exposure %.4g, %zu viewpoints\n", m.chunks.size(),
              static_cast<unsigned long long>(triangles), static_cast<unsigned long long>(bytes),
              m.settings.value("compress", false) ? "Draco" : "uncompressed", m.exposure, m.viewpoints.size());
  for (const ChunkInfo& c : m.chunks) {
    float seen = 0;
    for (float f : c.importance) seen = std::max(seen, f);
    std::printf("  %s: %llu triangles, %llu bytes, up to %.1f%% of a view\n", c.file.c_str(),
                static_cast<unsigned long long>(c.triangles), static_cast<unsigned long long>(c.bytes), 100.0 * seen);
  }
  const std::string report_path = folder + "/report.json";
  if (std::filesystem::exists(report_path)) {
    std::ifstream in(report_path);
    const nlohmann::json r = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (r.is_object() && r.contains("total_seconds") && r.contains("method"))
      std::printf("  report: %s, %.2f s\n", r["method"].get<std::string>().c_str(), r["total_seconds"].get<double>());
  }
  const std::string vdb = folder + "/extinction.vdb";
  if (std::filesystem::exists(vdb)) {
    const ExtinctionGrid grid = ExtinctionGrid::read(vdb);
    const ExtinctionGrid::Stats g = grid.stats();
    const Vec3 size = g.bounds.diagonal();
    std::printf("  extinction.vdb: %s volume clusters (%s polygons), voxel %.4g m, %llu active voxels over %.3g × %.3g × %.3g m,"
                " kappa %.4g to %.4g 1/m, %llu bytes in memory; rule: objects < %s × penumbra width\n",
                grid.metadata("volume_clusters").c_str(), grid.metadata("volume_polygons").c_str(), g.voxel_size,
                static_cast<unsigned long long>(g.active_voxels), size.x, size.y, size.z, g.kappa_min, g.kappa_max,
                static_cast<unsigned long long>(g.memory_bytes), grid.metadata("penumbra_ratio").c_str());
  }
  if (mesh_json.empty()) return;
  const ChunkMesh mesh = read_bake_mesh(folder);
  const nlohmann::json j = {{"positions", mesh.positions}, {"normals", mesh.normals}, {"colors", mesh.colors},
                            {"radiosity", mesh.radiosity}, {"indices", mesh.indices}};
  std::ofstream out(mesh_json, std::ios::binary);
  out << j.dump() << '\n';
  if (!out) throw OutputError(mesh_json + ": cannot write");
}

}  // namespace walkrad
