// The planets seen from the Earth (scene/Planets.hpp) over two years: their elongations
// within the inner planets' greatest (Mercury 28.3 deg, Venus 47.8 deg), their magnitudes
// within the ranges observed, and the light time; Mars left out when seen from Mars.
#include "scene/Ephemeris.hpp"
#include "scene/Planets.hpp"
#include "scene/Time.hpp"

#include <erfa.h>
#include <erfam.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

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

// Meeus, Astronomical Algorithms (2nd ed.), example 33.a: Venus on 1992-12-20 at 0h TD, its
// apparent place (light time, aberration, nutation; true equator and equinox of date)
// alpha = 21h04m41.454s, delta = -18 deg 53' 16.84". umbra's astrometric direction (eraPlan94,
// one light time back) taken to the apparent place with ERFA (the Earth's annual aberration,
// IAU 2006/2000A precession-nutation): within eraPlan94's stated accuracy for Venus (5" in
// right ascension, 1" in declination, 1800-2050) plus Meeus' own (his truncated VSOP87, ~1").
TEST(Planets, VenusApparentPlaceAgainstMeeus33a) {
  const double tt = 2448976.5;
  const UtcTime t = fromTt(tt, 0.0);
  const glm::dvec3 earth = heliocentricPositionM("Earth", t);
  const auto seen = planetsSeenFrom(earth, t);
  const auto venus = std::find_if(seen.begin(), seen.end(), [](const PlanetSeen& p) { return p.name == "Venus"; });
  ASSERT_NE(venus, seen.end());
  double pvh[2][3], pvb[2][3];
  eraEpv00(tt, 0.0, pvh, pvb);
  constexpr double kAuPerDayInC = ERFA_DAU / ERFA_CMPS / 86400.0;  // au/day in units of c
  double v[3], v2 = 0.0;
  for (int k = 0; k < 3; ++k) v[k] = pvb[1][k] * kAuPerDayInC, v2 += v[k] * v[k];
  const double sunDistanceAu = std::sqrt(pvh[0][0] * pvh[0][0] + pvh[0][1] * pvh[0][1] + pvh[0][2] * pvh[0][2]);
  double astrometric[3] = {venus->directionIcrs.x, venus->directionIcrs.y, venus->directionIcrs.z}, aberrated[3];
  eraAb(astrometric, v, sunDistanceAu, std::sqrt(1.0 - v2), aberrated);
  double npb[3][3], ofDate[3];
  eraPnm06a(tt, 0.0, npb);
  eraRxp(npb, aberrated, ofDate);
  double ra = 0.0, dec = 0.0;
  eraC2s(ofDate, &ra, &dec);
  ra = eraAnp(ra);
  const double meeusRa = (21.0 + 4.0 / 60.0 + 41.454 / 3600.0) * 15.0 * kDeg;
  const double meeusDec = -(18.0 + 53.0 / 60.0 + 16.84 / 3600.0) * kDeg;
  const double dRaArcsec = (ra - meeusRa) * std::cos(meeusDec) / kDeg * 3600.0;
  const double dDecArcsec = (dec - meeusDec) / kDeg * 3600.0;
  std::printf("  Venus apparent: RA %+.2f\" (on the sky), Dec %+.2f\" from Meeus 33.a; distance %.6f au (Meeus 0.910947)\n",
              dRaArcsec, dDecArcsec, venus->distanceAu);
  EXPECT_LT(std::abs(dRaArcsec), 6.0);
  EXPECT_LT(std::abs(dDecArcsec), 2.0);
  EXPECT_NEAR(venus->distanceAu, 0.910947, 1e-5);
}

TEST(Planets, SaturnsRingsEdgeOnToTheEarthOn2025March23) {
  // The Earth crossed Saturn's ring plane on 2025-03-23: the rings' tilt passes through 0
  // that day, from their north face (seen since 2009) to their south face. A year before
  // they were open by some 27 deg x sin(360 deg / 29.5) ~ 6 deg, give or take the Earth's
  // parallax.
  const auto saturnAt = [](const char* when) {
    const UtcTime t = parseUtc(when);
    for (const PlanetSeen& p : planetsSeenFrom(heliocentricPositionM("Earth", t), t))
      if (p.name == "Saturn") return p;
    throw std::runtime_error("no Saturn");
  };
  const PlanetSeen before = saturnAt("2025-03-22T00:00:00Z"), after = saturnAt("2025-03-25T00:00:00Z");
  std::printf("  Saturn's rings seen from the Earth: %+.4f deg on 03-22, %+.4f deg on 03-25\n", before.ringTiltDeg,
              after.ringTiltDeg);
  EXPECT_GT(before.ringTiltDeg, 0.0);
  EXPECT_LT(after.ringTiltDeg, 0.0);
  EXPECT_LT(before.ringTiltDeg - after.ringTiltDeg, 0.2);
  EXPECT_GT(saturnAt("2024-03-23T00:00:00Z").ringTiltDeg, 3.0);
  EXPECT_LT(saturnAt("2024-03-23T00:00:00Z").ringTiltDeg, 8.0);
  // Open to the Earth in 2032 (the authors' case's year), Saturn near opposition is brighter
  // than at the crossing, as its rings add ~0.8 mag.
  const PlanetSeen open = saturnAt("2032-12-25T00:00:00Z");
  std::printf("  2032-12-25: tilt %+.2f deg, V %.3f (Mallama & Hilton's case: 26.28 deg, -0.552)\n", open.ringTiltDeg,
              open.magnitudeV);
  EXPECT_NEAR(std::abs(open.ringTiltDeg), 26.28, 0.3);
  EXPECT_NEAR(open.magnitudeV, -0.552, 0.02);
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
  EXPECT_EQ(seen.size(), 4u);
  for (const PlanetSeen& p : seen) EXPECT_NE(p.name, "Mars");
}

}  // namespace
}  // namespace umbra::scene
