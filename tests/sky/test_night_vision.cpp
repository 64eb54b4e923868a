// Night vision (sky/NightVision): Larson's scotopic luminance, the CIE 191 mesopic
// adaptation and the colour the eye sees, against their closed forms and limits.
#include "NightVision.hpp"
#include "StarLight.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace umbra::sky;

// V = Y (1.33 (1 + (Y + Z) / X) - 1.68): D65 white (0.9505, 1, 1.089) gives 2.573; no X, no V.
TEST(NightVision, ScotopicLuminanceOfLarsonEtAl) {
  EXPECT_NEAR(scotopicLuminance({0.9505, 1.0, 1.089}), 1.33 * (1.0 + 2.089 / 0.9505) - 1.68, 1e-12);
  EXPECT_NEAR(scotopicLuminance({9.505, 10.0, 10.89}), 10.0 * scotopicLuminance({0.9505, 1.0, 1.089}), 1e-9);
  EXPECT_EQ(scotopicLuminance({0.0, 1.0, 1.0}), 0.0);
  // Sunlight is a little less blue than D65: its ratio is lower.
  EXPECT_LT(sunlightScotopicRatio(), scotopicLuminance({0.9505, 1.0, 1.089}));
  EXPECT_GT(sunlightScotopicRatio(), 2.0);
  EXPECT_NEAR(sunlightEfficacyLmPerW(), 97.7, 1.0);
}

// The CIE 191 cones' share: 1 from 5 cd/m^2 up, 0 from 0.005 down; between, the fixed point
// of its equation; the GLSL's 8 steps from 0.5 within 1e-3 of it.
TEST(NightVision, MesopicAdaptationOfCie191) {
  EXPECT_EQ(mesopicConeShare(10.0, 25.0), 1.0);
  EXPECT_EQ(mesopicConeShare(1e-4, 2.5e-4), 0.0);
  for (double lp : {0.01, 0.1, 1.0}) {
    const double ls = 2.5 * lp, m = mesopicConeShare(lp, ls);
    const double v0 = 683.0 / 1699.0;
    const double mes = (m * lp + (1.0 - m) * ls * v0) / (m + (1.0 - m) * v0);
    EXPECT_GT(m, 0.0);
    EXPECT_LT(m, 1.0);
    EXPECT_NEAR(m, 0.7670 + 0.3334 * std::log10(mes), 1e-12) << "Lp " << lp;
    EXPECT_NEAR(mesopicConeShareIterated(lp, ls, 8), m, 1e-3) << "Lp " << lp;
  }
  EXPECT_THROW(mesopicConeShare(-1.0, 1.0), std::invalid_argument);
}

// The colour seen: unchanged in daylight; grey in starlight (1e-6 cd/m^2), sunlight's white
// keeping its value and a blue brighter than a red of the same luminance (Purkinje);
// between, the colour's distance from that grey scaled by m.
TEST(NightVision, ColourFadesToAScotopicGrey) {
  const glm::dvec3 day(100.0, 50.0, 20.0);
  const glm::dvec3 seen = nightVisionColour(day);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], day[c], 1e-9);

  const double k = sunlightEfficacyLmPerW();
  const glm::dvec3 white = glm::dvec3(1e-6 / k);  // 1e-6 cd/m^2 of sunlight
  const glm::dvec3 w = nightVisionColour(white);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[c], white[c], 1e-4 * white[c]);  // the 4-decimal sRGB matrices
  const glm::dvec3 blue = nightVisionColour(glm::dvec3(0.2, 0.4, 3.0) * (1e-6 / k)),
                   red = nightVisionColour(glm::dvec3(3.0, 0.4, 0.2) * (1e-6 / k));
  EXPECT_NEAR(blue.r, blue.b, 1e-15);
  EXPECT_NEAR(red.r, red.g, 1e-15);
  EXPECT_GT(blue.g, red.g);

  const glm::dvec3 dusk = glm::dvec3(3.0, 1.0, 0.5) * (0.05 / k);  // about 0.05 cd/m^2
  const glm::dvec3 d = nightVisionColour(dusk);
  const glm::dvec3 u = dusk * sunLinearSrgb() * k;
  const double lp = 0.2126 * u.r + 0.7152 * u.g + 0.0722 * u.b;
  const glm::dvec3 xyz(0.4124 * u.r + 0.3576 * u.g + 0.1805 * u.b, lp, 0.0193 * u.r + 0.1192 * u.g + 0.9505 * u.b);
  const double m = mesopicConeShareIterated(lp, scotopicLuminance(xyz), 8);
  const double grey = scotopicLuminance(xyz) / (k * sunlightScotopicRatio());
  EXPECT_GT(m, 0.1);
  EXPECT_LT(m, 0.9);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c] - grey, m * (dusk[c] - grey), 1e-12);
}
