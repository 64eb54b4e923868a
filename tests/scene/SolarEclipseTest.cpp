// The Moon's shadow on the Earth from the ephemerides (scene::moonSeenFromM, the Earth's
// ellipsoid and rotation) against NASA's figures for the greatest eclipse of 2017-08-21
// (Espenak, eclipse.gsfc.nasa.gov: 18:26:40.2 TD; 36 58.0' N, 87 40.3' W; path width
// 114.7 km): where the shadow's axis meets the ground, and the umbra's width there across
// the path, from the exact visible fraction (eclipse::eclipseFactor).
#include "scene/Ephemeris.hpp"
#include "scene/Moon.hpp"
#include "scene/Scene.hpp"

#include "ShadowLut.hpp"
#include "SolarDisc.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

using namespace umbra;
using namespace umbra::scene;

namespace {

constexpr double kMoonRadiusM = 1737.4e3;
const GeographicLib::Geocentric& wgs84() { return GeographicLib::Geocentric::WGS84(); }

struct Ground {
  double latDeg = 0.0, lonDeg = 0.0;
};

/// Where the line from the Sun's centre through the Moon's meets the Earth's ellipsoid at t.
Ground axisOnTheGround(UtcTime t) {
  const glm::dvec3 earth = heliocentricPositionM("Earth", t);
  const glm::dmat3 toInertial = bodyFixedToInertial("Earth", t);
  const glm::dvec3 moon = moonSeenFromM(t, earth);
  // In the body-fixed frame, scaled so that the ellipsoid is the unit sphere.
  const double a = wgs84().EquatorialRadius(), b = a * (1.0 - wgs84().Flattening());
  const glm::dvec3 scale(1.0 / a, 1.0 / a, 1.0 / b);
  const glm::dvec3 o = glm::transpose(toInertial) * (glm::dvec3(0.0) - earth) * scale;
  const glm::dvec3 d = glm::normalize(glm::transpose(toInertial) * (moon - glm::dvec3(0.0)) * scale);
  const double bo = glm::dot(o, d), c = glm::dot(o, o) - 1.0;
  const double s = -bo - std::sqrt(bo * bo - c);  // the near side
  const glm::dvec3 p = (o + s * d) / scale;
  Ground g;
  double h = 0.0;
  wgs84().Reverse(p.x, p.y, p.z, g.latDeg, g.lonDeg, h);
  return g;
}

/// The Sun's visible fraction at a ground point (height 0) at t.
double visibleAt(UtcTime t, double latDeg, double lonDeg) {
  glm::dvec3 local;
  wgs84().Forward(latDeg, lonDeg, 0.0, local.x, local.y, local.z);
  const glm::dvec3 p = heliocentricPositionM("Earth", t) + bodyFixedToInertial("Earth", t) * local;
  return eclipse::eclipseFactor(p, glm::dvec3(0.0), eclipse::kSunRadiusM, {moonSeenFromM(t, p), kMoonRadiusM}, nullptr).g;
}

}  // namespace

TEST(SolarEclipse2017, TheShadowsAxisMeetsTheGroundAtNasasGreatestEclipse) {
  // The Moon from ELP 2000-82B with every term (well under an arcsecond, 2 km on the
  // ground): the axis lands 1.2 km from NASA's point.
  const UtcTime t = fromTt(2457986.5, 66400.2 / 86400.0);
  const Ground g = axisOnTheGround(t);
  double km = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(g.latDeg, g.lonDeg, 36.0 + 58.0 / 60.0, -(87.0 + 40.3 / 60.0), km);
  km /= 1000.0;
  std::printf("  axis on the ground %.4f N %.4f E, %.2f km from NASA's point\n", g.latDeg, g.lonDeg, km);
  EXPECT_LT(km, 5.0);
  EXPECT_EQ(visibleAt(t, g.latDeg, g.lonDeg), 0.0);
}

TEST(SolarEclipse2017, TheUmbrasWidthAcrossThePathIsNasas) {
  // Across the path (perpendicular to the axis point's motion over the ground) the umbra
  // spans NASA's 114.7 km within 2 % (114.44 km: the Moon a sphere of 1737.4 km, its mean
  // limb; the shadow moving over the ground at 0.648 km/s).
  const UtcTime t = fromTt(2457986.5, 66400.2 / 86400.0);
  const Ground g = axisOnTheGround(t);
  const GeographicLib::LocalCartesian enu(g.latDeg, g.lonDeg, 0.0, wgs84());
  const Ground later = axisOnTheGround(addSeconds(t, 10.0)), earlier = axisOnTheGround(addSeconds(t, -10.0));
  double x1, y1, z1, x0, y0, z0;
  enu.Forward(later.latDeg, later.lonDeg, 0.0, x1, y1, z1);
  enu.Forward(earlier.latDeg, earlier.lonDeg, 0.0, x0, y0, z0);
  const double along = std::hypot(x1 - x0, y1 - y0);
  const double ax = -(y1 - y0) / along, ay = (x1 - x0) / along;  // across the path, east-north plane
  const auto visibleAcross = [&](double sM) {
    double lat, lon, h;
    enu.Reverse(sM * ax, sM * ay, 0.0, lat, lon, h);
    return visibleAt(t, lat, lon);
  };
  const auto edge = [&](double sign) {  // bisection for the umbra's edge, 1 m
    double inside = 0.0, outside = sign * 150e3;
    while (std::abs(outside - inside) > 1.0) {
      const double mid = 0.5 * (inside + outside);
      (visibleAcross(mid) > 0.0 ? outside : inside) = mid;
    }
    return std::abs(0.5 * (inside + outside));
  };
  const double width = (edge(1.0) + edge(-1.0)) / 1000.0;
  std::printf("  shadow over the ground at %.3f km/s; the umbra %.2f km wide across the path (NASA 114.7)\n",
              along / 20.0 / 1000.0, width);
  EXPECT_NEAR(width, 114.7, 0.02 * 114.7);
}

