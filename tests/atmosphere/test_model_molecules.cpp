// Molecular (Rayleigh) scattering, Costa Eq. 11, and the refractive-index formulas,
// against published coefficients.
#include "Atmosphere.hpp"
#include "Components.hpp"
#include "ModelTestSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::atmosphere;

namespace {
const double kN0C = 101325.0 / (kBoltzmannJPerK * 273.15);  // ideal gas at 0 degC, 1 atm
}

TEST(ModelMolecules, PeckReederGivesCostaTable1AirIndices) {
  // Costa Table 1, m(lambda) of air: 1.00027598 (680 nm), 1.00027783 (550 nm), to the
  // last printed digit
  EXPECT_NEAR(airRefractivityPeckReeder(680.0), 2.7598e-4, 1e-8);
  EXPECT_NEAR(airRefractivityPeckReeder(550.0), 2.7783e-4, 1e-8);
  // Costa's third value, 1.00028276, is the formula at 400 nm (at 440 nm it gives 2.8090e-4)
  EXPECT_NEAR(airRefractivityPeckReeder(400.0), 2.8276e-4, 2e-8);
  EXPECT_NEAR(airRefractivityPeckReeder(440.0), 2.8090e-4, 5e-9);
  // the eclipse paper's sea-level n = 1.000277 is standard air in the visible
  EXPECT_NEAR(airRefractivityPeckReeder(550.0), 2.77e-4, 1e-6);
}

TEST(ModelMolecules, BideauMehuCO2IndexIsWithinHalfAPercentOfCostaTable1) {
  // Costa Table 1: n_CO2 = 1.00044661, 1.00045019, 1.00045558 at 680, 550, 440 nm and 273 K;
  // the formula is for 288.15 K (ideal-gas scaling; CO2's compressibility is the rest)
  const double toZeroC = 288.15 / 273.15;
  EXPECT_NEAR(co2RefractivityBideauMehu(680.0) * toZeroC / 4.4661e-4, 1.0, 0.005);
  EXPECT_NEAR(co2RefractivityBideauMehu(550.0) * toZeroC / 4.5019e-4, 1.0, 0.005);
  EXPECT_NEAR(co2RefractivityBideauMehu(440.0) * toZeroC / 4.5558e-4, 1.0, 0.005);
  // and its dispersion between 440 and 680 nm agrees to 0.1 %
  EXPECT_NEAR(co2RefractivityBideauMehu(440.0) / co2RefractivityBideauMehu(680.0), 4.5558 / 4.4661, 1e-3);
}

TEST(ModelMolecules, Eq11WithNishitaInputsGivesBrunetonsCoefficients) {
  // Bruneton 2017 (and Riley/Hillaire after him): 5.802, 13.558, 33.1 e-6 1/m at 680, 550,
  // 440 nm. They are Eq. 11 with Nishita et al. 1993's n = 1.0003 at every wavelength,
  // N = 2.545e25 1/m^3 and delta = 0.035.
  EXPECT_NEAR(rayleighScatteringPerM(3.0e-4, 2.545e25, 680.0, 0.035), 5.802e-6, 0.005 * 5.802e-6);
  EXPECT_NEAR(rayleighScatteringPerM(3.0e-4, 2.545e25, 550.0, 0.035), 13.558e-6, 0.005 * 13.558e-6);
  EXPECT_NEAR(rayleighScatteringPerM(3.0e-4, 2.545e25, 440.0, 0.035), 33.1e-6, 0.005 * 33.1e-6);
}

TEST(ModelMolecules, Eq11WithStandardAirGivesPenndorfsTableThatCostaQuotes) {
  // Costa Table 1 (standard mode): 5.1768, 12.2588, 30.5964 e-6 1/m, Penndorf 1957's
  // Table III for 0 degC, 1013.25 hPa, delta = 0.035. Eq. 11 with Peck & Reeder's index
  // and the cross-section taken to 0 degC reproduces them to 0.05 %.
  const double lambdas[] = {680.0, 550.0, 440.0};
  const double costa[] = {5.1768e-6, 12.2588e-6, 30.5964e-6};
  for (int i = 0; i < 3; ++i) {
    const double sigma = rayleighCrossSectionM2(airRefractivityPeckReeder(lambdas[i]),
                                                kStandardNumberDensityPerM3, lambdas[i], 0.035);
    EXPECT_NEAR(sigma * kN0C, costa[i], 5e-4 * costa[i]) << lambdas[i];
  }
}

