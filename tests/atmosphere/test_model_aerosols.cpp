// Aerosols: van de Hulst's scattering (Costa Eq. 17), the anomalous-diffraction
// extinction (Eq. 19-20) and absorption, the Earth and Mars presets' particles (Mars' by
// Lorenz-Mie theory over a size distribution, the "mie" model).
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

TEST(ModelAerosols, EarthBrunetonPresetHasBrunetonsAerosols) {
  const Atmosphere earth = loadAtmosphere("earth-bruneton", umbra::test::threeWavelengthsNm());
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

TEST(ModelAerosols, MarsDustIsLorenzMieOverAPublishedSizeDistribution) {
  const Atmosphere mars = loadAtmosphere("mars", umbra::test::threeWavelengthsNm());  // 680, 550, 440
  const Component& dust = mars.component("dust");
  // Costa's index 1.52 + ik over a log-normal of r_eff = 1.5 um, v_eff = 0.3, N = 5.8e6:
  // the loader's quick quadrature against the default (tight) one.
  const double k[3] = {0.001, 0.006, 0.013};
  const LogNormalSizes sizes = logNormalFromEffective(1.5e-6, 0.3, 5.8e6);
  for (std::size_t i = 0; i < 3; ++i) {
    const MieAerosol ref = mieLogNormal(mars.wavelengthsNm[i] * 1e-9, {1.52, k[i]}, sizes, 181);
    EXPECT_NEAR(dust.scatteringPerM[i], ref.scatteringPerM, 1e-3 * ref.scatteringPerM) << mars.wavelengthsNm[i];
    EXPECT_NEAR(dust.absorptionPerM[i], ref.absorptionPerM, 1e-3 * ref.absorptionPerM) << mars.wavelengthsNm[i];
    ASSERT_EQ(dust.phase(i).kind(), PhaseFunction::Kind::Tabulated);
    EXPECT_NEAR(dust.phase(i).asymmetry(), ref.asymmetry, 2e-3) << mars.wavelengthsNm[i];
    for (int j = 0; j < 181; ++j)  // every degree: within 1 % (linear between the 0.5-degree samples)
      EXPECT_NEAR(dust.phase(i)(ref.cosTheta[j]), ref.phase[j], 0.01 * ref.phase[j]) << 180 - j << " deg";
  }
  // Typical of Mars outside dust storms: tau(550) = 0.49 over H = 11.1 km, nearly grey.
  const std::vector<double> tau = mars.verticalOpticalDepth(dust, 0.0, 1e9);
  EXPECT_NEAR(tau[1], 0.49, 0.005);
  EXPECT_NEAR(tau[0] / tau[2], 1.0, 0.1);
  // The absorption of the index rises to the blue: albedo 0.97 (680), 0.84 (550), 0.71 (440).
  const double omega680 = dust.scatteringPerM[0] / dust.extinctionPerM(0);
  const double omega550 = dust.scatteringPerM[1] / dust.extinctionPerM(1);
  const double omega440 = dust.scatteringPerM[2] / dust.extinctionPerM(2);
  EXPECT_GT(omega680, omega550);
  EXPECT_GT(omega550, omega440);
  EXPECT_GT(omega440, 0.6);
  // The diffraction peak of micron grains (~lambda / r wide) is narrower and taller in the
  // blue: blue dominates inside a few degrees (the blue glow of the Martian sunset), red
  // beyond ~10 degrees (eclipse paper, Figure 12: Mars' umbra red at Phobos and Deimos,
  // whose limb is 20 and 8 degrees from the Sun). Henyey-Greenstein with the same mean
  // cosines has blue above red out to 15 degrees (x 2 at 8 degrees).
  auto p = [&](std::size_t i, double deg) { return dust.phase(i)(std::cos(deg * kPi / 180.0)); };
  EXPECT_GT(p(2, 1.0), 2.0 * p(0, 1.0));
  EXPECT_GT(p(0, 12.0), 1.2 * p(2, 12.0));
  EXPECT_GT(p(0, 20.0), 1.3 * p(2, 20.0));
  EXPECT_GT(dust.phase(2).asymmetry(), dust.phase(1).asymmetry());
  EXPECT_GT(dust.phase(1).asymmetry(), dust.phase(0).asymmetry());
}

TEST(ModelAerosols, MieModelWithoutSpreadIsOneSphere) {
  // effectiveVariance 0 (or absent): every particle of radius r_eff, Lorenz-Mie's sphere.
  const std::string json = R"({"bottomRadiusM": 6.0e6, "topRadiusM": 6.06e6, "components": {"dust": {
      "density": {"type": "exponential", "scaleHeightM": 1000},
      "optics": {"model": "mie", "effectiveRadiusM": 1.6e-6, "numberDensityPerM3": 1e6,
                 "refractiveIndexReal": 1.52, "refractiveIndexImag": 0.006}}}})";
  const Atmosphere a = parseAtmosphere(json, "sphere.json", {550.0});
  const Component& c = a.component("dust");
  const MieEfficiencies q = mieSphere(2.0 * kPi * 1.6e-6 / 550e-9, {1.52, 0.006});
  const double area = kPi * 1.6e-6 * 1.6e-6 * 1e6;
  EXPECT_NEAR(c.scatteringPerM[0], q.qSca * area, 1e-12 * q.qSca * area);
  EXPECT_NEAR(c.extinctionPerM(0), q.qExt * area, 1e-12 * q.qExt * area);
  EXPECT_NEAR(c.phase(0).asymmetry(), q.g, 2e-3);
  EXPECT_NEAR(umbra::test::integrateSphere([&](double mu) { return c.phase(0)(mu); }), 1.0, 1e-9);
  // Bad input: one message naming the field.
  std::string bad = json;
  bad.replace(bad.find("1.6e-6"), 6, "-1e-6");
  try {
    parseAtmosphere(bad, "sphere.json", {550.0});
    ADD_FAILURE() << "accepted a negative effective radius";
  } catch (const AtmosphereError& e) {
    EXPECT_NE(std::string(e.what()).find("sphere.json: components.dust.optics.effectiveRadiusM: expected an effective radius"),
              std::string::npos)
        << e.what();
  }
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

