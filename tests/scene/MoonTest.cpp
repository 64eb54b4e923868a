// The Moon's numbers (app/scene/Moon.hpp) from the ephemeris against Meeus, Astronomical
// Algorithms (2nd ed.), examples 47.a, 48.a and 53.a: 1992 April 12, 0h TD.
#include "scene/Moon.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

using namespace umbra::scene;

namespace {
const UtcTime kMeeusDate = fromTt(2448724.5, 0.0);  // 1992-04-12 0h TD (TT)
}

// Example 47.a: lambda 133.162655 deg, beta -3.229126 deg (geocentric, mean equinox of
// date), Delta 368 409.7 km. Meeus computes them with his truncated series (ERFA's
// eraMoon98: 10 arcsec in longitude, 4 in latitude, 0.2 arcsec in parallax or about 20 km
// in distance, as he states); the scenes' Moon is ELP 2000-82B with every term, which
// differs from them by 1.1 and 0.3 arcsec and 4.1 km. Within 2 arcsec and 5 km.
TEST(Moon, PositionOfMeeus47a) {
  const MoonNumbers m = moonNumbers(kMeeusDate, std::nullopt);
  std::printf("  lambda %.6f deg, beta %.6f deg, Delta %.1f km\n", m.eclipticLongitudeDeg, m.eclipticLatitudeDeg,
              m.distanceKm);
  EXPECT_NEAR(m.eclipticLongitudeDeg, 133.162655, 2.0 / 3600.0);
  EXPECT_NEAR(m.eclipticLatitudeDeg, -3.229126, 2.0 / 3600.0);
  EXPECT_NEAR(m.distanceKm, 368409.7, 5.0);
  EXPECT_FALSE(m.topocentric);
  EXPECT_FALSE(m.altitudeDeg.has_value());
}

// Example 48.a: phase angle i 69.0756 deg, illuminated fraction k 0.6786, within 0.01 deg
// and 0.0005; the bright limb at 285.0 deg.
TEST(Moon, PhaseOfMeeus48a) {
  const MoonNumbers m = moonNumbers(kMeeusDate, std::nullopt);
  std::printf("  i %.4f deg, k %.4f, chi %.2f deg\n", m.phaseAngleDeg, m.illuminatedFraction,
              m.brightLimbPositionAngleDeg);
  EXPECT_NEAR(m.phaseAngleDeg, 69.0756, 0.01);
  EXPECT_NEAR(m.illuminatedFraction, 0.6786, 0.0005);
  EXPECT_NEAR(m.brightLimbPositionAngleDeg, 285.0, 0.1);
}

// Example 53.a: optical libration l' -1.206 deg, b' +4.194 deg, within 0.05 deg.
TEST(Moon, LibrationOfMeeus53a) {
  const MoonNumbers m = moonNumbers(kMeeusDate, std::nullopt);
  std::printf("  l' %.4f deg, b' %.4f deg\n", m.librationLongitudeDeg, m.librationLatitudeDeg);
  EXPECT_NEAR(m.librationLongitudeDeg, -1.206, 0.05);
  EXPECT_NEAR(m.librationLatitudeDeg, 4.194, 0.05);
}

// NASA's greatest eclipse of 2017-08-21 (Espenak, eclipse.gsfc.nasa.gov: 18:26:40.2 TD, at
// 36 58.0' N, 87 40.3' W; the Sun 63.9 deg up at azimuth 197.9 deg; the umbra 114.7 km
// wide, magnitude 1.0306): seen from that point at that instant the Sun stands where NASA
// puts it (to its 0.1 deg) and the Moon covers it whole, its centre within 15 arcseconds of the
// Sun's (eraMoon98 is good to about 10; the Moon's disc exceeds the Sun's by 29 there).
TEST(Moon, SunAndMoonInTheHorizonAtTheGreatestEclipseOf2017) {
  const UtcTime t = fromTt(2457986.5, 66400.2 / 86400.0);
  const Observer there{"Earth", 36.0 + 58.0 / 60.0, -(87.0 + 40.3 / 60.0), 0.0};
  const SunAndMoonInHorizon s = sunAndMoonInHorizon(t, there);
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double altitude = std::atan2(s.sunM.z, std::hypot(s.sunM.x, s.sunM.y)) / kDeg;
  double azimuth = std::atan2(s.sunM.x, s.sunM.y) / kDeg;
  if (azimuth < 0.0) azimuth += 360.0;
  const double separation = std::acos(std::clamp(glm::dot(glm::normalize(s.sunM), glm::normalize(s.moonM)), -1.0, 1.0));
  const double phiSun = std::asin(s.sunRadiusM / glm::length(s.sunM)), phiMoon = std::asin(s.moonRadiusM / glm::length(s.moonM));
  std::printf("  Sun altitude %.3f deg, azimuth %.3f deg; Moon - Sun %.1f arcsec apart, radii %.1f and %.1f arcsec\n",
              altitude, azimuth, separation / kDeg * 3600.0, phiMoon / kDeg * 3600.0, phiSun / kDeg * 3600.0);
  EXPECT_NEAR(altitude, 63.9, 0.06);
  EXPECT_NEAR(azimuth, 197.9, 0.06);
  EXPECT_LT(separation, 15.0 / 3600.0 * kDeg);
  EXPECT_NEAR(phiMoon / phiSun, 1.0306, 0.002);
  EXPECT_THROW(sunAndMoonInHorizon(t, Observer{"Mars", 0.0, 0.0, 0.0}), std::invalid_argument);
}
