// Light that cannot decay: closed sets of polygons that absorb nothing in a channel, found by rays
// inside a scene that absorbs elsewhere, and whether a light is inside them.
#include "walkrad/plan/lossless_enclosure.h"

#include <gtest/gtest.h>

#include "walkrad/testing/test_scenes.h"
#include "walkrad/scene/transmission_twins.h"

namespace walkrad {
namespace {

// A 2 m room of reflectance 0.5 (faces inwards) around a sealed 0.6 m box [0.7, 1.3]³ whose faces face
// inwards, of material `white` (index 1) but its floor, of material `glow` (index 2): polygons 0-5 the
// room, 6-11 the box, 8 its floor. (A lamp hung inside would not do: its back absorbs, as every
// one-sided polygon's does.)
Scene room_with_box(Vec3 box, Vec3 glow_rho, Vec3 glow_emission) {
  Scene s = test::closed_box(2.0, Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 0));
  s.source = "room.mgf";
  s.materials.push_back({"white", box, Vec3(0, 0, 0)});
  s.materials.push_back({"glow", glow_rho, glow_emission});
  Scene inner = test::closed_box(0.6, box, Vec3(0, 0, 0));
  for (Polygon p : inner.polygons) {
    for (Vec3& v : p.v) v = v + Vec3(0.7, 0.7, 0.7);
    p.material = polygon_normal(p).z > 0.5 ? 2 : 1;
    p.source = uint32_t(s.polygons.size());
    s.polygons.push_back(p);
  }
  EXPECT_EQ(s.polygons[8].material, 2u);
  return s;
}

const Vec3 kWhite(1, 1, 1), kGrey(0.5, 0.5, 0.5), kOff(0, 0, 0), kOn(10, 10, 10);

std::vector<uint32_t> box_and_glow() { return {6, 7, 8, 9, 10, 11}; }

TEST(LosslessEnclosure, ASealedWhiteBoxAroundALightIsFoundInEveryChannel) {
  const Scene s = room_with_box(kWhite, kWhite, kOn);
  const std::vector<LosslessEnclosure> found = find_lossless_enclosures(s, RayScene(s));
  ASSERT_EQ(found.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(found[size_t(c)].channel, c);
    EXPECT_EQ(found[size_t(c)].polygons, box_and_glow());
    EXPECT_TRUE(found[size_t(c)].lit);
    EXPECT_TRUE(found[size_t(c)].lights.empty());
  }
  EXPECT_EQ(describe_polygons(s, found[0].polygons), "6 polygons (materials 'white', 'glow'; MGF lines 6, 7, 8, 9, 10, 11)");
  EXPECT_EQ(describe_polygons(s, found[0].polygons, 2), "6 polygons (materials 'white', 'glow'; MGF lines 6, 7, ...)");
}

// Only the channel that absorbs nothing: a box white in red, grey in green and blue.
TEST(LosslessEnclosure, OnlyTheChannelThatAbsorbsNothing) {
  const Scene s = room_with_box(Vec3(1, 0.5, 0.5), kWhite, kOn);
  const std::vector<LosslessEnclosure> found = find_lossless_enclosures(s, RayScene(s));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].channel, 0);
  EXPECT_EQ(found[0].polygons, box_and_glow());
}

// Any way out, any absorber inside: nothing. The light's own reflectance counts like the box's.
TEST(LosslessEnclosure, AnOpeningOrAnAbsorberInsideLetsTheLightDecay) {
  Scene open = room_with_box(kWhite, kWhite, kOn);
  open.polygons.erase(open.polygons.begin() + 9);  // the box's lid
  EXPECT_TRUE(find_lossless_enclosures(open, RayScene(open)).empty());
  const Scene grey_glow = room_with_box(kWhite, kGrey, kOn);
  EXPECT_TRUE(find_lossless_enclosures(grey_glow, RayScene(grey_glow)).empty());
  Scene grey_side = room_with_box(kWhite, kWhite, kOn);
  grey_side.polygons[9].material = 0;
  EXPECT_TRUE(find_lossless_enclosures(grey_side, RayScene(grey_side)).empty());
  // The room itself absorbs: no enclosure outside the box either, whatever lights it.
  const Scene grey_box = room_with_box(kGrey, kGrey, kOn);
  EXPECT_TRUE(find_lossless_enclosures(grey_box, RayScene(grey_box)).empty());
}

// Sealed and dark, its radiosity stays 0: found, not lit. A punctual light inside lights it; one
// outside does not.
TEST(LosslessEnclosure, APunctualLightInsideLightsItOneOutsideDoesNot) {
  Scene s = room_with_box(kWhite, kWhite, kOff);
  PunctualLight outside;
  outside.name = "outside";
  outside.position = Vec3(1.0, 1.0, 1.8);
  outside.intensity = Vec3(5, 5, 5);
  s.lights.push_back(outside);
  std::vector<LosslessEnclosure> found = find_lossless_enclosures(s, RayScene(s));
  ASSERT_EQ(found.size(), 3u);
  EXPECT_FALSE(found[0].lit);
  PunctualLight inside = outside;
  inside.name = "inside";
  inside.position = Vec3(1.0, 1.0, 1.0);
  inside.intensity = Vec3(0, 5, 0);  // green only
  s.lights.push_back(inside);
  found = find_lossless_enclosures(s, RayScene(s));
  ASSERT_EQ(found.size(), 3u);
  EXPECT_FALSE(found[0].lit);
  EXPECT_TRUE(found[1].lit);
  EXPECT_EQ(found[1].lights, std::vector<uint32_t>{1});
  EXPECT_FALSE(found[2].lit);
}

// ρ + τ = 1: light a face transmits leaves through its twin into the room, which absorbs. Without
// twins (transmission not simulated) τ is absorbed, and the box absorbs too.
TEST(LosslessEnclosure, LightTransmittedOutOfTheBoxDecays) {
  Scene s = room_with_box(kWhite, kWhite, kOn);
  s.materials.push_back({"pane", Vec3(0.6, 0.6, 0.6), Vec3(0, 0, 0), Vec3(0.4, 0.4, 0.4)});
  s.polygons[9].material = 3;
  const std::vector<uint32_t> twins = add_transmission_twins(s);
  EXPECT_TRUE(find_lossless_enclosures(s, RayScene(s), twins).empty());
  EXPECT_TRUE(find_lossless_enclosures(s, RayScene(s)).empty());
}

}  // namespace
}  // namespace walkrad
