// manifest.json: round trip, and refusal of a chunk path that leaves the bake folder.
#include "walkrad/formats/manifest.h"

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"

namespace walkrad {
namespace {

Manifest sample() {
  Manifest m;
  m.tool = "walkrad test";
  m.scene_file = "scene.gltf";
  m.scene_hash = "0123456789abcdef";
  m.bounds.extend({0, 0, 0});
  m.bounds.extend({1, 2, 3});
  m.exposure = 2.5;
  m.chunks.push_back({"chunk-0000.glb", m.bounds, 12, 3456, {0.25f}});
  Viewpoint v;
  v.name = "cam";
  v.position = {0, 1, 5};
  m.viewpoints.push_back(v);
  m.settings = {{"method", "classic"}};
  return m;
}

TEST(Manifest, RoundTrips) {
  const Manifest back = manifest_from_json(manifest_to_json(sample()), "manifest.json");
  EXPECT_EQ(back.tool, "walkrad test");
  EXPECT_EQ(back.scene_hash, "0123456789abcdef");
  EXPECT_DOUBLE_EQ(back.exposure, 2.5);
  ASSERT_EQ(back.chunks.size(), 1u);
  EXPECT_EQ(back.chunks[0].file, "chunk-0000.glb");
  EXPECT_EQ(back.chunks[0].triangles, 12u);
  EXPECT_EQ(back.chunks[0].bounds.hi, Vec3(1, 2, 3));
  ASSERT_EQ(back.chunks[0].importance.size(), 1u);
  EXPECT_FLOAT_EQ(back.chunks[0].importance[0], 0.25f);
  ASSERT_EQ(back.viewpoints.size(), 1u);
  EXPECT_EQ(back.viewpoints[0].name, "cam");
  EXPECT_EQ(back.settings["method"], "classic");
}

TEST(Manifest, RefusesAChunkOutsideTheFolder) {
  for (const char* bad : {"../../etc/passwd", "/etc/passwd", "..", "sub/chunk.glb", ""}) {
    nlohmann::json j = manifest_to_json(sample());
    j["chunks"][0]["file"] = bad;
    try {
      manifest_from_json(j, "manifest.json");
      FAIL() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.place(), "/chunks/0/file");
    }
  }
}

TEST(Manifest, RefusesImportanceNotOnePerViewpointOrOutsideZeroOne) {
  for (const nlohmann::json& bad : {nlohmann::json::array(), nlohmann::json{0.5, 0.5}, nlohmann::json{1.5}, nlohmann::json{-0.1}}) {
    nlohmann::json j = manifest_to_json(sample());
    j["chunks"][0]["importance"] = bad;
    try {
      manifest_from_json(j, "manifest.json");
      FAIL() << "accepted " << bad.dump();
    } catch (const InputError& e) {
      EXPECT_EQ(e.place().rfind("/chunks/0/importance", 0), 0u) << e.place();
    }
  }
}

TEST(Manifest, RefusesAnUnknownVersion) {
  nlohmann::json j = manifest_to_json(sample());
  j["version"] = 99;
  try {
    manifest_from_json(j, "manifest.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), kExitMissingFeature);
  }
}

}  // namespace
}  // namespace walkrad
