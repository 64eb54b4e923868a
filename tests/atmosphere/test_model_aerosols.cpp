// Aerosols: van de Hulst's scattering (Costa Eq. 17), the anomalous-diffraction
// extinction (Eq. 19-20) and absorption, the Earth and Mars presets' particles.
#include "Atmosphere.hpp"
#include "Components.hpp"
#include "Mie.hpp"
#include "ModelTestSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::atmosphere;
using umbra::test::kPi;

TEST(ModelAerosols, VanDeHulstScatteringFollowsEq17) {
  // T = 2, nu = 4, K = 0.0092 at 550 nm (Costa Table 1, Earth): 0.434 C pi (2 pi/lambda)^2 K
  const double C = (0.65 * 2.0 - 0.65) * 1e-16;
  const double k = 2.0 * kPi / 550e-9;
  EXPECT_NEAR(vanDeHulstScatteringPerM(2.0, 4.0, 0.0092, 550.0), 0.434 * C * kPi * k * k * 0.0092, 1e-20);
  EXPECT_NEAR(vanDeHulstScatteringPerM(2.0, 4.0, 0.0092, 550.0), 1.0641e-4, 0.0001e-4);
  // lambda^-(nu - 2) for a constant K; none at turbidity 1
  for (double nu : {3.0, 4.0}) {
    const double ratio = vanDeHulstScatteringPerM(3.0, nu, 1.0, 440.0) / vanDeHulstScatteringPerM(3.0, nu, 1.0, 680.0);
    EXPECT_NEAR(ratio, std::pow(680.0 / 440.0, nu - 2.0), 1e-12);
  }
  EXPECT_EQ(vanDeHulstScatteringPerM(1.0, 4.0, 1.0, 550.0), 0.0);
}

TEST(ModelAerosols, AnomalousDiffractionReducesToVanDeHulstsClassicFormula) {
  // k = 0: Q = 2 - (4/rho) sin rho + (4/rho^2)(1 - cos rho), rho = 4 pi r (m - 1) / lambda
  for (double r : {0.05e-6, 0.2e-6, 0.5e-6, 1.6e-6, 10e-6}) {
    const double rho = 4.0 * kPi * r * 0.33 / 550e-9;
    const double classic = 2.0 - 4.0 / rho * std::sin(rho) + 4.0 / (rho * rho) * (1.0 - std::cos(rho));
    EXPECT_NEAR(anomalousDiffractionExtinctionEfficiency(r, 1.33, 0.0, 550.0), classic, 1e-9 * classic) << r;
  }
  // the first maximum, Q = 3.17 near rho = 4.09 (van de Hulst 1957, Fig. 32)
  const double rAtMax = 4.09 * 550e-9 / (4.0 * kPi * 0.33);
  EXPECT_NEAR(anomalousDiffractionExtinctionEfficiency(rAtMax, 1.33, 0.0, 550.0), 3.17, 0.01);
}

TEST(ModelAerosols, AnomalousDiffractionLimitsAndSeriesBranch) {
  // large spheres: Q_ext -> 2 (the extinction paradox); absorbing ones: Q_abs -> 1
  EXPECT_NEAR(anomalousDiffractionExtinctionEfficiency(1e-3, 1.5, 0.01, 550.0), 2.0, 1e-3);
  EXPECT_NEAR(anomalousDiffractionAbsorptionEfficiency(1e-3, 0.01, 550.0), 1.0, 1e-3);
  // small spheres: Q_ext ~ rho^2 / 2 without absorption, Q_abs ~ 2 w / 3 with w = 4 x k
  const double r = 1e-9, rho = 4.0 * kPi * r * 0.5 / 550e-9;
  EXPECT_NEAR(anomalousDiffractionExtinctionEfficiency(r, 1.5, 0.0, 550.0), rho * rho / 2.0, 1e-3 * rho * rho / 2.0);
  const double w = 8.0 * kPi * r * 0.01 / 550e-9;
  EXPECT_NEAR(anomalousDiffractionAbsorptionEfficiency(r, 0.01, 550.0), 2.0 * w / 3.0, 1e-3 * 2.0 * w / 3.0);
  // the series (|rho (tan b + i)| < 0.1) and Eq. 19 agree across the switch
  const double rSwitch = 0.1 * 550e-9 / (4.0 * kPi * 0.5);
  const double below = anomalousDiffractionExtinctionEfficiency(rSwitch * (1 - 1e-9), 1.5, 0.001, 550.0);
  const double above = anomalousDiffractionExtinctionEfficiency(rSwitch * (1 + 1e-9), 1.5, 0.001, 550.0);
  EXPECT_NEAR(below / above, 1.0, 1e-7);
  // absorption never exceeds extinction
  for (double rr : {0.01e-6, 0.1e-6, 1e-6, 10e-6})
    for (double k : {0.0, 0.001, 0.01, 0.1, 1.0})
      EXPECT_LE(anomalousDiffractionAbsorptionEfficiency(rr, k, 550.0),
                anomalousDiffractionExtinctionEfficiency(rr, 1.52, k, 550.0) + 1e-12)
          << rr << " " << k;
}

