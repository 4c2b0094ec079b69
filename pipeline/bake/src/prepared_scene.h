// The bake's steps between reading and solving (bake.cpp): the scene as the methods take it, and the
// extinction grid its volume clusters need. Plain data handed on to the method's run. Private to this stage.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake_inputs.h"
#include "walkrad/bake/bake.h"
#include "walkrad/core/staged_output.h"
#include "walkrad/plan/effect_plan.h"
#include "walkrad/scene/cluster_tree.h"
#include "walkrad/scene/contact_split.h"
#include "walkrad/visibility/extinction_grid.h"
#include "walkrad/visibility/ray_scene.h"
#include "walkrad/visibility/volume_clusters.h"
#include "walkrad/visibility/volume_visibility.h"

namespace walkrad::bake_detail {

// The "prepare" phase: contacts split (contact_split.h), transmission's twins added, the rays, the
// cluster tree and the volume clusters built on that geometry, and the effects the scene calls for.
// Transmission is decided first: its twins (back faces) are geometry, in the rays and the tree.
struct PreparedScene {
  size_t input_polygons = 0;
  ContactSplitStats split_stats;
  Scene scene;
  Effect transmission;
  std::vector<uint32_t> twins;  // transmission_twins.h (empty when transmission is off)
  RayScene rays;
  ClusterTree tree;
  VolumeSettings volume_settings;
  VolumeClusters volume_clusters;  // empty for the classic method
  EffectPlan plan;

  // The input's polygons and textures are freed once split (the split scene holds copies). Throws
  // InputError for a closed scene that absorbs nothing in some channel (radiosity has no finite value).
  PreparedScene(BakeInputs& inputs, const BakeSettings& s);
};

// The "volumes" phase (when the plan turns volumes on): the extinction grid, reused from the previous
// bake in the output folder when made from the same geometry and settings, else rasterised, and
// written to the staged output; the solid scene without the volumes' polygons; the report's entry.
struct BakeVolumes {
  ExtinctionGrid grid;
  std::unique_ptr<RayScene> solid;
  VolumeVisibility visibility;  // points into grid and solid: a BakeVolumes is filled in place
  nlohmann::json report;
};
void build_volumes(const PreparedScene& p, const std::string& output, StagedOutput& out, BakeVolumes& v);

}  // namespace walkrad::bake_detail
