// The solve's checkpoint on disk: DIR/solve.checkpoint, the state after the last complete
// refinement round (solve_checkpoint.cpp), written by rank 0 under a temporary name and renamed over
// the last one, so that a bake killed at any moment leaves a whole checkpoint or the one before. It
// records the build that wrote it, the scene's and the walkthrough's hashes and the settings, and a
// bake with another of any refuses it. The state streams to and from the file in pieces (never held
// twice); under mpirun rank 0 reads it and sends each piece to the others.
//
// Layout: magic line, key (JSON), rounds done, the state's bytes, their count and checksum.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "walkrad/bake/bake.h"
#include "walkrad/core/byte_buffer.h"

namespace walkrad {

class CheckpointFile {
 public:
  // The scene's and the walkthrough's hashes as read by rank 0 (bake_inputs.h). Nothing is read or
  // written here: with s.checkpoint empty, the other calls must not be made.
  CheckpointFile(const BakeSettings& s, const std::string& scene_hash, const std::string& views_hash);

  std::string path() const;

  // Rank 0 makes the folder and tries a file in it, before the long work (OutputError, exit 5).
  void check_writable() const;

  // Rank 0 writes what write_state puts (the other ranks return at once); throws OutputError.
  void write(int rounds, const std::function<void(ByteWriter&)>& write_state) const;
  // False when there is none. Else the rounds it holds and a reader of its state, which every rank
  // reads alike (ByteFormatError once the last byte is read if the checksum does not match). Throws
  // InputError (exit 3), naming the file, when it is from another build, scene, walkthrough or
  // settings, or damaged.
  bool open(int& rounds, std::unique_ptr<ByteReader>& state) const;
  // After the bake is written (rank 0).
  void remove() const;

 private:
  std::string dir_, key_;
};

}  // namespace walkrad
