// Lines of sight through the shipped presets: refraction and transmittance.
#include "Atmosphere.hpp"
#include "SightLines.hpp"
#include "Spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::atmosphere;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
const std::vector<double> kRgb{680.0, 550.0, 440.0};
} // namespace

TEST(SightLines, EarthHorizontalRayBendsAboutSixTenthsOfADegree) {
  const Atmosphere earth = loadAtmosphere("earth", kRgb);
  const SightLine horizontal = traceSightLine(earth, 0.0, 90.0 * kDeg);
  EXPECT_GT(horizontal.deviationRad / kDeg, 0.55);
  EXPECT_LT(horizontal.deviationRad / kDeg, 0.65);
  EXPECT_FALSE(horizontal.hitGround);
  // Through ~38 air masses of Rayleigh + aerosol + ozone: blue far dimmer than red.
  EXPECT_LT(horizontal.transmittance[2], horizontal.transmittance[0]);
  EXPECT_GT(horizontal.transmittance[0], 0.0);
}

TEST(SightLines, MarsHorizontalDeviationIsBelowOnePercentOfEarths) {
  const double earth = traceSightLine(loadAtmosphere("earth", kRgb), 0.0, 90.0 * kDeg).deviationRad;
  const double mars = traceSightLine(loadAtmosphere("mars", kRgb), 0.0, 90.0 * kDeg).deviationRad;
  EXPECT_GT(mars, 0.0);
  EXPECT_LT(mars, 0.01 * earth);
}

TEST(SightLines, ZenithTransmittanceIsTheVerticalOpticalDepth) {
  for (const char* preset : {"earth", "mars", "earth-2015-calbuco"}) {
    const Atmosphere a = loadAtmosphere(preset, kRgb);
    const SightLine up = traceSightLine(a, 0.0, 0.0);
    const std::vector<double> tau = a.verticalOpticalDepth(0.0, a.thicknessM());
    EXPECT_NEAR(up.deviationRad, 0.0, 1e-12) << preset;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(up.transmittance[c], std::exp(-tau[c]), 1e-4 * std::exp(-tau[c])) << preset;
  }
}

TEST(SightLines, RaysBelowTheHorizonFromTheGroundAreBlocked) {
  const Atmosphere earth = loadAtmosphere("earth", kRgb);
  const SightLine down = traceSightLine(earth, 0.0, 91.0 * kDeg);
  EXPECT_TRUE(down.hitGround);
  EXPECT_LT(down.contactAltitudeM, 0.0);
  for (double t : down.transmittance) EXPECT_EQ(t, 0.0);
  // from 10 km up, a ray 2 degrees below the horizontal grazes above the ground
  const SightLine grazing = traceSightLine(earth, 10e3, 92.0 * kDeg);
  EXPECT_FALSE(grazing.hitGround);
  EXPECT_GT(grazing.contactAltitudeM, 0.0);
  EXPECT_LT(grazing.contactAltitudeM, 10e3);
}

TEST(SightLines, RedAndBlueBendByLessThanTwoHundredthsOfADegreeMore) {
  const Atmosphere earth = loadAtmosphere("earth", kRgb);
  const double red = traceRay(refractiveMedium(earth, 680.0), earth.bottomRadiusM, 0.0).deviationRad;
  const double blue = traceRay(refractiveMedium(earth, 440.0), earth.bottomRadiusM, 0.0).deviationRad;
  EXPECT_GT(blue, red);  // normal dispersion: n - 1 grows towards the blue
  EXPECT_LT((blue - red) / kDeg, 0.02);
}

// The one refractive medium: its n - 1 is Atmosphere::refractivity at every wavelength, its
// derivative that of n - 1 (against a central difference, 1 m apart), and it keeps its
// numbers when the atmosphere it came from is gone.
TEST(SightLines, OneMediumWithTheRefractivitysDerivative) {
  for (const char* preset : {"earth", "mars"}) {
    RefractiveMedium medium;
    std::vector<double> expected, slopes;
    const std::vector<double> heights{0.0, 3000.0, 11000.0, 40000.0};
    {
      const Atmosphere atm = loadAtmosphere(preset, kRgb);
      medium = refractiveMedium(atm, 440.0);
      for (double h : heights) {
        expected.push_back(atm.refractivity(h, 440.0));
        slopes.push_back((atm.refractivity(h + 1.0, 440.0) - atm.refractivity(h - 1.0, 440.0)) / 2.0);
      }
    }
    ASSERT_TRUE(medium.refractivityDerivativePerM) << preset;
    for (std::size_t i = 0; i < heights.size(); ++i) {
      EXPECT_NEAR(medium.refractivity(heights[i]), expected[i], 1e-15 * expected[i] + 1e-30) << preset << " " << heights[i];
      EXPECT_NEAR(medium.refractivityDerivativePerM(heights[i]), slopes[i], 1e-6 * std::abs(slopes[i]) + 1e-30)
          << preset << " " << heights[i];
    }
  }
}
