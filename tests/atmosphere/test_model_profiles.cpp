// Density profiles (Profiles.hpp): values, closed-form integrals against quadrature.
#include "ModelTestSupport.hpp"
#include "Profiles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace umbra::atmosphere;
using umbra::test::integrate;

TEST(ModelProfiles, ExponentialOpticalDepthIsBetaHTimesOneMinusExp) {
  const double beta = 13.5e-6, H = 8000.0, bottom = 6360e3, top = 6420e3;
  const DensityProfile p = DensityProfile::exponential(H);
  EXPECT_DOUBLE_EQ(p.at(0.0), 1.0);
  EXPECT_NEAR(p.at(H), std::exp(-1.0), 1e-16);
  const double expected = beta * H * (1.0 - std::exp(-(top - bottom) / H));
  EXPECT_NEAR(beta * p.integral(0.0, top - bottom), expected, 1e-15 * expected);
  const double numeric = beta * integrate([&](double h) { return p.at(h); }, 0.0, top - bottom);
  EXPECT_NEAR(numeric, expected, 1e-12 * expected);
  // thin layers high up keep their digits; reversed limits change the sign
  // (2 H sinh(1 / 2H) = 1 + 1/(24 H^2) + ...)
  const double thin = std::exp(-50000.5 / H) * (1.0 + 1.0 / (24.0 * H * H));
  EXPECT_NEAR(p.integral(50000.0, 50001.0), thin, 1e-14 * thin);
  EXPECT_DOUBLE_EQ(p.integral(1000.0, 0.0), -p.integral(0.0, 1000.0));
}

TEST(ModelProfiles, TentIntegralIsPeakTimesHalfWidth) {
  const DensityProfile ozone = DensityProfile::tent(25000.0, 15000.0);
  EXPECT_DOUBLE_EQ(ozone.at(25000.0), 1.0);
  EXPECT_DOUBLE_EQ(ozone.at(10000.0), 0.0);
  EXPECT_DOUBLE_EQ(ozone.at(32500.0), 0.5);
  EXPECT_DOUBLE_EQ(ozone.at(45000.0), 0.0);
  // whole layer: a triangle of base 2 w and height 1 -> w (peak x width)
  EXPECT_NEAR(ozone.integral(0.0, 60000.0), 15000.0, 1e-9);
  EXPECT_NEAR(ozone.integral(10000.0, 25000.0), 7500.0, 1e-9);
  EXPECT_NEAR(ozone.integral(0.0, 17500.0), 0.5 * 7500.0 * 0.5, 1e-9);  // up to half height
  EXPECT_NEAR(ozone.integral(20000.0, 30000.0), integrate([&](double h) { return ozone.at(h); }, 20000.0, 30000.0),
              1e-8);
  // 300 Dobson units: the peak density 5.374e18 1/m^3 times 15 km
  EXPECT_NEAR(5.374e18 * ozone.integral(0.0, 1e5) / 2.687e20, 300.0, 1e-9);
}

TEST(ModelProfiles, DoubleExponentialIntegralMatchesQuadrature) {
  const DensityProfile p = DensityProfile::doubleExponential(5000.0);
  EXPECT_DOUBLE_EQ(p.at(0.0), 1.0);
  EXPECT_NEAR(p.at(5000.0), std::exp(1.0 - std::exp(1.0)), 1e-16);
  for (auto [a, b] : {std::pair{0.0, 1000.0}, {0.0, 60000.0}, {2000.0, 9000.0}, {-3000.0, 4000.0}}) {
    const double numeric = integrate([&](double h) { return p.at(h); }, a, b);
    EXPECT_NEAR(p.integral(a, b), numeric, 1e-11 * numeric) << a << " " << b;
  }
}

TEST(ModelProfiles, TabulatedInterpolatesLinearlyIsZeroOutsideAndIntegratesExactly) {
  const DensityProfile p = DensityProfile::tabulated({0.0, 1000.0, 3000.0}, {1.0, 0.5, 0.1});
  EXPECT_DOUBLE_EQ(p.at(500.0), 0.75);
  EXPECT_DOUBLE_EQ(p.at(2000.0), 0.3);
  EXPECT_DOUBLE_EQ(p.at(3000.0), 0.1);
  EXPECT_DOUBLE_EQ(p.at(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(p.at(3000.1), 0.0);
  EXPECT_NEAR(p.integral(-500.0, 5000.0), 750.0 + 600.0, 1e-9);
  EXPECT_NEAR(p.integral(500.0, 2000.0), 0.5 * 500 * (0.75 + 0.5) + 0.5 * 1000 * (0.5 + 0.3), 1e-9);
}

TEST(ModelProfiles, InvalidShapesAreRefused) {
  EXPECT_THROW(DensityProfile::exponential(0.0), std::invalid_argument);
  EXPECT_THROW(DensityProfile::exponential(-8000.0), std::invalid_argument);
  EXPECT_THROW(DensityProfile::tent(25000.0, 0.0), std::invalid_argument);
  EXPECT_THROW(DensityProfile::tabulated({0.0, 2000.0, 1000.0}, {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(DensityProfile::tabulated({0.0, 1000.0}, {1.0, -0.1}), std::invalid_argument);
  EXPECT_THROW(DensityProfile::tabulated({0.0, 1000.0}, {1.0}), std::invalid_argument);
  DensityProfile tent;
  tent.kind = DensityProfile::Kind::Tent;
  tent.centreM = 25000.0;
  tent.halfWidthM = -1.0;
  EXPECT_EQ(tent.validate(), "halfWidthM: expected a positive length in metres, got -1");
}