TEST(ModelMolecules, Eq11LiterallyReproducesCostasMarsCoefficients) {
  // Costa Table 1, Mars: (1.2871, 3.0560, 7.6406)e-3 1/m from n_CO2 at 1 atm, N = 2.8e23
  // and delta = 0.09 inserted into Eq. 11 as they stand...
  EXPECT_NEAR(rayleighScatteringPerM(4.4661e-4, 2.8e23, 680.0, 0.09), 1.2871e-3, 1e-4 * 1.2871e-3);
  EXPECT_NEAR(rayleighScatteringPerM(4.5019e-4, 2.8e23, 550.0, 0.09), 3.0560e-3, 1e-4 * 3.0560e-3);
  EXPECT_NEAR(rayleighScatteringPerM(4.5558e-4, 2.8e23, 440.0, 0.09), 7.6406e-3, 1e-4 * 7.6406e-3);
  // ...which is (N_1atm / N_Mars)^2 too large: n - 1 must shrink with the density.
  const double consistent = rayleighCrossSectionM2(4.5019e-4, kN0C, 550.0, 0.09) * 2.8e23;
  EXPECT_NEAR(3.0560e-3 / consistent, std::pow(kN0C / 2.8e23, 2), 1e-3 * std::pow(kN0C / 2.8e23, 2));
}

TEST(ModelMolecules, EarthPresetFollowsLambdaToTheMinusFourTimesDispersion) {
  const auto wl = umbra::test::fifteenWavelengthsNm();
  const Atmosphere earth = loadAtmosphere("earth", wl);
  const Component& air = earth.component("molecules");
  // beta lambda^4 / (n^2 - 1)^2 is the same at every wavelength
  auto reduced = [&](std::size_t i) {
    const double r = airRefractivityPeckReeder(wl[i]);
    return air.scatteringPerM[i] * std::pow(wl[i], 4) / std::pow(r * (2.0 + r), 2);
  };
  for (std::size_t i = 1; i < wl.size(); ++i) EXPECT_NEAR(reduced(i) / reduced(0), 1.0, 1e-12) << wl[i];
  // so blue is scattered more than lambda^-4 alone says: 7.8 % more from 830 to 360 nm
  const double pure = std::pow(wl.back() / wl.front(), 4);
  const double ratio = air.scatteringPerM.front() / air.scatteringPerM.back();
  EXPECT_NEAR(ratio / pure, std::pow(airRefractivityPeckReeder(360.0) / airRefractivityPeckReeder(830.0), 2), 1e-3);
  EXPECT_NEAR(ratio / pure, 1.078, 0.002);
}

TEST(ModelMolecules, EarthPresetIsStandardAirAt15DegreesC) {
  // The preset: 288.15 K, 101325 Pa, delta = 0.0279 (Costa Table 1). Penndorf's values
  // (Costa Table 1, 0 degC, delta 0.035) scaled by 273.15/288.15 and the King-factor ratio:
  const Atmosphere earth = loadAtmosphere("earth", umbra::test::threeWavelengthsNm());
  const Component& air = earth.component("molecules");
  const double scale = 273.15 / 288.15 * kingFactor(0.0279) / kingFactor(0.035);
  EXPECT_NEAR(air.scatteringPerM[0], 5.1768e-6 * scale, 1e-3 * 5.1768e-6 * scale);
  EXPECT_NEAR(air.scatteringPerM[1], 12.2588e-6 * scale, 1e-3 * 12.2588e-6 * scale);
  EXPECT_NEAR(air.scatteringPerM[2], 30.5964e-6 * scale, 1e-3 * 30.5964e-6 * scale);
  // i.e. 4.85, 11.48, 28.66 e-6 1/m: 16 % below Bruneton's 5.8, 13.6, 33.1 (Nishita's n)
  EXPECT_NEAR(air.scatteringPerM[1], 11.48e-6, 0.01e-6);
  EXPECT_NEAR(air.scatteringPerM[1] / 13.558e-6, 0.847, 0.005);
  EXPECT_EQ(air.phase(1).kind(), PhaseFunction::Kind::Penndorf);
  EXPECT_EQ(air.absorptionPerM[1], 0.0);
}

TEST(ModelMolecules, MarsPresetUsesTheCO2IndexScaledToMarsDensity) {
  const Atmosphere mars = loadAtmosphere("mars", umbra::test::threeWavelengthsNm());
  const Component& co2 = mars.component("molecules");
  for (std::size_t i = 0; i < 3; ++i) {
    const double lambda = mars.wavelengthsNm[i];
    const double expected =
        rayleighCrossSectionM2(co2RefractivityBideauMehu(lambda), kStandardNumberDensityPerM3, lambda, 0.09) * 2.8e23;
    EXPECT_NEAR(co2.scatteringPerM[i], expected, 1e-12 * expected);
  }
  // 3.29e-7 1/m at 550 nm: vertical optical depth 0.0026 with H = 8 km
  EXPECT_NEAR(co2.scatteringPerM[1], 3.29e-7, 0.01e-7);
}
