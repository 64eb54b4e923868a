// Earthshine (sky/Earthshine.hpp): the paper's cubic against Jensen et al.'s closed form,
// and the irradiance of the full Earth.
#include "Earthshine.hpp"
#include "Colour.hpp"
#include "Photometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace umbra::sky;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

// Eq. 4 of the paper is within 3 % of Jensen's closed form (of its largest value, at new
// Moon) over the whole phase range, and both are 0 at full Moon.
TEST(Earthshine, PaperWithinThreePercentOfJensen) {
  const double largest = earthshineJensen(kPi);
  EXPECT_DOUBLE_EQ(largest, 0.095);
  double worst = 0.0, worstAt = 0.0;
  for (int k = 0; k <= 1800; ++k) {
    const double phi = k * kPi / 1800.0;
    const double d = std::abs(earthshinePaper(phi) - earthshineJensen(phi));
    if (d > worst) worst = d, worstAt = phi;
  }
  std::printf("  largest |paper - Jensen| %.4f at %.1f deg (%.1f %% of %.3f)\n", worst, worstAt * 180.0 / kPi,
              100.0 * worst / largest, largest);
  EXPECT_LT(worst, 0.03 * largest);
  EXPECT_EQ(earthshinePaper(0.0), 0.0);
  EXPECT_NEAR(earthshineJensen(0.0), 0.0, 1e-15);
}

// The full Earth (new Moon) lights the Moon with E_sun p_E (R_E / d)^2; a half Earth with
// less, a thin crescent with nothing; no NaN at the ends.
TEST(Earthshine, IrradianceOfTheEarth) {
  const double eSun = 1361.0, p = 0.367, r = 6371.0e3, d = 384400.0e3;
  const double full = earthshineIrradiance(eSun, p, r, d, 0.0);
  EXPECT_NEAR(full, eSun * p * (r / d) * (r / d), 1e-12 * full);
  EXPECT_NEAR(full, 0.137, 0.001);  // 1e-4 of the sunlight
  const double half = earthshineIrradiance(eSun, p, r, d, 0.5 * kPi);
  EXPECT_GT(half, 0.2 * full);
  EXPECT_LT(half, 0.5 * full);
  EXPECT_EQ(earthshineIrradiance(eSun, p, r, d, kPi), 0.0);
  EXPECT_EQ(earthshineIrradiance(eSun, p, r, r, 0.0), 0.0);  // inside the Earth: none
  EXPECT_TRUE(std::isfinite(earthshineIrradiance(eSun, p, r, 1e300, 0.0)));
}

// Its colour, the paper's beta_e, keeps the luminance and is bluish.
TEST(Earthshine, Colour) {
  const glm::dvec3 c = earthshineColour();
  EXPECT_NEAR(umbra::colour::luminance(c), 1.0, 1e-12);
  EXPECT_NEAR(c.r / c.b, 0.88, 1e-12);
  EXPECT_NEAR(c.g / c.b, 0.96, 1e-12);
}
