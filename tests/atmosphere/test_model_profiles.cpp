// Density profiles (Profiles.hpp): values, closed-form integrals against quadrature.
#include "ModelTestSupport.hpp"
#include "Profiles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

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

// OPAC's tropospheric layers: exp(-h/H) up to the mixing layer's top B, f exp(-(h-B)/H_ft)
// up to T, 0 above; the integral in closed form, against quadrature across both jumps.
TEST(ModelProfiles, BoundaryLayerIsTwoExponentialLayersWithJumps) {
  const double B = 2000.0, H = 8000.0, f = 0.0626, Hft = 8000.0, T = 12000.0;
  const DensityProfile p = DensityProfile::boundaryLayer(B, H, f, Hft, T);
  EXPECT_DOUBLE_EQ(p.at(0.0), 1.0);
  EXPECT_NEAR(p.at(1999.0), std::exp(-1999.0 / H), 1e-15);
  EXPECT_DOUBLE_EQ(p.at(2000.0), f);
  EXPECT_NEAR(p.at(10000.0), f * std::exp(-8000.0 / Hft), 1e-15);
  EXPECT_DOUBLE_EQ(p.at(12000.0), 0.0);
  const double whole = H * (1.0 - std::exp(-B / H)) + f * Hft * (1.0 - std::exp(-(T - B) / Hft));
  EXPECT_NEAR(p.integral(0.0, 100000.0), whole, 1e-12 * whole);
  const double numeric = integrate([&](double h) { return p.at(h); }, 500.0, B) +
                         integrate([&](double h) { return p.at(h); }, B, 11000.0);
  EXPECT_NEAR(p.integral(500.0, 11000.0), numeric, 1e-10 * numeric);
  EXPECT_DOUBLE_EQ(p.integral(11000.0, 500.0), -p.integral(500.0, 11000.0));
  EXPECT_EQ(p.kinksM(), (std::vector<double>{B, T}));
  // Without a free troposphere (T = B): the mixing layer alone.
  EXPECT_NEAR(DensityProfile::boundaryLayer(B, H, 0.0, Hft, B).integral(0.0, 1e5), H * (1.0 - std::exp(-B / H)), 1e-9);
  EXPECT_THROW(DensityProfile::boundaryLayer(B, H, f, Hft, 1000.0), std::invalid_argument);  // top below B
  EXPECT_THROW(DensityProfile::boundaryLayer(0.0, H, f, Hft, T), std::invalid_argument);
}

// The steps blended over w: continuous (and so is the slope) at every zone edge, the
// layers' own values outside the zones, the integral against quadrature.
TEST(ModelProfiles, BoundaryLayerBlendsItsStepsOverTheTransition) {
  const double B = 2000.0, H = 8000.0, f = 0.0626, T = 12000.0, w = 500.0;
  const DensityProfile p = DensityProfile::boundaryLayer(B, H, f, H, T, w);
  const DensityProfile steps = DensityProfile::boundaryLayer(B, H, f, H, T);
  for (double h : {0.0, 1500.0, 2500.0, 9000.0, 11500.0, 12500.0}) EXPECT_DOUBLE_EQ(p.at(h), steps.at(h)) << h;
  EXPECT_NEAR(p.at(B), 0.5 * (std::exp(-B / H) + f), 1e-15);  // halfway through the zone
  for (double edge : {B - 250.0, B + 250.0, T - 250.0, T + 250.0}) {
    EXPECT_NEAR(p.at(edge - 1e-3), p.at(edge + 1e-3), 1e-6) << edge;
    // one-sided slopes 1 cm either side: equal but for the blend's curvature (6 / w^2 x the step)
    const double below = (p.at(edge) - p.at(edge - 0.01)) / 0.01, above = (p.at(edge + 0.01) - p.at(edge)) / 0.01;
    EXPECT_NEAR(below, above, 1e-6) << edge;
  }
  EXPECT_EQ(p.kinksM(), (std::vector<double>{B - 250.0, B, B + 250.0, T - 250.0, T + 250.0}));
  double numeric = 0.0;
  const std::vector<double> at{0.0, B - 250.0, B, B + 250.0, T - 250.0, T + 250.0, 20000.0};
  for (std::size_t i = 0; i + 1 < at.size(); ++i) numeric += integrate([&](double h) { return p.at(h); }, at[i], at[i + 1]);
  EXPECT_NEAR(p.integral(0.0, 20000.0), numeric, 1e-10 * numeric);
  EXPECT_NEAR(p.integral(1900.0, 2100.0), integrate([&](double h) { return p.at(h); }, 1900.0, 2100.0), 1e-9);
  EXPECT_THROW(DensityProfile::boundaryLayer(B, H, f, H, T, 4000.0), std::invalid_argument);  // >= 2 B
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
