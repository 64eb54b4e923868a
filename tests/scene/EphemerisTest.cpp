#include "scene/Ephemeris.hpp"
#include "scene/Units.hpp"

#include <erfa.h>
#include <erfam.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

using namespace umbra::scene;

namespace {

constexpr double kDeg = ERFA_DD2R;

double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) / kDeg;
}

glm::dvec3 unitFromRaDec(double raDeg, double decDeg) {
  return {std::cos(decDeg * kDeg) * std::cos(raDeg * kDeg),
          std::cos(decDeg * kDeg) * std::sin(raDeg * kDeg), std::sin(decDeg * kDeg)};
}

void expectRotation(const glm::dmat3& m) {
  const glm::dmat3 identity = glm::transpose(m) * m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(identity[i][j], i == j ? 1.0 : 0.0, 1e-12);
  EXPECT_NEAR(glm::determinant(m), 1.0, 1e-12);
}

} // namespace

// The years ERFA's Earth ephemeris is fitted to: no note inside, one naming the time outside.
TEST(Ephemeris, RangeNoteOutside1900To2100) {
  EXPECT_EQ(ephemerisRangeNote(parseUtc("2026-10-26T04:00:00Z")), "");
  EXPECT_EQ(ephemerisRangeNote(parseUtc("1901-01-01T00:00:00Z")), "");
  for (const char* t : {"1850-01-01T00:00:00Z", "2150-01-01T00:00:00Z"}) {
    const std::string note = ephemerisRangeNote(parseUtc(t));
    EXPECT_EQ(note.rfind(std::string("note: ") + std::string(t).substr(0, 10), 0), 0u) << note;
    EXPECT_NE(note.find("outside 1900-2100"), std::string::npos) << note;
  }
}

TEST(Ephemeris, SunIsTheOrigin) {
  EXPECT_EQ(heliocentricPositionM("Sun", parseUtc("2015-09-28T02:47Z")), glm::dvec3(0.0));
}

TEST(Ephemeris, EarthSunDistanceOn2015September28) {
  const UtcTime t = parseUtc("2015-09-28T00:00Z");
  const double au = glm::length(heliocentricPositionM("Earth", t)) / kAuM;
  // Independent rough value: the Astronomical Almanac's low-precision Sun formula,
  // r = 1.00014 - 0.01671 cos g - 0.00014 cos 2g, g = 357.529 + 0.98560028 n (n days
  // from J2000): 1.00224 au on that date.
  const double n = (t.jd1 - 2451545.0) + t.jd2;
  const double g = (357.529 + 0.98560028 * n) * kDeg;
  const double almanacAu = 1.00014 - 0.01671 * std::cos(g) - 0.00014 * std::cos(2.0 * g);
  EXPECT_NEAR(au, almanacAu, 1e-4);
  EXPECT_NEAR(au, 1.0027, 1e-3);
}

TEST(Ephemeris, SupermoonPerigeeAtTheEclipseMaximum) {
  // 2015-09-28 02:47 UTC: greatest eclipse; perigee (356 877 km) came about an hour earlier.
  const UtcTime t = parseUtc("2015-09-28T02:47Z");
  const glm::dvec3 earth = heliocentricPositionM("Earth", t);
  const glm::dvec3 moon = heliocentricPositionM("Moon", t);
  EXPECT_NEAR(glm::length(moon - earth) / 1e3, 356900.0, 1000.0);
  // The Moon is in Earth's shadow: almost exactly opposite the Sun (gamma = -0.33).
  EXPECT_LT(angleDeg(moon - earth, earth), 0.5);
}

TEST(Ephemeris, MarsStaysBetweenPerihelionAndAphelion) {
  for (const char* when : {"2015-09-28T00:00Z", "2018-07-31T00:00Z", "2030-01-01T00:00Z"}) {
    const double au = glm::length(heliocentricPositionM("Mars", parseUtc(when))) / kAuM;
    EXPECT_GT(au, 1.3814) << when;
    EXPECT_LT(au, 1.6660) << when;
  }
}

TEST(Ephemeris, OnlyFourBodiesHaveAnEphemeris) {
  EXPECT_TRUE(hasEphemeris("Earth"));
  EXPECT_FALSE(hasEphemeris("Phobos"));
  try {
    heliocentricPositionM("Phobos", parseUtc("2015-09-28T00:00Z"));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no ephemeris for 'Phobos': give its position explicitly in metres");
  }
  EXPECT_THROW(bodyFixedToInertial("Deimos", parseUtc("2015-09-28T00:00Z")),
               std::invalid_argument);
}

