// The Sun's disc cut by the horizon and covered by an occluder (terrain/EclipsedDisc.hpp):
// against the horizon alone (Eq. 7), the eclipse alone (eclipse/SolarDisc.hpp) and brute
// force over the disc, where the two cut the disc together.
#include "TerrainTestSupport.hpp"

#include "EclipsedDisc.hpp"
#include "SolarDisc.hpp"

#include <gtest/gtest.h>

using namespace umbra;
using namespace umbra::terrain;

// Without an occluder: Eq. 7's segment; with the Sun high above the horizon: the eclipse
// library's limb-darkened fraction for the same discs (a flat site), to 1e-6.
TEST(EclipsedDisc, EachAloneIsItsOwnClosedForm) {
  for (double d : {-0.7, -0.2, 0.0, 0.35, 0.9})
    EXPECT_NEAR(visibleFractionAboveHorizonOutside(d, {}, 0.0), test::segmentFraction(d), 1e-7) << d;
  for (const OccluderOnDisc& o : {OccluderOnDisc{0.3, -0.4, 0.6}, OccluderOnDisc{1.2, 0.5, 3.6}, OccluderOnDisc{0.0, 0.1, 3.6},
                                  OccluderOnDisc{-0.9, 0.0, 0.2}}) {
    for (double u : {0.0, 0.6}) {
      const double eclipse = eclipse::visibleFractionLimbDarkened(o.radius, std::hypot(o.x, o.y), u).value;
      EXPECT_NEAR(visibleFractionAboveHorizonOutside(3.0, o, u), eclipse, 1e-6)
          << o.x << ", " << o.y << ", r " << o.radius << ", u " << u;
    }
  }
}

// Both at once, against brute force (2000 x 2000 cells of the disc): an occluder beside,
// above and below the horizon's cut, the Earth from the Moon (3.6 solar radii) half over
// the disc; to 2e-4 (the sampling's own error). The product of the two fractions is not
// the answer: printed for the case where it is furthest off.
TEST(EclipsedDisc, HorizonAndOccluderTogetherAgreeWithBruteForce) {
  struct Case {
    double d;
    OccluderOnDisc o;
    double u;
  };
  double worstProduct = 0.0;
  for (const Case& c : {Case{0.2, {0.0, -0.8, 0.7}, 0.0}, Case{-0.3, {0.5, 0.3, 0.5}, 0.6}, Case{0.5, {-3.0, -1.5, 3.6}, 0.6},
                        Case{0.0, {0.9, 0.0, 0.4}, 0.0}, Case{0.7, {0.0, 0.9, 0.3}, 0.6}}) {
    const double exact = visibleFractionAboveHorizonOutside(c.d, c.o, c.u);
    const double sampled = visibleFractionAboveHorizonOutsideSampled(c.d, c.o, c.u, 2000);
    EXPECT_NEAR(exact, sampled, 2e-4) << "d " << c.d << ", occluder " << c.o.x << ", " << c.o.y << ", r " << c.o.radius;
    SunDisc sun;
    sun.limbDarkening = c.u;
    const double product = discFractionForOffset(c.d, sun) *
                           eclipse::visibleFractionLimbDarkened(c.o.radius, std::hypot(c.o.x, c.o.y), c.u).value;
    worstProduct = std::max(worstProduct, std::abs(product - exact));
  }
  std::printf("  the product of the two fractions is off by up to %.3f\n", worstProduct);
  EXPECT_GT(worstProduct, 0.05);  // (which is why they are not multiplied)
}

// The occluder's place on the disc: an occluder straight above the Sun by 0.5 deg, the Sun
// 0.25 deg in radius, is 2 radii up; beside it, 2 radii along the horizon.
TEST(EclipsedDisc, OccluderPlacedOnTheDisc) {
  const double r = 0.25 * test::kDeg;
  const glm::dvec3 up(0.0, 0.0, 1.0);
  const glm::dvec3 sun = sunDirectionFromElevationAzimuth(10.0 * test::kDeg, 90.0 * test::kDeg);
  const OccluderOnDisc above =
      occluderOnDisc(sun, r, sunDirectionFromElevationAzimuth(10.5 * test::kDeg, 90.0 * test::kDeg), 0.9 * test::kDeg, up);
  EXPECT_NEAR(above.x, 0.0, 1e-9);
  EXPECT_NEAR(above.y, 2.0, 1e-6);
  EXPECT_NEAR(above.radius, 3.6, 1e-12);
  const double beside = 0.5 * test::kDeg / std::cos(10.0 * test::kDeg);  // azimuth step of 0.5 deg on the sky
  const OccluderOnDisc side = occluderOnDisc(
      sun, r, sunDirectionFromElevationAzimuth(10.0 * test::kDeg, 90.0 * test::kDeg + beside), 0.9 * test::kDeg, up);
  EXPECT_NEAR(std::abs(side.x), 2.0, 1e-3);
  EXPECT_NEAR(side.y, 0.0, 0.01);
}
