// Absorbers (Costa Eq. 13-15): the ozone layer and the O2 A band of the Earth preset.
#include "Atmosphere.hpp"
#include "ModelTestSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::atmosphere;

TEST(ModelAbsorbers, OzoneAbsorptionPeaksInTheChappuisBandNear600nm) {
  std::vector<double> wl;
  for (double l = 400.0; l <= 800.0; l += 5.0) wl.push_back(l);
  const Atmosphere earth = loadAtmosphere("earth", wl);
  const Component& ozone = earth.component("ozone");
  std::size_t peak = 0;
  for (std::size_t i = 0; i < wl.size(); ++i) {
    EXPECT_EQ(ozone.scatteringPerM[i], 0.0);
    if (ozone.absorptionPerM[i] > ozone.absorptionPerM[peak]) peak = i;
  }
  EXPECT_GE(wl[peak], 590.0);
  EXPECT_LE(wl[peak], 610.0);
  // at the peak: 5.374e18 1/m^3 x 5.019e-25 m^2 (Serdyuchenko 2014 at 233 K, 600-610 nm)
  EXPECT_NEAR(ozone.absorptionPerM[peak], 5.374e18 * 5.019e-25, 1e-9 * 5.374e18 * 5.019e-25);
  // Chappuis is a broad hump: 10x weaker at 450 nm and at 750 nm than at the peak
  EXPECT_LT(ozone.absorptionPerM[10] * 10.0, ozone.absorptionPerM[peak]);  // 450 nm
  EXPECT_LT(ozone.absorptionPerM[70] * 10.0, ozone.absorptionPerM[peak]);  // 750 nm
}

TEST(ModelAbsorbers, OzoneCrossSectionsInterpolateLinearlyInWavelength) {
  const Atmosphere earth = loadAtmosphere("earth", {545.0, 550.0, 555.0, 300.0, 900.0});
  const Component& ozone = earth.component("ozone");
  EXPECT_NEAR(ozone.absorptionPerM[1], 5.374e18 * 3.5e-25, 1e-9 * ozone.absorptionPerM[1]);
  EXPECT_NEAR(ozone.absorptionPerM[0], 5.374e18 * 0.5 * (3.091e-25 + 3.5e-25), 1e-9 * ozone.absorptionPerM[0]);
  EXPECT_NEAR(ozone.absorptionPerM[2], 5.374e18 * 0.5 * (3.5e-25 + 4.266e-25), 1e-9 * ozone.absorptionPerM[2]);
  // beyond the table: its end values
  EXPECT_NEAR(ozone.absorptionPerM[3], 5.374e18 * 1.18e-27, 1e-9 * ozone.absorptionPerM[3]);
  EXPECT_NEAR(ozone.absorptionPerM[4], 5.374e18 * 7.105e-27, 1e-9 * ozone.absorptionPerM[4]);
}

TEST(ModelAbsorbers, OzoneColumnIs300DobsonUnitsInATentAt25km) {
  const Atmosphere earth = loadAtmosphere("earth", {600.0});
  const Component& ozone = earth.component("ozone");
  EXPECT_EQ(ozone.density.kind, DensityProfile::Kind::Tent);
  EXPECT_EQ(ozone.density.centreM, 25000.0);
  EXPECT_EQ(ozone.density.halfWidthM, 15000.0);
  const double tau = earth.verticalOpticalDepth(ozone, 0.0, earth.thicknessM())[0];
  // 300 DU = 8.061e22 molecules/m^2, times 5.019e-25 m^2: 0.0405 at 600 nm
  EXPECT_NEAR(tau, 300.0 * 2.687e20 * 5.019e-25, 1e-9 * tau);
}

TEST(ModelAbsorbers, OxygenAbsorbsOnlyInTheABandWithLecknersOneAirMassTransmittance) {
  const Atmosphere earth = loadAtmosphere("earth", {550.0, 687.0, 760.0, 770.0, 800.0});
  const Component& o2 = earth.component("oxygen");
  EXPECT_EQ(o2.absorptionPerM[0], 0.0);
  EXPECT_EQ(o2.absorptionPerM[1], 0.0);
  EXPECT_EQ(o2.absorptionPerM[4], 0.0);
  // vertical optical depth = 1.41 k / (1 + 118.93 k)^0.45 (Leckner 1978), k = 3.0 and 0.21
  const std::vector<double> tau = earth.verticalOpticalDepth(o2, 0.0, 1e9);
  EXPECT_NEAR(tau[2], 1.41 * 3.0 / std::pow(1.0 + 118.93 * 3.0, 0.45), 1e-4);
  EXPECT_NEAR(tau[3], 1.41 * 0.21 / std::pow(1.0 + 118.93 * 0.21, 0.45), 1e-4);
  // Costa Eq. 14: 20.95 % of the molecules, following the same exponential
  EXPECT_EQ(o2.density.kind, DensityProfile::Kind::Exponential);
  EXPECT_EQ(o2.density.scaleHeightM, earth.component("molecules").density.scaleHeightM);
}
