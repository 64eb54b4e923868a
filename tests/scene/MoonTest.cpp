// The Moon's numbers (app/scene/Moon.hpp) from the ephemeris against Meeus, Astronomical
// Algorithms (2nd ed.), examples 47.a, 48.a and 53.a: 1992 April 12, 0h TD.
#include "scene/Moon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace umbra::scene;

namespace {
const UtcTime kMeeusDate = fromTt(2448724.5, 0.0);  // 1992-04-12 0h TD (TT)
}

// Example 47.a: lambda 133.162655 deg, beta -3.229126 deg (geocentric, mean equinox of
// date), Delta 368 409.7 km: within 2 arcsec and 1 km.
TEST(Moon, PositionOfMeeus47a) {
  const MoonNumbers m = moonNumbers(kMeeusDate, std::nullopt);
  std::printf("  lambda %.6f deg, beta %.6f deg, Delta %.1f km\n", m.eclipticLongitudeDeg, m.eclipticLatitudeDeg,
              m.distanceKm);
  EXPECT_NEAR(m.eclipticLongitudeDeg, 133.162655, 2.0 / 3600.0);
  EXPECT_NEAR(m.eclipticLatitudeDeg, -3.229126, 2.0 / 3600.0);
  EXPECT_NEAR(m.distanceKm, 368409.7, 1.0);
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
