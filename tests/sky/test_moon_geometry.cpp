// How the Moon is seen (sky/MoonGeometry.hpp) against Meeus, Astronomical Algorithms
// (2nd ed.), examples 48.a and 53.a (1992 April 12, 0h TD): the formulas fed with the
// example's own inputs.
#include "MoonGeometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::sky;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

// Example 48.a: the Sun at RA 20.6579 deg, Dec +8.6964 deg, the Moon at RA 134.688470 deg,
// Dec +13.768368 deg: the bright limb at position angle 285.0 deg; i = 69.0756 deg gives
// k = 0.6786.
TEST(MoonGeometry, BrightLimbAndIlluminatedFractionOfMeeus48a) {
  EXPECT_NEAR(brightLimbPositionAngle(20.6579 * kDeg, 8.6964 * kDeg, 134.688470 * kDeg, 13.768368 * kDeg) / kDeg,
              285.0, 0.05);
  EXPECT_NEAR(illuminatedFraction(69.0756 * kDeg), 0.6786, 0.00005);
  // A waning Moon (the Sun west of it) has its bright limb towards the west, near 90 deg.
  EXPECT_NEAR(brightLimbPositionAngle(0.0, 0.0, 0.5, 0.0) / kDeg, 270.0, 1e-9);
  EXPECT_NEAR(brightLimbPositionAngle(0.5, 0.0, 0.0, 0.0) / kDeg, 90.0, 1e-9);
}

// Example 53.a: lambda 133.167265 deg (apparent) less the nutation 0.004610 deg, beta
// -3.229127 deg, Omega 274.400656 deg, F 219.889726 deg: l' = -1.206 deg, b' = +4.194 deg.
TEST(MoonGeometry, OpticalLibrationOfMeeus53a) {
  const Libration l = opticalLibration((133.167265 - 0.004610) * kDeg, -3.229127 * kDeg, 274.400656 * kDeg,
                                       219.889726 * kDeg);
  EXPECT_NEAR(l.longitudeRad / kDeg, -1.206, 0.0005);
  EXPECT_NEAR(l.latitudeRad / kDeg, 4.194, 0.0005);
}

// The angle between two vectors keeps its digits near 0 and pi, where acos does not.
TEST(MoonGeometry, AngleBetween) {
  const glm::dvec3 x(1.0, 0.0, 0.0);
  EXPECT_NEAR(angleBetween(x, {1.0, 1e-9, 0.0}), 1e-9, 1e-20);
  EXPECT_NEAR(angleBetween(x, {-1.0, 1e-9, 0.0}), 3.14159265358979323846 - 1e-9, 1e-15);
  EXPECT_DOUBLE_EQ(angleBetween(x, {0.0, 5.0, 0.0}), 0.5 * 3.14159265358979323846);
  EXPECT_EQ(angleBetween(x, 2.0 * x), 0.0);
}
