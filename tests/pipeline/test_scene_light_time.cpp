// Light time in scenes (eclipse::occluderSeenBy): the Moon casts its shadow on the Earth from
// where it was when the light that reaches the ground passed it, 1.28 s before, and the
// camera sees each body a light time back. At the greatest eclipse of 2017-08-21 the axis
// of the Moon's shadow meets the ground at NASA's point of greatest eclipse (36.97 N,
// 87.67 W; Espenak, NASA's eclipse web site, with Delta T 70.3 s: TD 18:26:40.2): the scene
// at the same Terrestrial Time (UTC 18:25:31.0 is TT 18:26:40.2) puts it there. And in the
// lunar eclipse of 2018-07-27 the Moon passes the Earth's shadow axis when and where NASA says.
#include "SceneInputs.h"

#include "ShadowLut.hpp"
#include "scene/Scene.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace umbra;
using namespace umbra::pipeline;

namespace {

const SphereBody& named(const SceneInputs& in, const std::string& name) {
  return *std::find_if(in.bodies.begin(), in.bodies.end(), [&](const SphereBody& b) { return b.name == name; });
}

struct GroundPoint {
  double latDeg = 0.0, lonDeg = 0.0;
};

// Where the line from the Sun's centre through `occluderM` first meets the WGS84 ellipsoid
// of `earth` (its centre and body-fixed frame), geodetic.
GroundPoint axisOnGround(const glm::dvec3& sunM, const glm::dvec3& occluderM, const SphereBody& earth) {
  const GeographicLib::Geocentric& wgs84 = GeographicLib::Geocentric::WGS84();
  const double a = wgs84.EquatorialRadius(), b = a * (1.0 - wgs84.Flattening());
  const glm::dmat3 toBody = glm::transpose(earth.bodyFixedToInertial);
  const glm::dvec3 o = toBody * (occluderM - earth.centreM), d = toBody * glm::normalize(occluderM - sunM);
  const glm::dvec3 scale(1.0 / a, 1.0 / a, 1.0 / b);  // the ellipsoid as the unit sphere
  const glm::dvec3 os = o * scale, ds = d * scale;
  const double qa = glm::dot(ds, ds), qb = 2.0 * glm::dot(os, ds), qc = glm::dot(os, os) - 1.0;
  const double disc = qb * qb - 4.0 * qa * qc;
  EXPECT_GT(disc, 0.0) << "the axis misses the Earth";
  const glm::dvec3 p = o + d * ((-qb - std::sqrt(std::max(disc, 0.0))) / (2.0 * qa));
  GroundPoint g;
  double h = 0.0;
  wgs84.Reverse(p.x, p.y, p.z, g.latDeg, g.lonDeg, h);
  return g;
}

}  // namespace

TEST(SceneLightTime, TheMoonsUmbraIn2017FallsOnNasasPointOfGreatestEclipse) {
  const scene::Scene s = scene::parseScene(R"({
    "time": "2017-08-21T18:25:31.0Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": 36.97, "lonDeg": -87.67, "altM": 2}, "target": "Moon"}
  })", "light-time test");
  const SceneInputs in = sceneInputs(s);
  const SphereBody& earth = named(in, "Earth");
  const SphereBody& moon = named(in, "Moon");
  const SphereBody seen = occluderSeenBy(moon, earth);

  const GroundPoint g = axisOnGround(in.sun.positionM, seen.centreM, earth);
  const scene::Body& geometric = *s.find("Moon");
  const GroundPoint old = axisOnGround(in.sun.positionM, geometric.positionM, earth);
  const double shiftKm = glm::length(seen.centreM - geometric.positionM) / 1e3;
  std::printf("  axis on the ground: %.3f N %.3f E with light time, %.3f N %.3f E without; the Moon moved %.1f km\n",
              g.latDeg, g.lonDeg, old.latDeg, old.lonDeg, shiftKm);
  // 0.02 deg: 2 km north-south, 1.8 km east-west at this latitude.
  EXPECT_NEAR(g.latDeg, 36.97, 0.02);
  EXPECT_NEAR(g.lonDeg, -87.67, 0.02);
  // Without the light time the axis lands 0.35 deg (32 km) to the north-west.
  EXPECT_GT(std::hypot(old.latDeg - 36.97, (old.lonDeg + 87.67) * std::cos(36.97 * 3.14159265358979 / 180.0)), 0.2);
  // The Moon's heliocentric speed (28-31 km/s that day) times its light time to the ground (1.2 s).
  EXPECT_GT(shiftKm, 33.0);
  EXPECT_LT(shiftKm, 40.0);
  // The camera on the ground sees the Moon a light time back too (within the Moon's
  // radius' light time, 170 m, of where the ground's shadow takes it), and the Earth it
  // stands on where it is.
  EXPECT_LT(glm::length(moon.centreM - seen.centreM), 300.0);
  EXPECT_LT(glm::length(earth.centreM - s.find("Earth")->positionM), 0.01);
}

