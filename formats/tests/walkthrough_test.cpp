// Walkthrough files: the two forms, and strict refusal of anything mistyped.
#include "walkrad/formats/walkthrough.h"

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"

namespace walkrad {
namespace {

using nlohmann::json;

json two_views() {
  return json::parse(R"({"format": "walkrad-walkthrough", "version": 1, "viewpoints": [
    {"name": "door", "position": [0, 1.6, 5], "target": [0, 1.6, 0], "yfov_deg": 60, "aspect": 1.5},
    {"position": [1, 1, 1], "direction": [0, 0, -2], "up": [0, 1, 0], "yfov_deg": 40}]})");
}

TEST(Walkthrough, ReadsViewpoints) {
  const auto v = walkthrough_from_json(two_views(), "w.json");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].name, "door");
  EXPECT_EQ(v[1].name, "view-1");
  EXPECT_NEAR(v[0].forward.z, -1.0, 1e-12);
  EXPECT_NEAR(v[0].yfov, 60 * 3.14159265358979 / 180, 1e-9);
  EXPECT_DOUBLE_EQ(v[0].aspect, 1.5);
  EXPECT_NEAR(dot(v[1].up, v[1].forward), 0.0, 1e-12);
}

TEST(Walkthrough, SamplesAPathThroughItsKeyframes) {
  const json j = json::parse(R"({"format": "walkrad-walkthrough", "version": 1, "path": {"frames": 11, "yfov_deg": 50,
    "keyframes": [{"time": 0, "position": [0, 1, 0], "target": [0, 1, -1]},
                  {"time": 1, "position": [5, 1, 0], "target": [5, 1, -1]},
                  {"time": 2, "position": [10, 1, 0], "target": [10, 1, -1]}]}})");
  const auto v = walkthrough_from_json(j, "p.json");
  ASSERT_EQ(v.size(), 11u);
  EXPECT_NEAR(v.front().position.x, 0.0, 1e-12);
  EXPECT_NEAR(v[5].position.x, 5.0, 1e-12);   // passes through the middle keyframe
  EXPECT_NEAR(v.back().position.x, 10.0, 1e-12);
  for (const auto& view : v) EXPECT_NEAR(view.forward.z, -1.0, 1e-9);
}

void expect_refused(const json& j, const std::string& place_part, ExitCode code = kExitBadInput) {
  try {
    walkthrough_from_json(j, "bad.json");
    FAIL() << "accepted: " << j.dump();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_NE(std::string(e.what()).find(place_part), std::string::npos) << e.what();
    EXPECT_EQ(e.code(), code);
  }
}

TEST(Walkthrough, RefusesAnUnknownField) {
  json j = two_views();
  j["viewpoints"][1]["fov"] = 40;  // misspelt: must not silently use a default
  expect_refused(j, "/viewpoints/1/fov");
}

TEST(Walkthrough, RefusesWrongTypesAndValues) {
  json j = two_views();
  j["viewpoints"][0]["position"] = json::array({0, "1", 2});
  expect_refused(j, "/viewpoints/0/position/1");
  j = two_views();
  j["viewpoints"][0]["target"] = j["viewpoints"][0]["position"];
  expect_refused(j, "/viewpoints/0");
  j = two_views();
  j["version"] = 2;
  expect_refused(j, "/version", kExitMissingFeature);
  j = two_views();
  j["format"] = "something-else";
  expect_refused(j, "/format");
}

TEST(Walkthrough, RefusesAHugePath) {
  const json j = json::parse(R"({"format": "walkrad-walkthrough", "version": 1, "path": {"frames": 1000000000,
    "yfov_deg": 50, "keyframes": [{"time": 0, "position": [0, 1, 0], "target": [0, 1, -1]}]}})");
  expect_refused(j, "/path/frames", kExitLimitReached);
}

TEST(Walkthrough, ViewpointRoundTripsThroughTheManifestForm) {
  const auto v = walkthrough_from_json(two_views(), "w.json");
  const Viewpoint back = viewpoint_from_json(viewpoint_to_json(v[0]), "m.json", "/viewpoints/0");
  EXPECT_EQ(back.name, v[0].name);
  EXPECT_EQ(back.position, v[0].position);
  EXPECT_NEAR(length(back.forward - v[0].forward), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(back.yfov, v[0].yfov);
}

}  // namespace
}  // namespace walkrad
