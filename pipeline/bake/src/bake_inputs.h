// What a bake reads: the scene, the walkthrough and their hashes. Under mpirun rank 0 alone reads the
// files and sends what it read to the other ranks (ranks.h: broadcast), so that other hosts need
// neither file; every rank then builds the same hierarchy from the same bytes. Private to
// this stage.
#pragma once

#include <string>
#include <vector>

#include "walkrad/bake/bake.h"
#include "walkrad/formats/scene.h"

namespace walkrad::bake_detail {

struct BakeInputs {
  Scene scene;                   // as read, duplicate polygons removed
  std::vector<Viewpoint> views;  // the walkthrough's, or the scene's cameras
  std::string scene_hash, views_hash;  // file_hash.h ("" without --views)
};

// Throws InputError (rank 0: the file and its fault; mpirun then ends the other ranks).
BakeInputs read_bake_inputs(const BakeSettings& s);

// The scene as bytes and back (exact: every number as stored).
std::vector<uint8_t> scene_to_bytes(const Scene& scene, const std::vector<Viewpoint>& views);
void scene_from_bytes(const std::vector<uint8_t>& bytes, Scene& scene, std::vector<Viewpoint>& views);

}  // namespace walkrad::bake_detail
