// Limits checked before anything is allocated from what an input file declares (README.md,
// "Limits"): every input is a regular file of bounded size (never a device, a FIFO or a folder,
// which could block or never end), JSON nests at most kMaxJsonDepth deep (tinygltf converts JSON
// recursively: a deeper file would overflow the stack), and the files a scene refers to (glTF buffers,
// images and IES profiles, MGF includes and luminaires) lie inside its input folder: a build farm
// baking many people's assets must not read /etc/passwd into a chunk because a URI said so. A refusal
// names the file and the rule.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace walkrad::input_limits {

constexpr uint64_t kMaxJsonBytes = uint64_t(256) << 20;   // walkthrough, manifest, .gltf text
constexpr uint64_t kMaxBinaryBytes = uint64_t(2) << 30;   // .glb, buffers, MGF files (tinygltf: < 4 GiB)
constexpr int kMaxJsonDepth = 64;                          // glTF needs 8 or so, walkrad's own files 4

// Throws InputError (kExitBadInput) unless `path` is a regular file, and (kExitLimitReached) when it
// is larger than max_bytes. Returns its size. Every reader opens its files after this check, which
// notes each in the ReadLogs alive on the thread (dependencies.h: a bake's depfile).
uint64_t check_regular_file(const std::string& path, uint64_t max_bytes, const std::string& what);

// The whole file, after check_regular_file.
std::vector<unsigned char> read_file(const std::string& path, uint64_t max_bytes, const std::string& what);

// Throws InputError (kExitLimitReached, place "byte N") where arrays and objects nest deeper than
// kMaxJsonDepth. Scans the text only (strings skipped); syntax is left to the parser.
void check_json_depth(const char* text, size_t size, const std::string& file);

// The folder a scene's referenced files must lie in: `given` where it is not empty, else the scene
// file's own folder.
std::string input_folder(const std::string& scene, const std::string& given);

// Empty where `path` lies inside `folder` (both resolved as the file system would: "." and ".." and
// symbolic links followed), else why not, to follow the path in a refusal ("lies outside the input
// folder ..."). Opens nothing, reads no file's bytes.
std::string outside(const std::string& path, const std::string& folder);

}  // namespace walkrad::input_limits