TEST(Ephemeris, RotationsAreProperRotations) {
  const UtcTime t = parseUtc("2015-09-28T01:45Z");
  for (const char* body : {"Sun", "Earth", "Moon", "Mars"}) {
    SCOPED_TRACE(body);
    expectRotation(bodyFixedToInertial(body, t));
  }
}

TEST(Ephemeris, GreenwichPointsAtMeanSiderealTime) {
  // The point lat 0, lon 0 lies at right ascension GMST in the mean equator and equinox
  // of date (nutation moves it by < 0.001 deg there). Independent path: eraGmst06 and the
  // bias-precession matrix eraPmat06.
  for (const char* when : {"2015-09-28T01:45Z", "2000-01-01T12:00Z", "2024-04-08T18:17Z"}) {
    SCOPED_TRACE(when);
    const UtcTime t = parseUtc(when);
    const glm::dvec3 greenwich = bodyFixedToInertial("Earth", t) * glm::dvec3(1.0, 0.0, 0.0);
    double tt1 = 0.0, tt2 = 0.0;
    toTt(t, tt1, tt2);
    double rbp[3][3];
    eraPmat06(tt1, tt2, rbp);
    double v[3] = {greenwich.x, greenwich.y, greenwich.z}, ofDate[3];
    eraRxp(rbp, v, ofDate);
    const double raDeg = std::atan2(ofDate[1], ofDate[0]) / kDeg;
    const double gmstDeg = eraGmst06(t.jd1, t.jd2, tt1, tt2) / kDeg;
    EXPECT_NEAR(std::remainder(raDeg - gmstDeg, 360.0), 0.0, 0.01);
    EXPECT_NEAR(std::asin(ofDate[2]) / kDeg, 0.0, 0.01);
  }
}

TEST(Ephemeris, EarthPoleIsNearIcrsZ) {
  // Precession moves the pole about 0.0056 deg per year from the J2000 pole.
  const glm::dvec3 pole =
      bodyFixedToInertial("Earth", parseUtc("2015-09-28T01:45Z")) * glm::dvec3(0, 0, 1);
  EXPECT_NEAR(angleDeg(pole, {0, 0, 1}), 15.74 * 0.0056, 0.01);
}

TEST(Ephemeris, IauPoleAndPrimeMeridian) {
  const glm::dmat3 m = iauBodyFixedToInertial(269.9949, 66.5392, 0.0);
  EXPECT_LT(angleDeg(m * glm::dvec3(0, 0, 1), unitFromRaDec(269.9949, 66.5392)), 1e-12);
  // W = 0: the prime meridian passes through the node Q of the body's equator on the
  // ICRS equator, at right ascension alpha0 + 90 deg.
  EXPECT_LT(angleDeg(m * glm::dvec3(1, 0, 0), unitFromRaDec(269.9949 + 90.0, 0.0)), 1e-12);
  // W grows eastwards: at W = 90 the +y axis is where +x was.
  const glm::dmat3 m90 = iauBodyFixedToInertial(269.9949, 66.5392, 90.0);
  EXPECT_LT(angleDeg(m90 * glm::dvec3(0, -1, 0), unitFromRaDec(269.9949 + 90.0, 0.0)), 1e-12);
}

TEST(Ephemeris, MoonFacesEarthWithinLibration) {
  // The sub-Earth point on the Moon stays within the libration range (|lat| < 7 deg,
  // |lon| < 8 deg), give or take the model's accuracy.
  for (const char* when : {"2015-09-28T02:47Z", "2020-06-01T00:00Z", "2024-01-15T00:00Z"}) {
    SCOPED_TRACE(when);
    const UtcTime t = parseUtc(when);
    const glm::dvec3 toEarth = heliocentricPositionM("Earth", t) - heliocentricPositionM("Moon", t);
    const glm::dvec3 local = glm::transpose(bodyFixedToInertial("Moon", t)) * glm::normalize(toEarth);
    EXPECT_LT(std::abs(std::asin(local.z) / kDeg), 9.0);
    EXPECT_LT(std::abs(std::atan2(local.y, local.x) / kDeg), 10.0);
  }
}

TEST(Ephemeris, MoonsSpinAxisStaysAtCassinisInclinationToTheEcliptic) {
  // Cassini's laws: the Moon's pole precesses about the ecliptic pole in 18.6 years at a
  // constant 1.54 deg (the IAU model's periodic E1 terms); the constant terms alone would
  // leave it within 0.03 deg of the ecliptic pole.
  const glm::dvec3 eclipticPole = unitFromRaDec(270.0, 90.0 - 23.4392911);
  for (const char* when : {"2000-01-01T12:00Z", "2004-08-01T00:00Z", "2009-03-01T00:00Z", "2013-10-01T00:00Z",
                           "2024-01-15T00:00Z"}) {
    SCOPED_TRACE(when);
    const glm::dvec3 pole = bodyFixedToInertial("Moon", parseUtc(when)) * glm::dvec3(0, 0, 1);
    EXPECT_NEAR(angleDeg(pole, eclipticPole), 1.54, 0.07);  // + the monthly terms (E2, E3)
  }
}

