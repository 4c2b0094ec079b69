// manifest.json (manifest.h): written by the pipeline, validated strictly when read, since the
// runtime opens files it names.
#include "walkrad/formats/manifest.h"

#include "json_util.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/walkthrough.h"

namespace walkrad {

using namespace json_util;

namespace {

json bounds_to_json(const Bounds& b) { return {{"min", to_json(b.lo)}, {"max", to_json(b.hi)}}; }

Bounds bounds_from_json(const json& j, const std::string& file, const std::string& p) {
  check_keys(j, {"min", "max"}, file, p);
  Bounds b;
  b.lo = vec3(member(j, "min", file, p), file, p + "/min");
  b.hi = vec3(member(j, "max", file, p), file, p + "/max");
  return b;
}

// A chunk's file must be a plain name inside the bake folder: never a path that leaves it.
std::string chunk_file_name(const json& j, const std::string& file, const std::string& p) {
  const std::string name = string(j, file, p);
  if (name.empty() || name.find('/') != std::string::npos || name.find('\\') != std::string::npos ||
      name == "." || name == ".." || name.find('\0') != std::string::npos)
    throw InputError(file, p, "chunk file must be a plain file name inside the bake folder");
  return name;
}

}  // namespace

json manifest_to_json(const Manifest& m) {
  json chunks = json::array();
  for (const ChunkInfo& c : m.chunks)
    chunks.push_back({{"file", c.file}, {"bounds", bounds_to_json(c.bounds)}, {"triangles", c.triangles}, {"bytes", c.bytes},
                      {"importance", c.importance}});
  json views = json::array();
  for (const Viewpoint& v : m.viewpoints) views.push_back(viewpoint_to_json(v));
  return {{"format", kManifestFormat}, {"version", kManifestVersion}, {"tool", m.tool},
          {"scene", {{"file", m.scene_file}, {"hash", m.scene_hash}}}, {"bounds", bounds_to_json(m.bounds)},
          {"exposure", m.exposure}, {"chunks", chunks}, {"viewpoints", views}, {"settings", m.settings}, {"effects", m.effects}};
}

Manifest manifest_from_json(const json& j, const std::string& file) {
  check_keys(j, {"format", "version", "tool", "scene", "bounds", "exposure", "chunks", "viewpoints", "settings", "effects"}, file, "");
  if (string(member(j, "format", file, ""), file, "/format") != kManifestFormat)
    throw InputError(file, "/format", std::string("expected \"") + kManifestFormat + "\"");
  if (number(member(j, "version", file, ""), file, "/version") != kManifestVersion)
    throw InputError(file, "/version", "unsupported manifest version", kExitMissingFeature);
  Manifest m;
  m.tool = string(member(j, "tool", file, ""), file, "/tool");
  const json& scene = member(j, "scene", file, "");
  check_keys(scene, {"file", "hash"}, file, "/scene");
  m.scene_file = string(member(scene, "file", file, "/scene"), file, "/scene/file");
  m.scene_hash = string(member(scene, "hash", file, "/scene"), file, "/scene/hash");
  m.bounds = bounds_from_json(member(j, "bounds", file, ""), file, "/bounds");
  m.exposure = number(member(j, "exposure", file, ""), file, "/exposure");
  if (!(m.exposure > 0)) throw InputError(file, "/exposure", "must be positive");
  const json& chunks = member(j, "chunks", file, "");
  if (!chunks.is_array()) throw InputError(file, "/chunks", "expected an array");
  for (size_t i = 0; i < chunks.size(); ++i) {
    const std::string p = "/chunks/" + std::to_string(i);
    check_keys(chunks[i], {"file", "bounds", "triangles", "bytes", "importance"}, file, p);
    ChunkInfo c;
    c.file = chunk_file_name(member(chunks[i], "file", file, p), file, p + "/file");
    c.bounds = bounds_from_json(member(chunks[i], "bounds", file, p), file, p + "/bounds");
    c.triangles = count(member(chunks[i], "triangles", file, p), uint64_t(1) << 32, file, p + "/triangles");
    c.bytes = count(member(chunks[i], "bytes", file, p), uint64_t(1) << 36, file, p + "/bytes");
    m.chunks.push_back(c);
  }
  const json& views = member(j, "viewpoints", file, "");
  if (!views.is_array()) throw InputError(file, "/viewpoints", "expected an array");
  for (size_t i = 0; i < views.size(); ++i)
    m.viewpoints.push_back(viewpoint_from_json(views[i], file, "/viewpoints/" + std::to_string(i)));
  // Importance: one fraction in [0, 1] per viewpoint, read once the viewpoints are known.
  for (size_t i = 0; i < chunks.size(); ++i) {
    const std::string p = "/chunks/" + std::to_string(i) + "/importance";
    const json& imp = member(chunks[i], "importance", file, "/chunks/" + std::to_string(i));
    if (!imp.is_array() || imp.size() != views.size())
      throw InputError(file, p, "expected an array with one number per viewpoint (" + std::to_string(views.size()) + ")");
    for (size_t v = 0; v < imp.size(); ++v) {
      const double x = number(imp[v], file, p + "/" + std::to_string(v));
      if (!(x >= 0 && x <= 1)) throw InputError(file, p + "/" + std::to_string(v), "must be a fraction in [0, 1]");
      m.chunks[i].importance.push_back(float(x));
    }
  }
  m.settings = member(j, "settings", file, "");
  if (j.contains("effects")) {
    m.effects = j["effects"];
    if (!m.effects.is_object()) throw InputError(file, "/effects", "expected an object");
  }
  return m;
}

Manifest read_manifest(const std::string& path) { return manifest_from_json(parse_file(path), path); }

}  // namespace walkrad
