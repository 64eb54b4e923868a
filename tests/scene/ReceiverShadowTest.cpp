// Which body shadows the camera's target, and where the target lies in that shadow.
#include "scene/ReceiverShadow.hpp"
#include "scene/Time.hpp"

#include "ShadowMapping.hpp"

#include <cstdio>

#include <gtest/gtest.h>

#include <string>

using namespace umbra;

namespace {

const std::string kExample = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/lunar-eclipse-2015-09-28.json";
constexpr double kAuM = 149597870700.0;

scene::Scene fixedScene(const std::string& target, const std::string& moonY) {
  return scene::parseScene(R"({
    "bodies": [
      {"preset": "Sun", "position": [0, 0, 0]},
      {"preset": "Earth", "position": [)" + std::to_string(kAuM) + R"(, 0, 0]},
      {"preset": "Moon", "position": [)" + std::to_string(kAuM + 384400e3) + ", " + moonY + R"(, 0]}
    ],
    "camera": {"position": [)" + std::to_string(kAuM) + R"(, 0, 7000e3], "target": ")" + target + R"("}
  })", "fixed.json");
}

} // namespace

TEST(ReceiverShadow, FixedGeometry) {
  const scene::ReceiverShadow r = scene::receiverShadow(fixedScene("Moon", "3000e3"));
  ASSERT_TRUE(r.valid) << r.why;
  EXPECT_EQ(r.receiver, "Moon");
  EXPECT_EQ(r.occluder, "Earth");
  EXPECT_NEAR(r.receiverDistanceM, 384400e3, 1e-3);
  EXPECT_NEAR(r.offsetM, 3000e3, 1e-3);
  EXPECT_NEAR(r.sunOccluderDistanceM, kAuM, 1e-3);
  EXPECT_DOUBLE_EQ(r.receiverRadiusM, 1737.4e3);
  // Earth's umbra at the Moon's mean distance: ~4600 km; penumbra ~8100 km.
  EXPECT_GT(r.umbraRadiusM, 4400e3);
  EXPECT_LT(r.umbraRadiusM, 4800e3);
  EXPECT_GT(r.penumbraRadiusM, 7900e3);
  EXPECT_LT(r.penumbraRadiusM, 8300e3);
}

TEST(ReceiverShadow, NothingToShadow) {
  // The Moon on the Sun's side of the Earth: no body lies between it and the Sun.
  scene::Scene s = fixedScene("Moon", "0");
  s.bodies[2].positionM.x = kAuM - 384400e3;
  const scene::ReceiverShadow r = scene::receiverShadow(s);
  EXPECT_FALSE(r.valid);
  EXPECT_NE(r.why.find("no body lies between the Sun and Moon"), std::string::npos) << r.why;

  const scene::ReceiverShadow sun = scene::receiverShadow(fixedScene("Sun", "0"));
  EXPECT_FALSE(sun.valid);
  EXPECT_FALSE(sun.why.empty());
}

TEST(ReceiverShadow, ExampleSceneDuringAndAfterTheEclipse) {
  scene::Scene s = scene::loadScene(kExample);
  scene::ReceiverShadow r = scene::receiverShadow(s);
  ASSERT_TRUE(r.valid) << r.why;
  EXPECT_EQ(r.receiver, "Moon");
  EXPECT_EQ(r.occluder, "Earth");
  EXPECT_GT(r.receiverDistanceM, 350000e3);  // perigee ("supermoon") eclipse
  EXPECT_LT(r.receiverDistanceM, 365000e3);
  // 01:45 UTC, partial phase: the Moon straddles the umbra's edge.
  EXPECT_LT(r.offsetM - r.receiverRadiusM, r.umbraRadiusM);
  EXPECT_GT(r.offsetM + r.receiverRadiusM, r.umbraRadiusM);

  // 05:30 UTC, after the last penumbral contact (05:22 UTC): the Moon is out of the penumbra.
  scene::setTime(s, scene::parseUtc("2015-09-28T05:30:00Z"));
  r = scene::receiverShadow(s);
  ASSERT_TRUE(r.valid) << r.why;
  EXPECT_GT(r.offsetM - r.receiverRadiusM, r.penumbraRadiusM);
}

// The lunar eclipse of 2018-07-27 at NASA's greatest eclipse (20:21:44 UT) seen from the
// Earth: the Moon lies NASA's gamma (0.1168 equatorial radii) from the axis of the Earth's
// shadow, placed as the renderer places both (light time); the Earth casts it with its
// outline towards the Sun, between its polar and equatorial radii (oblate, flattening
// 1/298.257), and the umbra is the cone of that radius.
TEST(ReceiverShadow, TheMoonIn2018LiesNasasGammaFromTheOblateEarthsShadowAxis) {
  const scene::Scene s = scene::parseScene(R"({
    "time": "2018-07-27T20:21:44Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": -19.0, "lonDeg": 56.0, "altM": 2}, "target": "Moon"}
  })", "receiver-shadow test");
  const scene::ReceiverShadow r = scene::receiverShadow(s);
  ASSERT_TRUE(r.valid) << r.why;
  EXPECT_EQ(r.occluder, "Earth");
  EXPECT_NEAR(r.offsetM / 6378137.0, 0.1168, 0.0005);
  const scene::Body& earth = *s.find("Earth");
  std::printf("  the Earth's outline towards the Sun %.3f km (polar %.3f, equatorial %.3f)\n", r.occluderRadiusM / 1e3,
              earth.polarRadiusM / 1e3, earth.equatorialRadiusM / 1e3);
  EXPECT_GT(r.occluderRadiusM, earth.polarRadiusM + 1.0);
  EXPECT_LT(r.occluderRadiusM, earth.equatorialRadiusM - 1.0);
  const auto cones = eclipse::shadowConeRadii({r.sunRadiusM, r.occluderRadiusM, r.sunOccluderDistanceM},
                                              r.receiverDistanceM);
  EXPECT_DOUBLE_EQ(r.umbraRadiusM, cones.umbraRadiusM);
}
