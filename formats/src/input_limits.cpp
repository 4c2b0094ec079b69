#include "input_limits.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "walkrad/formats/dependencies.h"
#include "walkrad/formats/error.h"

namespace walkrad::input_limits {

uint64_t check_regular_file(const std::string& path, uint64_t max_bytes, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(path, "", "cannot open " + what + " (no such file)");
  if (!fs::is_regular_file(st)) throw InputError(path, "", "cannot open " + what + " (not a regular file)");
  const uint64_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "", "cannot open " + what + " (" + ec.message() + ")");
  if (size > max_bytes)
    throw InputError(path, "", what + " of " + std::to_string(size) + " bytes exceeds the limit of " +
                               std::to_string(max_bytes) + " bytes", kExitLimitReached);
  ReadLog::note(path);  // what the bake depends on (its --depfile)
  return size;
}

std::vector<unsigned char> read_file(const std::string& path, uint64_t max_bytes, const std::string& what) {
  const uint64_t size = check_regular_file(path, max_bytes, what);
  std::vector<unsigned char> bytes(size);
  std::ifstream in(path, std::ios::binary);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw InputError(path, "", "cannot read " + what);
  return bytes;
}

void check_json_depth(const char* text, size_t size, const std::string& file) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(file, "byte " + std::to_string(i), "JSON nests deeper than " + std::to_string(kMaxJsonDepth) +
                                                                " arrays and objects", kExitLimitReached);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

std::string input_folder(const std::string& scene, const std::string& given) {
  if (!given.empty()) return given;
  const std::string parent = std::filesystem::path(scene).parent_path().string();
  return parent.empty() ? "." : parent;
}

std::string outside(const std::string& path, const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  if (ec) return "the input folder '" + folder + "' cannot be resolved (" + ec.message() + ")";
  const fs::path target = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return "cannot be resolved (" + ec.message() + ")";
  auto r = root.begin(), t = target.begin();
  for (; r != root.end() && t != target.end() && *r == *t; ++r, ++t) {
  }
  // weakly_canonical keeps a trailing separator as an empty last part.
  if (r == root.end() || (std::next(r) == root.end() && r->empty())) return "";
  return "lies outside the input folder " + root.string() +
         " (referenced files must lie inside the scene's folder, or the one --input-folder names)";
}

}  // namespace walkrad::input_limits
