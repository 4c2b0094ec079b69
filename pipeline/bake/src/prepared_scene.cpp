#include "prepared_scene.h"

#include <cstdio>
#include <filesystem>

#include "walkrad/core/file_hash.h"
#include "walkrad/formats/error.h"
#include "walkrad/core/ranks.h"
#include "walkrad/plan/back_lit.h"
#include "walkrad/plan/lossless_enclosure.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad::bake_detail {

namespace {

Scene split_and_free(BakeInputs& inputs, ContactSplitStats& stats) {
  Scene scene = split_contacts(inputs.scene, stats);
  std::vector<Polygon>().swap(inputs.scene.polygons);
  std::vector<Texture>().swap(inputs.scene.textures);
  return scene;
}

VolumeSettings volume_settings_of(const BakeSettings& s) {
  VolumeSettings vs;
  vs.min_polygons = s.volume_min_polygons;
  vs.penumbra_ratio = s.volume_penumbra_ratio;
  return vs;
}

// A closed scene (no ray escapes) whose surfaces absorb nothing in some channel returns all the light
// at every bounce: refused with the channels named.
void refuse_lossless_enclosure(const Scene& scene, const RayScene& rays, const ClusterTree& tree, const std::string& file) {
  const std::vector<int> lossless = channels_without_absorption(scene);
  if (lossless.empty()) return;
  uint64_t closure_rays = 0, pressed = 0;
  if (!is_closed(scene, rays, closure_rays, pressed, nullptr, &tree)) return;
  static const char* kNames[] = {"red", "green", "blue"};
  std::string which;
  for (int c : lossless) which += std::string(which.empty() ? "" : ", ") + kNames[c];
  throw InputError(file, "", "the scene is closed (no ray escapes) and no surface absorbs light (reflectance + "
                             "transmittance = 1 everywhere, channels: " + which + "): every bounce returns all "
                             "the light, so radiosity has no finite value; give some surface a reflectance below 1");
}

// Lossless polygons closed among themselves with a light inside, anywhere in the scene (a sealed white
// box around a lamp): refused, naming them and the channels, before anything is solved.
void refuse_lit_enclosures(const Scene& scene, const RayScene& rays, const std::vector<uint32_t>& twins,
                           const std::string& file) {
  const std::vector<LosslessEnclosure> found = find_lossless_enclosures(scene, rays, twins);
  for (const LosslessEnclosure& e : found) {
    if (!e.lit) continue;
    static const char* kNames[] = {"red", "green", "blue"};
    std::string channels, lights;
    for (const LosslessEnclosure& same : found)  // the same polygons, lit, in other channels
      if (same.lit && same.polygons == e.polygons) channels += std::string(channels.empty() ? "" : ", ") + kNames[same.channel];
    for (uint32_t l : e.lights) lights += std::string(lights.empty() ? " and light '" : ", '") + scene.lights[l].name + "'";
    throw InputError(file, "", describe_polygons(scene, e.polygons) + lights +
                                   " enclose a light and absorb none of it (reflectance + transmittance = 1 in " + channels +
                                   "): every bounce returns all the light, so radiosity has no finite value there; give "
                                   "one of them a reflectance below 1, or open them");
  }
}

// Most of the light lost on the backs of one-sided polygons: warned (stderr and report.json), not refused.
void warn_back_lit(const Scene& scene, const RayScene& rays, const std::string& file, std::vector<std::string>& warnings) {
  const std::string w = back_lit_warning(scene, light_on_back_faces(scene, rays));
  if (w.empty()) return;
  if (ranks().rank == 0) std::fprintf(stderr, "walkrad: warning: %s: %s\n", file.c_str(), w.c_str());
  warnings.push_back(w);
}

// Identifies what the extinction grid is made from: every polygon's corners and the volume settings
// (FNV-1a 64 over their bytes). A rebake with the same key reuses the grid.
std::string volume_key(const Scene& scene, const VolumeSettings& vs) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto add = [&](const void* data, size_t size) { h = fnv1a(data, size, h); };
  for (const Polygon& p : scene.polygons) {
    add(&p.count, sizeof p.count);
    for (int k = 0; k < p.count; ++k) add(&p.v[size_t(k)], sizeof(Vec3));
  }
  add(&vs.min_polygons, sizeof vs.min_polygons);
  add(&vs.feature_ratio, sizeof vs.feature_ratio);
  add(&vs.small_object, sizeof vs.small_object);
  add(&vs.max_dispersion, sizeof vs.max_dispersion);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace

PreparedScene::PreparedScene(BakeInputs& inputs, const BakeSettings& s)
    : input_polygons(inputs.scene.polygons.size()),
      scene(split_and_free(inputs, split_stats)),
      transmission(plan_transmission(scene, s.method, s.effects)),
      twins(transmission.on ? add_transmission_twins(scene) : std::vector<uint32_t>{}),
      rays(scene),
      tree(build_cluster_tree(scene)),
      volume_settings(volume_settings_of(s)),
      volume_clusters(s.method == Method::hierarchical ? find_volume_clusters(scene, tree, volume_settings) : VolumeClusters{}) {
  refuse_lossless_enclosure(scene, rays, tree, s.scene);
  refuse_lit_enclosures(scene, rays, twins, s.scene);
  warn_back_lit(scene, rays, s.scene, inputs.scene.warnings);
  plan = plan_effects(scene, rays, inputs.views, s.view_independent, s.method, s.effects, &volume_clusters, &tree);
  plan.transmission = transmission;
}

void build_volumes(const PreparedScene& p, const std::string& output, StagedOutput& out, BakeVolumes& v) {
  const VolumeSettings& vs = p.volume_settings;
  const VolumeClusters& clusters = p.volume_clusters;
  const std::string key = volume_key(p.scene, vs);
  const std::string previous = output + "/extinction.vdb";
  bool reused = false;
  if (std::filesystem::exists(previous)) {
    try {
      ExtinctionGrid old = ExtinctionGrid::read(previous);
      if (old.metadata("geometry_key") == key) {
        v.grid = std::move(old);
        reused = true;
      }
    } catch (const InputError& e) {
      std::fprintf(stderr, "walkrad: warning: %s: not reused (%s)\n", previous.c_str(), e.what());
    }
  }
  if (!reused) v.grid = ExtinctionGrid::build(clusters.boxes, ExtinctionGrid::choose_voxel_size(clusters.boxes));
  v.grid.write(out.path("extinction.vdb"), {{"geometry_key", key},
                                            {"volume_clusters", std::to_string(clusters.boxes.size())},
                                            {"volume_polygons", std::to_string(clusters.volume_polygons)},
                                            {"min_polygons", std::to_string(vs.min_polygons)},
                                            {"feature_ratio", nlohmann::json(vs.feature_ratio).dump()},
                                            {"penumbra_ratio", nlohmann::json(vs.penumbra_ratio).dump()}});
  v.solid = std::make_unique<RayScene>(p.scene, clusters.polygon_in_volume);
  v.visibility = {&clusters, &v.grid, v.solid.get(), vs.penumbra_ratio};
  const ExtinctionGrid::Stats gs = v.grid.stats();
  v.report = {{"on", true}, {"grid", reused ? "reused" : "built"}, {"file", "extinction.vdb"},
              {"clusters", clusters.boxes.size()}, {"polygons", clusters.volume_polygons},
              {"voxel_size_m", gs.voxel_size}, {"active_voxels", gs.active_voxels}, {"kappa_max", gs.kappa_max},
              {"min_polygons", vs.min_polygons}, {"feature_ratio", vs.feature_ratio},
              {"penumbra_ratio", vs.penumbra_ratio}};
}

}  // namespace walkrad::bake_detail