// An OPAC component as an atmosphere file writes it (a "mie" model by mode radius, sigma
// and radius range, hygroscopicGrowth from OPAC's wet mode radii): at 80 % relative
// humidity the particle grows by 1.4434 and its index mixes with water's, and the
// coefficients at 550 nm for 1 particle per cm^3 are OPAC's "waso80" row (extinction
// 9.584e-3, scattering 9.434e-3 per 1000 km; Hess, Koepke & Schult 1998) within 0.5 %; dry,
// its "waso00" row (3.905e-3, 3.755e-3).
TEST(ModelAerosols, OpacWaterSolubleGrowsWithHumidity) {
  auto document = [](double humidity) {
    return std::string(R"({"bottomRadiusM": 6371000, "topRadiusM": 6471000, "relativeHumidity": )") +
           std::to_string(humidity) + R"(,
      "components": {"waso": {"density": {"type": "exponential", "scaleHeightM": 2000},
        "optics": {"model": "mie", "medianRadiusM": 0.0212e-6, "geometricStdDev": 2.24,
                   "radiusRangeM": [0.005e-6, 20e-6], "numberDensityPerM3": 1e6,
                   "refractiveIndexReal": 1.53, "refractiveIndexImag": 0.006,
                   "hygroscopicGrowth": {"relativeHumidity": [0, 0.5, 0.7, 0.8, 0.9],
                                         "radiusFactor": [1, 1.2358, 1.3443, 1.4434, 1.6415]}}}}})";
  };
  struct Case {
    double humidity, extPer1000Km, scaPer1000Km;
  };
  for (const Case c : {Case{0.0, 3.905e-3, 3.755e-3}, Case{0.8, 9.584e-3, 9.434e-3}}) {
    const Atmosphere a = parseAtmosphere(document(c.humidity), "waso.json", {550.0});
    const Component& w = a.component("waso");
    EXPECT_NEAR(w.extinctionPerM(0) * 1e6 / c.extPer1000Km, 1.0, 5e-3) << c.humidity;
    EXPECT_NEAR(w.scatteringPerM[0] * 1e6 / c.scaPer1000Km, 1.0, 5e-3) << c.humidity;
  }
  EXPECT_THROW(parseAtmosphere(document(1.0), "waso.json", {550.0}), AtmosphereError);
}

