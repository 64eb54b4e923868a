// The planets seen from the Earth (scene/Planets.hpp) over two years: their elongations
// within the inner planets' greatest (Mercury 28.3 deg, Venus 47.8 deg), their magnitudes
// within the ranges observed, and the light time; Mars left out when seen from Mars.
#include "scene/Ephemeris.hpp"
#include "scene/Planets.hpp"
#include "scene/Time.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace umbra::scene {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(Planets, FromTheEarthOverTwoYearsTheyStayWhereAndAsBrightAsTheyAre) {
  // The inner planets within their greatest elongations (Mercury 28.3 deg, Venus 47.8 deg),
  // the outer ones at opposition; the magnitudes within the extremes Mallama & Hilton 2018
  // give for each planet seen from the Earth: Mercury -2.48 to +7.25, Venus -4.92 to -2.98,
  // Mars -2.94 to +1.86, Jupiter -2.94 to -1.66.
  std::map<std::string, std::pair<double, double>> range, elongation;
  for (int day = 0; day < 730; day += 3) {
    const UtcTime t = addSeconds(parseUtc("2026-01-01T00:00:00Z"), day * 86400.0);
    const glm::dvec3 earth = heliocentricPositionM("Earth", t);
    const glm::dvec3 toSun = glm::normalize(-earth);
    for (const PlanetSeen& p : planetsSeenFrom(earth, t)) {
      ASSERT_NEAR(glm::length(p.directionIcrs), 1.0, 1e-12);
      ASSERT_TRUE(std::isfinite(p.magnitudeV)) << p.name;
      auto& r = range.try_emplace(p.name, 99.0, -99.0).first->second;
      r = {std::min(r.first, p.magnitudeV), std::max(r.second, p.magnitudeV)};
      const double e = std::acos(std::clamp(glm::dot(p.directionIcrs, toSun), -1.0, 1.0)) / kDeg;
      auto& el = elongation.try_emplace(p.name, 999.0, -1.0).first->second;
      el = {std::min(el.first, e), std::max(el.second, e)};
    }
  }
  for (const auto& [name, r] : range)
    std::printf("%s: V %.2f to %.2f, elongation %.1f to %.1f deg\n", name.c_str(), r.first, r.second,
                elongation[name].first, elongation[name].second);
  EXPECT_LE(elongation["Mercury"].second, 28.3);
  EXPECT_GT(elongation["Mercury"].second, 17.8);
  EXPECT_LE(elongation["Venus"].second, 47.8);
  EXPECT_GT(elongation["Venus"].second, 45.0);
  EXPECT_GT(elongation["Mars"].second, 170.0);
  EXPECT_GT(elongation["Jupiter"].second, 170.0);
  const std::map<std::string, std::pair<double, double>> extremes{
      {"Mercury", {-2.48, 7.25}}, {"Venus", {-4.92, -2.98}}, {"Mars", {-2.94, 1.86}}, {"Jupiter", {-2.94, -1.66}}};
  for (const auto& [name, e] : extremes) {
    EXPECT_GE(range[name].first, e.first - 0.01) << name;
    EXPECT_LE(range[name].second, e.second + 0.01) << name;
  }
}

TEST(Planets, TheLightTimeMovesThePlaceByThePlanetsMotion) {
  // Jupiter is some 40 light minutes away: its place then differs from now by its motion
  // over that time, about 13 km/s x 2400 s = 30 000 km, seen from 5 au: ~8 arcseconds.
  const UtcTime t = parseUtc("2027-08-02T10:06:00Z");
  const glm::dvec3 earth = heliocentricPositionM("Earth", t);
  for (const PlanetSeen& p : planetsSeenFrom(earth, t)) {
    if (p.name != "Jupiter") continue;
    const glm::dvec3 now = glm::normalize(planetHeliocentricPositionM("Jupiter", t) - earth);
    const double shiftArcsec = std::acos(std::min(1.0, glm::dot(now, p.directionIcrs))) / kDeg * 3600.0;
    EXPECT_GT(shiftArcsec, 2.0);
    EXPECT_LT(shiftArcsec, 30.0);
    EXPECT_NEAR(p.distanceAu, glm::length(planetHeliocentricPositionM("Jupiter", t) - earth) / 149597870700.0, 1e-4);
  }
}

TEST(Planets, AnObserverAtMarsDoesNotSeeMarsAsAStar) {
  const UtcTime t = parseUtc("2027-08-02T10:06:00Z");
  const glm::dvec3 mars = heliocentricPositionM("Mars", t);
  const auto seen = planetsSeenFrom(mars + glm::dvec3(3.4e6, 0.0, 0.0), t);
  EXPECT_EQ(seen.size(), 3u);
  for (const PlanetSeen& p : seen) EXPECT_NE(p.name, "Mars");
}

}  // namespace
}  // namespace umbra::scene