TEST(ModelAerosols, EarthPresetHasBrunetonsAerosols) {
  const Atmosphere earth = loadAtmosphere("earth", umbra::test::threeWavelengthsNm());
  const Component& a = earth.component("aerosols");
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(a.scatteringPerM[i], 3.996e-6);
    EXPECT_NEAR(a.extinctionPerM(i), 5.328e-3 / 1200.0, 1e-18);  // Angstrom beta / H
    EXPECT_NEAR(a.scatteringPerM[i] / a.extinctionPerM(i), 0.9, 1e-12);
    EXPECT_EQ(a.phase(i).kind(), PhaseFunction::Kind::CornetteShanks);
    EXPECT_EQ(a.phase(i).g(), 0.8);
  }
  EXPECT_EQ(a.density.scaleHeightM, 1200.0);
}

TEST(ModelAerosols, MarsDustFollowsCostaTable1) {
  const Atmosphere mars = loadAtmosphere("mars", umbra::test::threeWavelengthsNm());  // 680, 550, 440
  const Component& dust = mars.component("dust");
  // extinction: Eq. 20 with r = 1.6 um, m = 1.52 + ik, N = 2.8e6: tau(550) = 0.494 over H = 11.1 km
  const double tau550 = mars.verticalOpticalDepth(dust, 0.0, 1e9)[1];
  EXPECT_NEAR(tau550, kPi * 1.6e-6 * 1.6e-6 * 1.977 * 2.8e6 * 11100.0, 0.002);
  // hematite's absorption rises to the blue: single-scattering albedo 0.98 (680), 0.87 (550), 0.74 (440)
  const double omega680 = dust.scatteringPerM[0] / dust.extinctionPerM(0);
  const double omega550 = dust.scatteringPerM[1] / dust.extinctionPerM(1);
  const double omega440 = dust.scatteringPerM[2] / dust.extinctionPerM(2);
  EXPECT_NEAR(omega680, 0.98, 0.01);
  EXPECT_NEAR(omega550, 0.87, 0.01);
  EXPECT_NEAR(omega440, 0.74, 0.02);
  // Henyey-Greenstein whose asymmetry is Lorenz-Mie theory's for the same sphere
  // (r = 1.6 um, m = 1.52 + ik): forward-peaked at every wavelength, blue the most. Costa's
  // Table 1 double Henyey-Greenstein has mean cosines 0.10, 0.87, 0.05 at 440, 550, 680 nm
  // (only green forward-peaked: a yellow-green day sky and a green sunset glow).
  const double k[3] = {0.001, 0.006, 0.013};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(dust.phase(i).kind(), PhaseFunction::Kind::HenyeyGreenstein);
    const double x = 2.0 * kPi * 1.6e-6 / (mars.wavelengthsNm[i] * 1e-9);
    EXPECT_NEAR(dust.phase(i).asymmetry(), mieSphere(x, {1.52, k[i]}).g, 0.002) << mars.wavelengthsNm[i];
  }
  EXPECT_GT(dust.phase(2).asymmetry(), dust.phase(1).asymmetry());
  EXPECT_GT(dust.phase(1).asymmetry(), dust.phase(0).asymmetry());
}

TEST(ModelAerosols, TabulatedComponentIsTheMieHook) {
  std::vector<PhaseFunction> phases(2, PhaseFunction::tabulatedDegrees({0.0, 90.0, 180.0}, {10.0, 1.0, 2.0}));
  const Component c = tabulatedComponent("mie", DensityProfile::exponential(1200.0), {1e-5, 2e-5}, {1e-6, 0.0}, phases);
  EXPECT_DOUBLE_EQ(c.extinctionPerM(0), 1.1e-5);
  EXPECT_TRUE(c.scatters());
  EXPECT_NEAR(umbra::test::integrateSphere([&](double mu) { return c.phase(1)(mu); }), 1.0, 1e-12);
  EXPECT_THROW(tabulatedComponent("mie", DensityProfile::exponential(1200.0), {1e-5, std::nan("")}, {0.0, 0.0}, phases),
               std::invalid_argument);
  EXPECT_THROW(tabulatedComponent("mie", DensityProfile::exponential(1200.0), {1e-5, 1e-5}, {0.0, -1e-7}, phases),
               std::invalid_argument);
  EXPECT_THROW(tabulatedComponent("mie", DensityProfile::exponential(1200.0), {1e-5}, {0.0}, phases),
               std::invalid_argument);
}
