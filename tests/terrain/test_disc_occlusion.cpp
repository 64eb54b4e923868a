// Disc occlusion (terrain paper Eq. 6-7) and its limb-darkened variant.
#include "SolarDisc.hpp"
#include "TerrainTestSupport.hpp"

#include <gtest/gtest.h>

using namespace umbra;
using umbra::test::segmentFraction;

TEST(DiscOcclusion, UniformDiscIsTheCircularSegmentOfEq7) {
  for (double d = -1.0; d <= 1.0; d += 1.0 / 64) EXPECT_NEAR(eclipse::visibleFractionAboveHorizon(d), segmentFraction(d), 1e-13) << d;
  EXPECT_DOUBLE_EQ(eclipse::visibleFractionAboveHorizon(-2.0), 0.0);
  EXPECT_DOUBLE_EQ(eclipse::visibleFractionAboveHorizon(3.0), 1.0);
  EXPECT_NEAR(eclipse::visibleFractionAboveHorizon(0.0), 0.5, 1e-15);
  // A thin sliver keeps its relative accuracy: area of a cap of sagitta h -> (4 sqrt 2 / 3) h^1.5 / pi.
  const double h = 1e-9;
  EXPECT_NEAR(eclipse::visibleFractionAboveHorizon(-1.0 + h), 4.0 * std::sqrt(2.0) / 3.0 * std::pow(h, 1.5) / test::kPi,
              1e-6 * std::pow(h, 1.5));
}

TEST(DiscOcclusion, LimbDarkenedMatchesA2dQuadratureOfEq1) {
  for (double u : {0.3, 0.6, 1.0}) {
    for (double d : {-0.9, -0.5, -0.1, 0.0, 0.3, 0.77}) {
      // Midpoint rule over the disc in polar-free Cartesian cells.
      const int n = 1200;
      double visible = 0.0, total = 0.0;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const double x = -1.0 + (a + 0.5) * 2.0 / n, y = -1.0 + (b + 0.5) * 2.0 / n;
          const double rho2 = x * x + y * y;
          if (rho2 >= 1.0) continue;
          const double I = 1.0 - u * (1.0 - std::sqrt(1.0 - rho2));
          total += I;
          if (y > -d) visible += I;
        }
      EXPECT_NEAR(eclipse::visibleFractionAboveHorizonLimbDarkened(d, u), visible / total, 2e-4) << u << " " << d;
    }
    // Symmetry: what is hidden at d is what is visible at -d.
    for (double d : {0.1, 0.45, 0.99})
      EXPECT_NEAR(eclipse::visibleFractionAboveHorizonLimbDarkened(d, u) +
                      eclipse::visibleFractionAboveHorizonLimbDarkened(-d, u), 1.0, 1e-14);
  }
  // Limb darkening concentrates flux at the centre: half a disc more visible than the uniform's
  // fraction when the centre is up.
  EXPECT_GT(eclipse::visibleFractionAboveHorizonLimbDarkened(0.5, 0.6), eclipse::visibleFractionAboveHorizon(0.5));
}
