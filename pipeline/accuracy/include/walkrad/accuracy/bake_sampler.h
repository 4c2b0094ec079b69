// BakeSampler: what a bake shows along a ray. The bake's chunks (their triangles, with the physical
// radiosity _RADIOSITY per vertex) go into an Embree scene; a ray's first hit gives B interpolated
// across the triangle as a viewer interpolates COLOR_0. Comparing bakes, or a bake against the
// reference tracer, through the same rays measures the error where the walkthrough looks, whatever
// the meshes (docs/accuracy.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "walkrad/formats/chunk.h"
#include "walkrad/visibility/ray_scene.h"

namespace walkrad {

class BakeSampler {
 public:
  explicit BakeSampler(ChunkMesh mesh);
  // Every chunk of the bake folder named by its manifest.json (throws InputError).
  static BakeSampler open(const std::string& bake_dir);

  struct Sample {
    bool hit = false;
    double distance = 0;  // along the (unit) direction
    Vec3 B;               // radiosity, W/m²
  };
  Sample along(const Vec3& origin, const Vec3& unit_direction) const;

  // Luminance of B through each pixel centre of a square grid × grid image of the view, NaN where the
  // ray escapes (rows from the bottom).
  std::vector<double> luminance_image(const Viewpoint& view, int grid) const;

 private:
  ChunkMesh mesh_;
  Scene triangles_;
  std::unique_ptr<RayScene> rays_;
};

}  // namespace walkrad
