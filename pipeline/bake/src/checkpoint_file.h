// The solve's checkpoint on disk (issue 28): DIR/solve.checkpoint, the state after the last complete
// refinement round (solve_checkpoint.cpp), written by rank 0 under a temporary name and renamed over
// the last one, so that a bake killed at any moment leaves a whole checkpoint or the one before. It
// records the build that wrote it, the scene's and the walkthrough's hashes and the settings, and a
// bake with another of any refuses it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "walkrad/bake/bake.h"

namespace walkrad {

class CheckpointFile {
 public:
  // The scene's and the walkthrough's hashes as read by rank 0 (bake_inputs.h). Nothing is read or
  // written here: with s.checkpoint empty, the other calls must not be made.
  CheckpointFile(const BakeSettings& s, const std::string& scene_hash, const std::string& views_hash);

  std::string path() const;

  // Rank 0 writes (others return at once); throws OutputError.
  void write(int rounds, const std::vector<uint8_t>& state) const;
  // Rank 0 reads and every rank gets the state (ranks.h: broadcast). False when there is none;
  // InputError (exit 3) naming the file when it is from another build, scene, walkthrough or
  // settings, or damaged.
  bool read(int& rounds, std::vector<uint8_t>& state) const;
  // After the bake is written (rank 0).
  void remove() const;

 private:
  std::string dir_, key_;
};

}  // namespace walkrad