// The example scene from 400 km over the 2024-04-08 eclipse: the camera is in the
// penumbra, north of the umbra; three hours later, past the eclipse, the Sun shows whole.
TEST(SolarEclipse2024, TheSunsVisibleFractionAtTheCamera) {
  Scene s = loadScene(UMBRA_SOURCE_DIR "/examples/scenes/solar-eclipse-2024-04-08-from-400km.json");
  const std::optional<double> f = sunVisibleFractionAtCamera(s);
  ASSERT_TRUE(f.has_value());
  EXPECT_GT(*f, 0.001);
  EXPECT_LT(*f, 0.3);
  std::printf("  %s\n", describeSunVisible(*f).c_str());
  EXPECT_NE(describeSunVisible(*f).find("% visible"), std::string::npos);
  EXPECT_EQ(describeSunVisible(0.0), "Sun hidden");
  setTime(s, addSeconds(s.time, 3.0 * 3600.0));
  EXPECT_FALSE(sunVisibleFractionAtCamera(s).has_value());
}

// The example scenes from the ground: at their instants the camera is in the umbra
// (Mazatlan 2024, Burgos 2026, Luxor 2027: the Sun hidden) or in the antumbra of the
// annular eclipse of 2023 (the ring: a sixteenth of the Sun's light; NASA's magnitude
// 0.952 leaves 1 - 0.952^2 = 9 % of the disc's area, less of its limb-darkened light).
TEST(SolarEclipseScenes, TheGroundScenesAreInTotalityOrInTheRing) {
  for (const char* name : {"solar-eclipse-2024-04-08-mazatlan", "solar-eclipse-2026-08-12-burgos",
                           "solar-eclipse-2027-08-02-luxor"}) {
    const Scene s = loadScene(std::string(UMBRA_SOURCE_DIR "/examples/scenes/") + name + ".json");
    const std::optional<double> f = sunVisibleFractionAtCamera(s);
    ASSERT_TRUE(f.has_value()) << name;
    EXPECT_EQ(*f, 0.0) << name;
  }
  const Scene ring = loadScene(UMBRA_SOURCE_DIR "/examples/scenes/annular-eclipse-2023-10-14.json");
  const std::optional<double> f = sunVisibleFractionAtCamera(ring);
  ASSERT_TRUE(f.has_value());
  std::printf("  the ring: %.4f of the Sun's light\n", *f);
  EXPECT_GT(*f, 0.04);
  EXPECT_LT(*f, 0.09);
}

// From L1 as EPIC: the camera 1.5 million km out, 4 to 15 degrees off the Sun-Earth line,
// so that the Moon, near that line in the eclipse, lies outside the 0.62 degree field.
TEST(SolarEclipseScenes, FromL1TheMoonStandsOutsideTheField) {
  const Scene s = loadScene(UMBRA_SOURCE_DIR "/examples/scenes/solar-eclipse-2024-04-08-from-l1.json");
  const glm::dvec3 earth = s.find("Earth")->positionM, moon = s.find("Moon")->positionM, cam = s.camera.positionM;
  const double off = std::acos(glm::dot(glm::normalize(cam - earth), glm::normalize(-earth))) / (3.14159265358979 / 180.0);
  const double moonFromCentre =
      std::acos(std::min(1.0, glm::dot(glm::normalize(moon - cam), glm::normalize(earth - cam)))) / (3.14159265358979 / 180.0);
  const double moonRadiusDeg = std::asin(kMoonRadiusM / glm::length(moon - cam)) / (3.14159265358979 / 180.0);
  std::printf("  %.1f deg off the Sun-Earth line, the Moon %.2f deg from the view's centre\n", off, moonFromCentre);
  EXPECT_GT(off, 4.0);
  EXPECT_LT(off, 15.0);
  EXPECT_NEAR(glm::length(cam - earth), 1.5e9, 0.02e9);
  EXPECT_GT(moonFromCentre - moonRadiusDeg, 0.5 * 0.62 * std::sqrt(2.0));
}
