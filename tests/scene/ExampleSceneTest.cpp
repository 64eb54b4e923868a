// The example scene examples/scenes/lunar-eclipse-2015-09-28.json.
#include "scene/Bodies.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::scene;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

const std::string kExample =
    std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/lunar-eclipse-2015-09-28.json";

/// Geodetic zenith (unit, ICRS axes) of the observer.
glm::dvec3 zenith(const Observer& o, UtcTime t) {
  const double lat = o.latDeg * kDeg, lon = o.lonDeg * kDeg;
  const glm::dvec3 local(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon),
                         std::sin(lat));
  return bodyFixedToInertial("Earth", t) * local;
}

/// Latitude and longitude where the Moon is at the geodetic zenith (fixed-point iteration).
Observer subLunarPoint(const Scene& scene) {
  const Body& earth = *scene.find("Earth");
  const glm::dmat3 toFixed = glm::transpose(bodyFixedToInertial("Earth", scene.time));
  const glm::dvec3 moon = toFixed * (scene.find("Moon")->positionM - earth.positionM);
  Observer o{"Earth", 0.0, 0.0, 0.0};
  for (int i = 0; i < 20; ++i) {
    const glm::dvec3 ground = toFixed * (observerPositionM(earth, o, scene.time) - earth.positionM);
    const glm::dvec3 d = glm::normalize(moon - ground);
    o.latDeg = std::asin(d.z) / kDeg;
    o.lonDeg = std::atan2(d.y, d.x) / kDeg;
  }
  return o;
}

} // namespace

TEST(ExampleScene, LoadsWithTheMoonNearTheZenith) {
  const Scene scene = loadScene(kExample);
  EXPECT_EQ(formatUtc(scene.time), "2015-09-28T01:45:00Z");
  ASSERT_TRUE(scene.camera.observer);
  const Observer& o = *scene.camera.observer;
  const glm::dvec3 toMoon = scene.find("Moon")->positionM - scene.camera.positionM;
  const double elevationDeg =
      90.0 - std::acos(glm::dot(glm::normalize(toMoon), zenith(o, scene.time))) / kDeg;
  EXPECT_GT(elevationDeg, 60.0);
  EXPECT_GT(elevationDeg, 89.9); // the observer stands at the (rounded) sub-lunar point

  const Observer exact = subLunarPoint(scene);
  EXPECT_NEAR(o.latDeg, exact.latDeg, 0.01);
  EXPECT_NEAR(o.lonDeg, exact.lonDeg, 0.01);
}

TEST(ExampleScene, MoonFillsAboutEightyPercentOfTheImageHeight) {
  const Scene scene = loadScene(kExample);
  const double distanceM = glm::length(scene.camera.targetM - scene.camera.positionM);
  const double diameterDeg = 2.0 * std::asin(scene.find("Moon")->radiusM / distanceM) / kDeg;
  EXPECT_NEAR(diameterDeg, 0.568, 0.002);
  EXPECT_NEAR(diameterDeg / scene.camera.fovDeg, 0.8, 0.02);
}

TEST(ExampleScene, MoonStraddlesTheUmbraEdge) {
  // Partial phase: the edge of Earth's umbra (a cone, geometric) crosses the Moon's disc.
  const Scene scene = loadScene(kExample);
  const glm::dvec3 earth = scene.find("Earth")->positionM;
  const glm::dvec3 moon = scene.find("Moon")->positionM;
  const double sunR = scene.sun().radiusM, earthR = scene.find("Earth")->radiusM;
  const glm::dvec3 axis = glm::normalize(earth);
  const double along = glm::dot(moon - earth, axis);
  const double offAxisM = glm::length(moon - earth - along * axis);
  const double umbraRadiusM = earthR - along * (sunR - earthR) / glm::length(earth);
  const double moonR = scene.find("Moon")->radiusM;
  EXPECT_GT(offAxisM, umbraRadiusM - moonR);
  EXPECT_LT(offAxisM, umbraRadiusM + moonR);
}
