// Star places (scene/Stars) against ERFA's own observed places (eraAtco13, no refraction):
// the direction umbra computes, turned into the observer's horizon by the scene's Earth
// rotation, lands within 1" of ERFA's azimuth and zenith distance.
#include "scene/Ephemeris.hpp"
#include "scene/Stars.hpp"

#include <erfa.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace umbra;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kArcsec = kDeg / 3600.0;

// Rows of kstars-data's stars.dat.
const char* const kRows[] = {
    "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, Sirius",
    "183656.34 +384701.3 +000201.0+000287.500128.9 00.03-0.00A0 0            , alp Lyr, Vega",
    "023149.09 +891550.8 +000044.2-000011.700007.6 01.9700.64F7 0 0.04   3.97, alp UMi, Polaris",
    "143936.50 -605002.3 -003678.2+000481.800742.1 -0.0100.71G2 1            , alp1Cen, Rigel Kentaurus"};

/// ERFA's observed azimuth (from north through east) and zenith distance, without
/// refraction (pressure 0), UT1 = UTC and no polar motion, as the scene assumes.
glm::dvec2 erfaAzZd(const sky::CatalogueStar& s, scene::UtcTime t, double latDeg, double lonDeg, double altM) {
  const double mas = kArcsec / 1000.0;
  double aob, zob, hob, dob, rob, eo;
  const int status = eraAtco13(s.raRad, s.decRad, s.pmRaCosDecMasPerYear * mas / std::cos(s.decRad),
                               s.pmDecMasPerYear * mas, s.parallaxMas / 1000.0, 0.0, t.jd1, t.jd2, 0.0, lonDeg * kDeg,
                               latDeg * kDeg, altM, 0.0, 0.0, 0.0, 0.0, 0.0, 0.55, &aob, &zob, &hob, &dob, &rob, &eo);
  EXPECT_GE(status, 0);
  return {aob, zob};
}

glm::dvec2 umbraAzZd(const glm::dvec3& directionGcrs, scene::UtcTime t, double latDeg, double lonDeg) {
  const glm::dvec3 d = glm::transpose(scene::bodyFixedToInertial("Earth", t)) * directionGcrs;
  const double phi = latDeg * kDeg, lambda = lonDeg * kDeg;
  const glm::dvec3 up(std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi));
  const glm::dvec3 east(-std::sin(lambda), std::cos(lambda), 0.0);
  const glm::dvec3 north = glm::cross(up, east);
  double az = std::atan2(glm::dot(d, east), glm::dot(d, north));
  if (az < 0.0) az += 2.0 * 3.14159265358979323846;
  return {az, std::acos(glm::dot(d, up))};
}

/// The Earth on the WGS84 ellipsoid, which eraAtco13 puts its observers on.
scene::Body wgs84Earth() {
  scene::Body earth;
  earth.name = earth.preset = "Earth";
  earth.equatorialRadiusM = 6378137.0;
  earth.polarRadiusM = 6378137.0 * (1.0 - 1.0 / 298.257223563);
  earth.radiusM = (2.0 * earth.equatorialRadiusM + earth.polarRadiusM) / 3.0;
  earth.positionM = {1.5e11, 0.0, 0.0};  // observerOnEarth takes it away again
  return earth;
}

scene::StarObserver observerAt(double latDeg, double lonDeg, double altM, scene::UtcTime t) {
  return scene::observerOnEarth(wgs84Earth(), scene::Observer{"Earth", latDeg, lonDeg, altM}, t);
}

double separation(glm::dvec2 a, glm::dvec2 b) {  // between two (az, zd) points
  const auto unit = [](glm::dvec2 p) {
    return glm::dvec3(std::sin(p.y) * std::cos(p.x), std::sin(p.y) * std::sin(p.x), std::cos(p.y));
  };
  return std::acos(std::min(1.0, glm::dot(unit(a), unit(b))));
}

}  // namespace