// The Sun from a body's centre in its body-fixed frame (scene::sunFromBody, the Sun of
// `umbra terrain shadow --time`): on Earth its declination is 0 at the March equinox
// (2024-03-20 03:06 UTC) and +23.44 deg at the June solstice (2024-06-20 20:51 UTC); at
// 12:00 UTC on 2024-03-20 it stands 1.8 deg east of Greenwich (the equation of time,
// -7.3 min: it transits at 12:07 UTC); at perihelion (2024-01-03) it is 0.98331 au away,
// 16.27' in radius (16'16" for the Sun's 696 342 km). From the Moon (axis 1.54 deg to the ecliptic) it stays within 1.6 deg
// of the equator.
TEST(Ephemeris, SunFromBodyGivesDeclinationHourAngleAndDistance) {
  const auto declinationDeg = [](const SunFromBody& s) { return std::asin(s.directionBodyFixed.z) / kDeg; };
  EXPECT_NEAR(declinationDeg(sunFromBody("Earth", parseUtc("2024-03-20T03:06Z"))), 0.0, 0.01);
  EXPECT_NEAR(declinationDeg(sunFromBody("Earth", parseUtc("2024-06-20T20:51Z"))), 23.44, 0.01);
  const SunFromBody noon = sunFromBody("Earth", parseUtc("2024-03-20T12:00Z"));
  EXPECT_NEAR(std::atan2(noon.directionBodyFixed.y, noon.directionBodyFixed.x) / kDeg, 1.8, 0.1);
  EXPECT_NEAR(glm::length(noon.directionBodyFixed), 1.0, 1e-12);
  const SunFromBody perihelion = sunFromBody("Earth", parseUtc("2024-01-03T00:39Z"));
  EXPECT_NEAR(perihelion.distanceM / 1.495978707e11, 0.98331, 0.00003);
  EXPECT_NEAR(perihelion.angularRadiusRad / kDeg * 60.0, 16.27, 0.01);
  for (const char* time : {"2024-01-01T00:00Z", "2024-04-10T00:00Z", "2024-07-15T00:00Z", "2024-11-02T00:00Z"})
    EXPECT_LT(std::abs(declinationDeg(sunFromBody("Moon", parseUtc(time)))), 1.6) << time;
  EXPECT_THROW(sunFromBody("Sun", parseUtc("2024-01-01T00:00Z")), std::invalid_argument);
  EXPECT_THROW(sunFromBody("Phobos", parseUtc("2024-01-01T00:00Z")), std::invalid_argument);
}

// Meeus, Astronomical Algorithms (2nd ed.), example 32.a: Venus on 1992-12-20 at 0h TD,
// heliocentric on the mean ecliptic and equinox of date (VSOP87): L = 26.11428 deg,
// B = -2.62070 deg, R = 0.724603 au. eraPlan94 rotated to that ecliptic (eraEcm06) agrees
// within its documented few arcseconds.
TEST(Ephemeris, VenusAgainstMeeus32a) {
  const UtcTime t = fromTt(2448976.5, 0.0);
  const glm::dvec3 p = planetHeliocentricPositionM("Venus", t) / kAuM;
  double rm[3][3];
  eraEcm06(2448976.5, 0.0, rm);
  const glm::dvec3 e(rm[0][0] * p.x + rm[0][1] * p.y + rm[0][2] * p.z, rm[1][0] * p.x + rm[1][1] * p.y + rm[1][2] * p.z,
                     rm[2][0] * p.x + rm[2][1] * p.y + rm[2][2] * p.z);
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  double L = std::atan2(e.y, e.x) / kDeg;
  if (L < 0.0) L += 360.0;
  const double B = std::atan2(e.z, std::hypot(e.x, e.y)) / kDeg, R = glm::length(e);
  std::printf("  Venus L %.5f deg, B %.5f deg, R %.6f au\n", L, B, R);
  EXPECT_NEAR(L, 26.11428, 5.0 / 3600.0);
  EXPECT_NEAR(B, -2.62070, 5.0 / 3600.0);
  EXPECT_NEAR(R, 0.724603, 2e-6);
  EXPECT_THROW(planetHeliocentricPositionM("Pluto", t), std::invalid_argument);
  EXPECT_THROW(planetHeliocentricPositionM("", t), std::invalid_argument);
  // Mars through both routes.
  EXPECT_EQ(planetHeliocentricPositionM("Mars", t), heliocentricPositionM("Mars", t));
}