// A "mixture" (an OPAC aerosol type) is its parts in one density: the coefficients of the
// parts read as components of their own add up, and the phase function is their
// scattering-weighted mean.
TEST(ModelAerosols, MixtureAddsItsPartsCoefficientsAndMixesTheirPhases) {
  const std::string small = R"({"model": "mie", "medianRadiusM": 0.0212e-6, "geometricStdDev": 2.24,
      "numberDensityPerM3": 7e9, "refractiveIndexReal": 1.53, "refractiveIndexImag": 0.006})";
  const std::string large = R"({"model": "mie", "medianRadiusM": 0.471e-6, "geometricStdDev": 2.51,
      "numberDensityPerM3": 4e5, "refractiveIndexReal": 1.53, "refractiveIndexImag": 0.008})";
  const std::string density = R"({"type": "exponential", "scaleHeightM": 2000})";
  const std::string head = R"({"bottomRadiusM": 6371000, "topRadiusM": 6471000, "components": )";
  const Atmosphere mixed = parseAtmosphere(head + R"({"haze": {"density": )" + density +
                                               R"(, "optics": {"model": "mixture", "of": {"small": )" + small +
                                               R"(, "large": )" + large + "}}}}}",
                                           "mixed.json", umbra::test::threeWavelengthsNm());
  const Atmosphere apart = parseAtmosphere(head + R"({"small": {"density": )" + density + R"(, "optics": )" + small +
                                               R"(}, "large": {"density": )" + density + R"(, "optics": )" + large + "}}}",
                                           "apart.json", umbra::test::threeWavelengthsNm());
  const Component &h = mixed.component("haze"), &s = apart.component("small"), &l = apart.component("large");
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(h.scatteringPerM[i], s.scatteringPerM[i] + l.scatteringPerM[i]);
    EXPECT_DOUBLE_EQ(h.absorptionPerM[i], s.absorptionPerM[i] + l.absorptionPerM[i]);
    const double ws = s.scatteringPerM[i] / h.scatteringPerM[i];
    EXPECT_NEAR(h.phase(i).asymmetry(), ws * s.phase(i).asymmetry() + (1.0 - ws) * l.phase(i).asymmetry(), 1e-9);
    EXPECT_NEAR(h.phase(i)(1.0), ws * s.phase(i)(1.0) + (1.0 - ws) * l.phase(i)(1.0), 1e-9 * h.phase(i)(1.0));
  }
  // A part without a phase of its own cannot be mixed.
  try {
    parseAtmosphere(head + R"({"haze": {"density": )" + density +
                        R"(, "optics": {"model": "mixture", "of": {"c": {"model": "coefficients", "scatteringPerM": 1e-6}}}}}})",
                    "bad.json", {550.0});
    ADD_FAILURE() << "no error";
  } catch (const AtmosphereError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: components.haze.optics.of.c: expected a model with its own phase"),
              std::string::npos)
        << e.what();
  }
}

// "aerosolOpticalDepth550" scales the components marked "aerosol" together (their ratios
// kept), at whatever wavelengths the run has: their vertical optical depth at 550 nm is the
// requested one, the others' (the stratosphere's) are untouched, and a second wavelength set
// gives the same.
TEST(ModelAerosols, AerosolOpticalDepthScalesTheMarkedComponents) {
  const Atmosphere rgb = loadAtmosphere("earth", umbra::test::threeWavelengthsNm());  // 680, 550, 440
  auto tauOf = [](const Atmosphere& a, const char* name, std::size_t l) {
    return a.verticalOpticalDepth(a.component(name), 0.0, a.thicknessM())[l];
  };
  EXPECT_NEAR(tauOf(rgb, "troposphere", 1), 0.1, 1e-12);
  // OPAC's stratospheric background: 3 sulphate droplets per cm^3 over 12-35 km, 7.120e-5 /km
  // per particle per cm^3 at 550 nm (the package's suso00 file): 0.00491.
  EXPECT_NEAR(tauOf(rgb, "stratosphere", 1), 3.0 * 7.120e-5 * 23.0, 0.005 * 3.0 * 7.120e-5 * 23.0);
  const Atmosphere bruneton = loadAtmosphere("earth-bruneton", umbra::test::threeWavelengthsNm());
  EXPECT_EQ(rgb.component("molecules").scatteringPerM, bruneton.component("molecules").scatteringPerM);
  EXPECT_EQ(rgb.find("aerosols"), nullptr);
  EXPECT_EQ(bruneton.find("troposphere"), nullptr);
  // The turbid sky: three times the particles, the same mixture; the same stratosphere.
  const Atmosphere turbid = loadAtmosphere("earth-turbid", umbra::test::threeWavelengthsNm());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(turbid.component("troposphere").absorptionPerM[i] / rgb.component("troposphere").absorptionPerM[i], 3.0,
                1e-9);
    EXPECT_EQ(turbid.component("stratosphere").scatteringPerM[i], rgb.component("stratosphere").scatteringPerM[i]);
  }
  // Without 550 nm among the wavelengths: 545 and 555 nm bracket it.
  const Atmosphere pair = loadAtmosphere("earth", {545.0, 555.0});
  EXPECT_GT(tauOf(pair, "troposphere", 0), 0.1);
  EXPECT_LT(tauOf(pair, "troposphere", 1), 0.1);
  const std::string noAerosol = R"({"bottomRadiusM": 6371000, "topRadiusM": 6471000, "aerosolOpticalDepth550": 0.1,
    "components": {"air": {"density": {"type": "exponential", "scaleHeightM": 8000},
      "optics": {"model": "coefficients", "scatteringPerM": 1e-5}, "phase": {"type": "isotropic"}}}})";
  try {
    parseAtmosphere(noAerosol, "t.json", {550.0});
    ADD_FAILURE() << "no error";
  } catch (const AtmosphereError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: aerosolOpticalDepth550: no component has \"aerosol\": true"),
              std::string::npos)
        << e.what();
  }
}