namespace {
// The distance of `pointM` from the line through `aM` and `bM`.
double distanceFromLine(const glm::dvec3& pointM, const glm::dvec3& aM, const glm::dvec3& bM) {
  const glm::dvec3 d = glm::normalize(bM - aM);
  const glm::dvec3 r = pointM - aM;
  return glm::length(r - glm::dot(r, d) * d);
}

// The Moon's centre from the Earth's shadow axis in equatorial radii at `time` (UTC): as
// the camera on the Earth sees the Moon, the Earth's shadow where the light that reaches
// the Moon passed it; or, without the light time, both where they are.
double gammaAt(const std::string& time, bool lightTime) {
  const scene::Scene s = scene::parseScene(R"({
    "time": ")" + time + R"(",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": -19.0, "lonDeg": 56.0, "altM": 2}, "target": "Moon"}
  })", "light-time test");
  const SceneInputs in = sceneInputs(s);
  const SphereBody& earth = named(in, "Earth");
  const SphereBody& moon = named(in, "Moon");
  constexpr double kEquatorialRadiusM = 6378137.0;
  if (!lightTime)
    return distanceFromLine(s.find("Moon")->positionM, in.sun.positionM, s.find("Earth")->positionM) /
           kEquatorialRadiusM;
  return distanceFromLine(moon.centreM, in.sun.positionM, occluderSeenBy(earth, moon).centreM) / kEquatorialRadiusM;
}

// The time of the least of three distances a minute apart (a parabola through them), in
// seconds from the middle one.
double leastAtS(double before, double at, double after) {
  return 60.0 * (before - after) / (2.0 * (before - 2.0 * at + after));
}

}  // namespace

// The lunar eclipse of 2018-07-27 about NASA's greatest eclipse (20:21:44 UT; the scene's
// TT is 69.2 s later, NASA's Delta T 69 s). With the light time the Moon passes closest to
// the shadow's axis within 5 s of NASA's instant, at NASA's gamma, 0.1168 equatorial radii
// (within 0.0005: 3 km); without it, 43 s later (the 38 km the Earth and the Moon move
// in their light times, at the Moon's 0.9 km/s across the shadow).
TEST(SceneLightTime, TheMoonIn2018PassesTheEarthsShadowAxisWhenAndWhereNasaSays) {
  for (bool lightTime : {true, false}) {
    const double before = gammaAt("2018-07-27T20:20:44Z", lightTime), at = gammaAt("2018-07-27T20:21:44Z", lightTime),
                 after = gammaAt("2018-07-27T20:22:44Z", lightTime);
    const double leastS = leastAtS(before, at, after);
    std::printf("  %s light time: gamma %.4f at 20:21:44, least %+.1f s from it (NASA 0.1168, 0 s)\n",
                lightTime ? "with" : "without", at, leastS);
    if (lightTime) {
      EXPECT_NEAR(at, 0.1168, 0.0005);
      EXPECT_NEAR(leastS, 0.0, 5.0);
    } else {
      EXPECT_GT(std::abs(leastS), 20.0);
    }
  }
}
