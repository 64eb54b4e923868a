// The shipped presets: they load for 3 and 15 wavelengths, their sums, refractivity and
// the 2015 Calbuco variant's stratospheric optical depth.
#include "Atmosphere.hpp"
#include "ModelTestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace umbra::atmosphere;

TEST(ModelPresets, TheThreePresetsAreListed) {
  const std::vector<std::string> names = presetNames();
  for (const char* name : {"earth", "mars", "earth-2015-calbuco"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(ModelPresets, EveryPresetLoadsWithFiniteNonNegativeCoefficients) {
  for (const std::string& name : presetNames()) {
    for (const auto& wl : {umbra::test::threeWavelengthsNm(), umbra::test::fifteenWavelengthsNm()}) {
      const Atmosphere a = loadAtmosphere(name, wl);
      EXPECT_EQ(a.validate(), "") << name;
      EXPECT_EQ(a.wavelengthsNm, wl);
      EXPECT_GT(a.topRadiusM, a.bottomRadiusM);
      ASSERT_FALSE(a.components.empty());
      for (const Component& c : a.components) {
        ASSERT_EQ(c.scatteringPerM.size(), wl.size()) << name << " " << c.name;
        ASSERT_EQ(c.absorptionPerM.size(), wl.size());
        ASSERT_EQ(c.phases.size(), wl.size());
        for (std::size_t i = 0; i < wl.size(); ++i) {
          EXPECT_TRUE(std::isfinite(c.scatteringPerM[i]) && c.scatteringPerM[i] >= 0.0) << name << " " << c.name;
          EXPECT_TRUE(std::isfinite(c.absorptionPerM[i]) && c.absorptionPerM[i] >= 0.0) << name << " " << c.name;
        }
      }
      for (double h : {0.0, 1000.0, 25000.0, a.thicknessM()})
        for (double beta : a.extinctionPerM(h)) EXPECT_TRUE(std::isfinite(beta) && beta >= 0.0) << name;
      for (double tau : a.verticalOpticalDepth(0.0, a.thicknessM())) EXPECT_TRUE(std::isfinite(tau) && tau > 0.0);
    }
  }
}

TEST(ModelPresets, ExtinctionIsTheSumOfTheComponentsScaledByTheirProfiles) {
  const Atmosphere earth = loadAtmosphere("earth-bruneton", umbra::test::threeWavelengthsNm());
  for (double h : {0.0, 3000.0, 25000.0, 70000.0}) {
    const std::vector<double> total = earth.extinctionPerM(h), sca = earth.scatteringPerM(h),
                              abs = earth.absorptionPerM(h);
    for (std::size_t i = 0; i < 3; ++i) {
      double expected = 0.0;
      for (const Component& c : earth.components) expected += c.density.at(h) * c.extinctionPerM(i);
      EXPECT_NEAR(total[i], expected, 1e-15 * expected);
      EXPECT_NEAR(sca[i] + abs[i], total[i], 1e-15 * expected);
    }
  }
  // at the ground, 550 nm: air 1.148e-5 + aerosols 4.44e-6 + a trace of ozone (0 at h = 0)
  EXPECT_NEAR(earth.extinctionPerM(0.0)[1], 11.483e-6 + 4.44e-6, 0.005e-6);
}

TEST(ModelPresets, RefractivityFollowsTheMolecularDensityWithDispersion) {
  const Atmosphere earth = loadAtmosphere("earth", umbra::test::threeWavelengthsNm());
  EXPECT_NEAR(earth.refractivity(0.0, 550.0), 2.77e-4, 1e-18);  // eclipse paper: n = 1.000277
  EXPECT_NEAR(earth.refractivity(8000.0, 550.0), 2.77e-4 / std::exp(1.0), 1e-18);
  EXPECT_NEAR(earth.refractivity(0.0, 440.0) / earth.refractivity(0.0, 680.0),
              airRefractivityPeckReeder(440.0) / airRefractivityPeckReeder(680.0), 1e-14);
  const Atmosphere mars = loadAtmosphere("mars", umbra::test::threeWavelengthsNm());
  EXPECT_NEAR(mars.refractivity(0.0, 550.0), 3.38e-6, 1e-20);  // eclipse paper, section 2.3
  EXPECT_NEAR(mars.refractivity(16000.0, 550.0), 3.38e-6 * std::exp(-2.0), 1e-20);
  EXPECT_GT(mars.refractivity(0.0, 440.0), mars.refractivity(0.0, 680.0));
}

// earth-2015-calbuco: earth with three times the stratospheric sulphate (0.0049 -> 0.015 at
// 550 nm: Calbuco's 0.01 on OPAC's background), everything else earth's.
TEST(ModelPresets, CalbucoIsEarthWithThreeTimesTheStratosphere) {
  const auto wl = umbra::test::fifteenWavelengthsNm();
  const Atmosphere earth = loadAtmosphere("earth", wl);
  const Atmosphere calbuco = loadAtmosphere("earth-2015-calbuco", wl);
  const double L = earth.thicknessM();
  ASSERT_EQ(L, calbuco.thicknessM());
  const std::vector<double> tauEarth = earth.verticalOpticalDepth(earth.component("stratosphere"), 0.0, L);
  const std::vector<double> tauCalbuco = calbuco.verticalOpticalDepth(calbuco.component("stratosphere"), 0.0, L);
  for (std::size_t i = 0; i < wl.size(); ++i) EXPECT_NEAR(tauCalbuco[i] / tauEarth[i], 3.0, 1e-12);
  const Atmosphere at550 = loadAtmosphere("earth-2015-calbuco", {550.0});
  EXPECT_NEAR(at550.verticalOpticalDepth(at550.component("stratosphere"), 0.0, L)[0], 0.0148, 0.0005);
  EXPECT_EQ(calbuco.name, "earth-2015-calbuco");
  EXPECT_EQ(calbuco.components.size(), earth.components.size());
  for (const char* same : {"molecules", "troposphere", "ozone"}) {
    EXPECT_EQ(calbuco.component(same).scatteringPerM, earth.component(same).scatteringPerM) << same;
    EXPECT_EQ(calbuco.component(same).absorptionPerM, earth.component(same).absorptionPerM) << same;
  }
  EXPECT_EQ(calbuco.seaLevelRefractivity, earth.seaLevelRefractivity);
}

// earth-volcanic: earth with four times the stratospheric sulphate (0.0049 -> 0.020 at
// 550 nm), the troposphere and the rest unchanged.
TEST(ModelPresets, VolcanicIsEarthWithFourTimesTheStratosphere) {
  const Atmosphere earth = loadAtmosphere("earth", umbra::test::threeWavelengthsNm());
  const Atmosphere volcanic = loadAtmosphere("earth-volcanic", umbra::test::threeWavelengthsNm());
  const double L = earth.thicknessM();
  const double tauEarth = earth.verticalOpticalDepth(earth.component("stratosphere"), 0.0, L)[1];
  EXPECT_NEAR(volcanic.verticalOpticalDepth(volcanic.component("stratosphere"), 0.0, L)[1] / tauEarth, 4.0, 1e-12);
  EXPECT_NEAR(4.0 * tauEarth, 0.0197, 0.0003);
  EXPECT_EQ(volcanic.component("troposphere").scatteringPerM, earth.component("troposphere").scatteringPerM);
  EXPECT_EQ(volcanic.components.size(), earth.components.size());
}

// The boundary layer's height moves the tropospheric aerosol up or down; with
// aerosolOpticalDepth550 its vertical optical depth stays the requested one.
TEST(ModelPresets, BoundaryLayerHeightMovesTheAerosolNotItsOpticalDepth) {
  const Atmosphere low = parseAtmosphere(R"({"extends": "earth", "boundaryLayerHeightM": 1000})", "low.json", {550.0});
  const Atmosphere high = parseAtmosphere(R"({"extends": "earth", "boundaryLayerHeightM": 3000})", "high.json", {550.0});
  const Component &a = low.component("troposphere"), &b = high.component("troposphere");
  EXPECT_EQ(a.density.boundaryLayerTopM, 1000.0);
  EXPECT_EQ(b.density.boundaryLayerTopM, 3000.0);
  EXPECT_NEAR(low.verticalOpticalDepth(a, 0.0, low.thicknessM())[0], 0.1, 1e-12);
  EXPECT_NEAR(high.verticalOpticalDepth(b, 0.0, high.thicknessM())[0], 0.1, 1e-12);
  // At 2 km: above the low layer's top (its free troposphere), inside the high one.
  EXPECT_LT(a.extinctionPerM(0) * a.density.at(2000.0), 0.2 * b.extinctionPerM(0) * b.density.at(2000.0));
  try {
    parseAtmosphere(R"({"extends": "earth", "boundaryLayerHeightM": 20000})", "bad.json", {550.0});
    ADD_FAILURE() << "no error";
  } catch (const AtmosphereError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: components.troposphere.density.freeTroposphere.topM: expected an "
                                         "altitude at or above the boundary layer's top (20000 m), got 12000"),
              std::string::npos)
        << e.what();
  }
}

TEST(ModelPresets, LoadsFromAPathToo) {
  const Atmosphere viaPath = loadAtmosphere(presetDirectory() + "/mars.json", {550.0});
  EXPECT_EQ(viaPath.name, "mars");
  EXPECT_EQ(viaPath.component("dust").scatteringPerM, loadAtmosphere("mars", {550.0}).component("dust").scatteringPerM);
}