TEST(StarPlaces, WithinAnArcsecondOfErfaObservedPlaces) {
  struct Site {
    double latDeg, lonDeg, altM;
  };
  for (const Site site : {Site{52.52, 13.40, 34.0}, Site{-30.24, -70.74, 2200.0}, Site{89.9, 0.0, 0.0}}) {
    for (const char* when : {"2026-10-26T22:00:00Z", "2015-09-28T02:47:00Z", "2100-01-01T00:00:00Z"}) {
      const scene::UtcTime t = scene::parseUtc(when);
      const scene::StarObserver observer = observerAt(site.latDeg, site.lonDeg, site.altM, t);
      for (const char* row : kRows) {
        const sky::CatalogueStar star = *sky::parseKStarsLine(row);
        SCOPED_TRACE(star.name + " at " + when + " from latitude " + std::to_string(site.latDeg));
        const glm::dvec2 ours = umbraAzZd(scene::apparentStarDirection(star, t, observer), t, site.latDeg, site.lonDeg);
        const glm::dvec2 erfa = erfaAzZd(star, t, site.latDeg, site.lonDeg, site.altM);
        EXPECT_LT(separation(ours, erfa) / kArcsec, 1.0);
      }
    }
  }
}

// Aberration and proper motion are there: the apparent place differs from the catalogue's
// J2000 place by about the annual aberration (up to 20.5"), and a century's proper motion
// of Rigel Kentaurus (3.7"/yr in RA) moves it by minutes of arc.
TEST(StarPlaces, AberrationAndProperMotionMoveTheStar) {
  const sky::CatalogueStar vega = *sky::parseKStarsLine(kRows[1]);
  const scene::UtcTime t = scene::parseUtc("2000-01-01T12:00:00Z");
  const glm::dvec3 catalogue(std::cos(vega.decRad) * std::cos(vega.raRad), std::cos(vega.decRad) * std::sin(vega.raRad),
                             std::sin(vega.decRad));
  const double moved = std::acos(glm::dot(catalogue, scene::apparentStarDirection(vega, t, scene::StarObserver{})));
  EXPECT_GT(moved / kArcsec, 5.0);
  EXPECT_LT(moved / kArcsec, 21.0);

  const sky::CatalogueStar alphaCen = *sky::parseKStarsLine(kRows[3]);
  const glm::dvec3 a2000 = scene::apparentStarDirection(alphaCen, t, scene::StarObserver{});
  const glm::dvec3 a2100 = scene::apparentStarDirection(alphaCen, scene::parseUtc("2100-01-01T12:00:00Z"), scene::StarObserver{});
  EXPECT_NEAR(std::acos(glm::dot(a2000, a2100)) / kArcsec, 100.0 * std::hypot(3678.2, 481.8) / 1000.0, 30.0);
}

// The extremes: observers at the poles, 1 au from the Earth, dates 2000 years off: unit
// vectors, never NaN; an observer at the Sun's centre is refused.
TEST(StarPlaces, ExtremesGiveUnitDirectionsOrAClearError) {
  const sky::CatalogueStar polaris = *sky::parseKStarsLine(kRows[2]);
  const sky::CatalogueStar alphaCen = *sky::parseKStarsLine(kRows[3]);
  for (const char* when : {"0026-06-01T00:00:00Z", "2026-06-01T00:00:00Z", "4026-06-01T00:00:00Z"}) {
    const scene::UtcTime t = scene::parseUtc(when);
    for (double lat : {90.0, -90.0}) {
      const scene::StarObserver pole = observerAt(lat, 0.0, 0.0, t);
      for (const auto* star : {&polaris, &alphaCen}) {
        const glm::dvec3 d = scene::apparentStarDirection(*star, t, pole);
        EXPECT_NEAR(glm::length(d), 1.0, 1e-12) << when << " latitude " << lat;
      }
    }
    const scene::StarObserver farAway{{149597870700.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    EXPECT_NEAR(glm::length(scene::apparentStarDirection(alphaCen, t, farAway)), 1.0, 1e-12) << when;
    const glm::dvec3 sunFromEarth = scene::heliocentricPositionM("Sun", t) - scene::heliocentricPositionM("Earth", t);
    EXPECT_THROW(scene::apparentStarDirection(alphaCen, t, scene::StarObserver{sunFromEarth, {}}), std::invalid_argument);
  }
  // A 2000-year baseline: Rigel Kentaurus has moved by 2000 x 3.7" = 2 deg.
  const glm::dvec3 a = scene::apparentStarDirection(alphaCen, scene::parseUtc("0026-06-01T00:00:00Z"), {});
  const glm::dvec3 b = scene::apparentStarDirection(alphaCen, scene::parseUtc("2026-06-01T00:00:00Z"), {});
  EXPECT_NEAR(std::acos(glm::dot(a, b)) / kDeg, 2000.0 * std::hypot(3678.2, 481.8) / 1000.0 / 3600.0, 0.05);
}
