// Refraction (eclipse paper, section 4.1) and the transmittance parametrisation (Eq. 2).
#include "Refraction.hpp"
#include "TextureCoords.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace umbra::atmosphere;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kArcmin = kDeg / 60.0;

// Test Earth: n - 1 = 2.77e-4 exp(-h / 8 km) (n = 1.000277 at sea level as in the paper;
// 8 km is the density scale height of an isothermal atmosphere at about 273 K), mean
// radius, atmosphere 100 km thick.
constexpr double kEarthBottomM = 6371e3, kEarthTopM = 6471e3;
// Test Mars: n - 1 = 3.38e-6 at the surface, scale height 11.1 km, 80 km thick.
constexpr double kMarsBottomM = 3389.5e3, kMarsTopM = 3469.5e3;

RefractiveMedium earth() {
  return exponentialRefractiveMedium(kEarthBottomM, kEarthTopM, 2.77e-4, 8000.0);
}
RefractiveMedium mars() {
  return exponentialRefractiveMedium(kMarsBottomM, kMarsTopM, 3.38e-6, 11100.0);
}

// Bennett (1982), "The calculation of astronomical refraction in marine navigation",
// J. Navigation 35, 255: refraction for an apparent altitude h (degrees), in arcminutes,
// R = cot(h + 7.31 / (h + 4.4)); standard conditions (10 degC, 101.0 kPa).
double bennettArcmin(double apparentAltitudeDeg) {
  const double h = apparentAltitudeDeg;
  return 1.0 / std::tan((h + 7.31 / (h + 4.4)) * kDeg);
}

/// Largest relative change of Bouguer's invariant n r sin(z) along a traced ray.
double bouguerDrift(const RefractiveMedium& m, double r, double mu, double stepM) {
  double first = -1.0, worst = 0.0;
  TraceOptions options;
  options.stepM = stepM;
  options.point = [&](const RayPoint& p) {
    const double k = bouguerInvariantM(m, p);
    if (first < 0.0) first = k;
    worst = std::max(worst, std::abs(k / first - 1.0));
  };
  traceRay(m, r, mu, options);
  return worst;
}

bool finite(const RayPath& p) {
  return std::isfinite(p.deviationRad) && std::isfinite(p.contactAltitudeM) &&
         std::isfinite(p.exitMu) && std::isfinite(p.centralAngleRad) && std::isfinite(p.pathLengthM);
}
} // namespace

// ---- the parametrisation ------------------------------------------------------------------

TEST(TextureCoords, TexelCentresLieOnTheEndsOfTheUnitRange) {
  for (int n : {2, 16, 256, 512}) {
    EXPECT_DOUBLE_EQ(textureCoordFromUnitRange(0.0, n), 0.5 / n);
    EXPECT_DOUBLE_EQ(textureCoordFromUnitRange(1.0, n), 1.0 - 0.5 / n);
    for (double x : {0.0, 0.125, 0.5, 0.9, 1.0}) {
      EXPECT_NEAR(unitRangeFromTextureCoord(textureCoordFromUnitRange(x, n), n), x, 1e-15);
    }
  }
}

TEST(TextureCoords, EndsOfTheRangesAreZenithHorizonGroundAndTop) {
  const ShellRadii shell{kEarthBottomM, kEarthTopM};
  const double H = std::sqrt(kEarthTopM * kEarthTopM - kEarthBottomM * kEarthBottomM);
  for (double xR : {0.0, 0.3, 1.0}) {
    const RadiusMu zenith = rMuFromTransmittanceCoords(shell, {0.0, xR});
    EXPECT_EQ(zenith.mu, 1.0);
    EXPECT_NEAR(zenith.radiusM, std::sqrt(xR * xR * H * H + kEarthBottomM * kEarthBottomM), 1e-6);
    const RadiusMu horizon = rMuFromTransmittanceCoords(shell, {1.0, xR});
    EXPECT_NEAR(horizon.mu, horizonCosine(kEarthBottomM, horizon.radiusM), 1e-15);
    EXPECT_FALSE(rayIntersectsGround(kEarthBottomM, horizon.radiusM, horizon.mu + 1e-9));
    EXPECT_TRUE(rayIntersectsGround(kEarthBottomM, horizon.radiusM, horizon.mu - 1e-9));
  }
  const RadiusMu ground = rMuFromTransmittanceCoords(shell, {1.0, 0.0});
  EXPECT_EQ(ground.radiusM, kEarthBottomM);
  EXPECT_EQ(ground.mu, 0.0);  // the horizontal ray on the ground, exactly
  EXPECT_EQ(rMuFromTransmittanceCoords(shell, {0.5, 1.0}).radiusM, kEarthTopM);
  // Distances: straight up from the ground, horizontally from the ground, down to it.
  EXPECT_NEAR(distanceToTopBoundaryM(kEarthTopM, kEarthBottomM, 1.0), 100e3, 1e-9);
  EXPECT_NEAR(distanceToTopBoundaryM(kEarthTopM, kEarthBottomM, 0.0), H, 1e-6);
  EXPECT_NEAR(distanceToBottomBoundaryM(kEarthBottomM, kEarthTopM, -1.0), 100e3, 1e-9);
  EXPECT_EQ(distanceToTopBoundaryM(kEarthTopM, kEarthTopM, 0.5), 0.0);
}

// distanceToSunCosineM against the geometry it stands for: at the distance the Sun's
// zenith cosine is m, and before it, on a fine sampling of the ray, it is below m; where
// it returns infinity the cosine stays below m along 3 radii of ray.
TEST(TextureCoords, DistanceToSunCosineIsTheFirstPointWithThatSun) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  const auto unit = [&] {
    const glm::dvec3 v(g(rng), g(rng), g(rng));
    return v / glm::length(v);
  };
  const double r = kEarthTopM;
  int found = 0, never = 0, cases = 0;
  for (double m : {-0.2079116908177593, -0.05, 0.0}) {
    for (int k = 0; k < 4000; ++k) {
      const glm::dvec3 up = unit(), dir = unit(), sun = unit();
      const double mu = glm::dot(up, dir), muS = glm::dot(up, sun), nu = glm::dot(dir, sun);
      const auto sunCosineAt = [&](double d) {
        const glm::dvec3 x = r * up + d * dir;
        return glm::dot(x, sun) / glm::length(x);
      };
      const double d = distanceToSunCosineM(r, mu, muS, nu, m);
      if (muS >= m) {
        EXPECT_EQ(d, 0.0);
        continue;
      }
      ++cases;
      const double reach = std::isfinite(d) ? d : 3.0 * r;
      for (int i = 0; i < 400; ++i) {
        const double di = reach * i / 400.0;
        if (std::abs(glm::length(r * up + di * dir)) < 1e-3 * r) continue;  // through the centre
        ASSERT_LT(sunCosineAt(di), m + 1e-12) << "m " << m << " case " << k << " at " << di << " of " << d;
      }
      if (std::isfinite(d)) {
        EXPECT_NEAR(sunCosineAt(d), m, 1e-9) << "m " << m << " case " << k;
        ++found;
      } else {
        ++never;
      }
    }
  }
  EXPECT_GT(found, 1000);
  EXPECT_GT(never, 1000);
  std::printf("%d rays below the Sun's cosine: %d reach it, %d never do\n", cases, found, never);
}

TEST(TextureCoords, RadiusAndMuRoundTripThroughEquation2) {
  const ShellRadii shell{kEarthBottomM, kEarthTopM};
  double worstR = 0.0, worstMu = 0.0, worstX = 0.0;
  for (double alt : {0.0, 1.0, 100.0, 1e3, 10e3, 50e3, 90e3, 99e3}) {
    const double r = kEarthBottomM + alt;
    const double muH = horizonCosine(kEarthBottomM, r);
    for (int i = 0; i <= 64; ++i) {
      const double mu = muH + (1.0 - muH) * i / 64.0;
      const TransmittanceCoords x = transmittanceCoordsFromRMu(shell, r, mu);
      const RadiusMu back = rMuFromTransmittanceCoords(shell, x);
      worstR = std::max(worstR, std::abs(back.radiusM - r) / r);
      worstMu = std::max(worstMu, std::abs(back.mu - mu));
    }
  }
  // And the other way, over the whole unit square (x_r = 1 is the top, where all upward
  // rays share x_mu = 0 but every x_mu maps to one ray).
  for (int j = 0; j <= 32; ++j) {
    for (int i = 0; i <= 32; ++i) {
      const TransmittanceCoords x{i / 32.0, j / 32.0};
      const RadiusMu rm = rMuFromTransmittanceCoords(shell, x);
      const TransmittanceCoords back = transmittanceCoordsFromRMu(shell, rm.radiusM, rm.mu);
      worstX = std::max({worstX, std::abs(back.xMu - x.xMu), std::abs(back.xR - x.xR)});
    }
  }
  EXPECT_LT(worstR, 1e-12);
  EXPECT_LT(worstMu, 1e-12);
  EXPECT_LT(worstX, 1e-12);
  // Through the texture coordinates of a 512 x 256 table.
  const TransmittanceCoords uv = transmittanceUvFromRMu(shell, kEarthBottomM + 5e3, 0.1, 512, 256);
  const RadiusMu rm = rMuFromTransmittanceUv(shell, uv, 512, 256);
  EXPECT_NEAR(rm.radiusM, kEarthBottomM + 5e3, 1e-5);
  EXPECT_NEAR(rm.mu, 0.1, 1e-12);
}

// ---- the ray ------------------------------------------------------------------------------

TEST(Refraction, VacuumGivesStraightRaysAndTheGeometricContact) {
  RefractiveMedium vacuum{kEarthBottomM, kEarthTopM, [](double) { return 0.0; }, {}};
  for (double r : {kEarthBottomM, kEarthBottomM + 1.0, kEarthBottomM + 30e3, kEarthTopM, 1e11}) {
    for (double mu : {-1.0, -0.5, -0.05, -0.01, -1e-4, 0.0, 1e-4, 0.3, 1.0}) {
      const RayPath p = traceRay(vacuum, r, mu);
      const double sinZ = std::sqrt(1.0 - mu * mu);
      const double expected = (mu < 0.0 ? r * sinZ : r) - kEarthBottomM;
      SCOPED_TRACE(testing::Message() << "r " << r << " mu " << mu);
      ASSERT_TRUE(finite(p));
      EXPECT_NEAR(p.deviationRad, 0.0, 1e-15);
      EXPECT_NEAR(p.contactAltitudeM, expected, 1e-6 + 1e-15 * r);
      EXPECT_EQ(p.hitGround, expected < 0.0);
      EXPECT_TRUE(p.completed);
    }
  }
}

TEST(Refraction, EarthHorizontalRayAtSeaLevelDeviatesAboutSixTenthsOfADegree) {
  const RayPath p = traceRay(earth(), kEarthBottomM, 0.0);
  // Going up only: one-way (astronomical) horizontal refraction; paper: "about 0.6 deg".
  EXPECT_GT(p.deviationRad, 0.55 * kDeg);
  EXPECT_LT(p.deviationRad, 0.65 * kDeg);
  EXPECT_EQ(p.contactAltitudeM, 0.0);
  EXPECT_FALSE(p.hitGround);
  EXPECT_TRUE(p.completed);
  // It leaves at the top: Bouguer, n_top top sin(z_exit) = n_0 bottom.
  const double sinExit = std::sqrt(1.0 - p.exitMu * p.exitMu);
  EXPECT_NEAR(sinExit * kEarthTopM * earth().refractiveIndex(kEarthTopM),
              kEarthBottomM * earth().refractiveIndex(kEarthBottomM), 1e-3);
}

TEST(Refraction, AgreesWithBennettsRefractionAbove5Degrees) {
  const RefractiveMedium m = earth();
  const RefractionTable table = buildRefractionTable(m, 64, 16, 10e3);
  double worstTable = 0.0, worstTraced = 0.0;
  for (double e = 5.0; e <= 85.0; e += 0.5) {
    const double bennett = bennettArcmin(e) * kArcmin;
    const double traced = traceRay(m, kEarthBottomM, std::sin(e * kDeg)).deviationRad;
    const double looked = table.sample(kEarthBottomM, std::sin(e * kDeg)).deviationRad;
    worstTraced = std::max(worstTraced, std::abs(traced / bennett - 1.0));
    worstTable = std::max(worstTable, std::abs(looked / bennett - 1.0));
  }
  EXPECT_LT(worstTraced, 0.10);
  EXPECT_LT(worstTable, 0.10);
  // Towards the zenith Bennett's fit crosses zero; there the two agree in absolute terms.
  for (double e = 85.0; e <= 90.0; e += 0.25) {
    EXPECT_NEAR(table.sample(kEarthBottomM, std::sin(e * kDeg)).deviationRad,
                bennettArcmin(e) * kArcmin, 0.05 * kArcmin);
  }
  // Below 5 degrees the scale height matters; the exponential model stays near it.
  EXPECT_NEAR(traceRay(m, kEarthBottomM, std::sin(2.0 * kDeg)).deviationRad,
              bennettArcmin(2.0) * kArcmin, 0.1 * bennettArcmin(2.0) * kArcmin);
}

TEST(Refraction, MarsHorizontalDeviationIsBelowOnePercentOfEarths) {
  const double earthDev = traceRay(earth(), kEarthBottomM, 0.0).deviationRad;
  const double marsDev = traceRay(mars(), kMarsBottomM, 0.0).deviationRad;
  EXPECT_GT(marsDev, 0.0);
  EXPECT_LT(marsDev, 0.01 * earthDev);
}

TEST(Refraction, RedAndBlueDifferByLessThanTwoHundredthsOfADegree) {
  // Edlen 1966 for standard air: n - 1 = 2.7714e-4 at the sodium D line, the paper's
  // sea-level value; 1.8 % more at 440 nm than at 680 nm.
  EXPECT_NEAR(edlenStandardAirRefractivity(589.3e-9), 2.7714e-4, 2e-8);
  const double ref = edlenStandardAirRefractivity(589.3e-9);
  const double red = edlenStandardAirRefractivity(680e-9) / ref;
  const double blue = edlenStandardAirRefractivity(440e-9) / ref;
  EXPECT_GT(blue, red);
  const double devRed = traceRay(scaledRefractiveMedium(earth(), red), kEarthBottomM, 0.0).deviationRad;
  const double devBlue = traceRay(scaledRefractiveMedium(earth(), blue), kEarthBottomM, 0.0).deviationRad;
  EXPECT_GT(devBlue, devRed);
  EXPECT_LT(devBlue - devRed, 0.02 * kDeg);
}

TEST(Refraction, BouguerInvariantHoldsAlongTheRay) {
  const RefractiveMedium m = earth();
  // At the default step: every ray within 14 degrees of the horizon from the ground (the
  // ones that bend), and rays from altitude down to, past and through the ground.
  for (double mu : {0.0, 0.02, 0.05, 0.1, 0.15, 0.2, 0.25}) {
    EXPECT_LT(bouguerDrift(m, kEarthBottomM, mu, 10e3), 1e-9) << "mu " << mu;
  }
  for (double alt : {1.0, 1e3, 10e3, 50e3, 100e3}) {
    const double r = kEarthBottomM + alt, muH = horizonCosine(kEarthBottomM, r);
    for (double f : {1.01, 1.0, 0.999, 0.9, 0.5}) {
      EXPECT_LT(bouguerDrift(m, r, muH * f, 10e3), 1e-9) << "alt " << alt << " mu " << muH * f;
    }
  }
  // Steep rays change little in direction but cross the 8 km scale height in less than a
  // step: there the drift is the RK4 truncation error, below 1e-9 from 2.5 km steps on.
  for (double mu : {0.3, 0.5, 0.7, 0.9, 0.99, 1.0}) {
    EXPECT_LT(bouguerDrift(m, kEarthBottomM, mu, 2.5e3), 1e-9) << "mu " << mu;
    EXPECT_LT(bouguerDrift(m, kEarthBottomM, mu, 10e3), 3e-7) << "mu " << mu;
  }
  // ... and falls as h^4.
  const double d10 = bouguerDrift(m, kEarthBottomM, 0.7, 10e3);
  const double d5 = bouguerDrift(m, kEarthBottomM, 0.7, 5e3);
  EXPECT_GT(d10 / d5, 12.0);
}

TEST(Refraction, Rk4ConvergesAtFourthOrder) {
  const RefractiveMedium m = earth();
  struct Ray {
    double r, mu;
  };
  const double r10 = kEarthBottomM + 10e3;
  const std::vector<Ray> rays{{kEarthBottomM, 0.0},
                              {kEarthBottomM, std::sin(5 * kDeg)},
                              {kEarthBottomM, std::sin(30 * kDeg)},
                              {kEarthBottomM, 0.9},
                              {kEarthBottomM + 30e3, -0.08},                         // turns at 9 km
                              {r10, 0.999 * horizonCosine(kEarthBottomM, r10)},      // into the ground
                              {1e11, -std::sqrt(1.0 - std::pow(kEarthBottomM / 1e11, 2))}};  // from far away
  for (const Ray& ray : rays) {
    const double d10 = traceRay(m, ray.r, ray.mu, 10e3).deviationRad;
    const double d5 = traceRay(m, ray.r, ray.mu, 5e3).deviationRad;
    EXPECT_LT(std::abs(d10 - d5), 1e-6) << "r " << ray.r << " mu " << ray.mu;
  }
  // The error ratio between halved steps is 2^4 where the error is above rounding.
  const double mu30 = std::sin(30 * kDeg);
  const double reference = traceRay(m, kEarthBottomM, mu30, 312.5).deviationRad;
  const double e20 = std::abs(traceRay(m, kEarthBottomM, mu30, 20e3).deviationRad - reference);
  const double e10 = std::abs(traceRay(m, kEarthBottomM, mu30, 10e3).deviationRad - reference);
  const double e5 = std::abs(traceRay(m, kEarthBottomM, mu30, 5e3).deviationRad - reference);
  EXPECT_GT(e20 / e10, 13.0);
  EXPECT_LT(e20 / e10, 19.0);
  EXPECT_GT(e10 / e5, 13.0);
  EXPECT_LT(e10 / e5, 19.0);
  EXPECT_LT(e10, 1e-7);
}

TEST(Refraction, NumericalDerivativeMatchesTheExactOne) {
  RefractiveMedium numerical = earth();
  numerical.refractivityDerivativePerM = {};
  for (double mu : {0.0, 0.1, 0.7}) {
    EXPECT_NEAR(traceRay(numerical, kEarthBottomM, mu).deviationRad,
                traceRay(earth(), kEarthBottomM, mu).deviationRad, 1e-11);
  }
  const double r = kEarthBottomM + 20e3;
  EXPECT_NEAR(traceRay(numerical, r, horizonCosine(kEarthBottomM, r)).deviationRad,
              traceRay(earth(), r, horizonCosine(kEarthBottomM, r)).deviationRad, 1e-11);
}

TEST(Refraction, RaysThroughTheGroundContinueStraightWithTheGroundsIndex) {
  const RefractiveMedium m = earth();
  const double r = kEarthBottomM + 10e3, muH = horizonCosine(kEarthBottomM, r);
  // The geometric horizon is bent into the ground.
  const RayPath horizon = traceRay(m, r, muH);
  EXPECT_TRUE(horizon.hitGround);
  EXPECT_LT(horizon.contactAltitudeM, 0.0);
  EXPECT_TRUE(horizon.completed);
  // Under ground the path is one straight chord: its end keeps the direction it entered with.
  std::vector<RayPoint> points;
  TraceOptions options;
  options.point = [&](const RayPoint& p) { points.push_back(p); };
  traceRay(m, r, muH, options);
  auto chord = std::find_if(points.begin(), points.end(), [](const RayPoint& p) { return p.underGround; });
  ASSERT_NE(chord, points.end());
  ASSERT_NE(chord, points.begin());
  const RayPoint& in = *(chord - 1);
  EXPECT_NEAR(std::hypot(in.xM, in.yM), kEarthBottomM, 1e-6);
  EXPECT_NEAR(std::hypot(chord->xM, chord->yM), kEarthBottomM, 1e-6);
  EXPECT_NEAR(in.dirX * chord->dirY - in.dirY * chord->dirX, 0.0, 1e-15);
  const double len = std::hypot(chord->xM - in.xM, chord->yM - in.yM);
  EXPECT_NEAR(in.dirX * (chord->xM - in.xM) + in.dirY * (chord->yM - in.yM), len, 1e-6);
  EXPECT_NEAR(len, chord->pathLengthM - in.pathLengthM, 1e-6);
  // Deviation and contact are continuous through the contact = 0 boundary: the bending
  // lost under ground goes like the chord's length, sqrt(-contact).
  double previousDev = -1.0, previousContact = 0.0;
  int crossings = 0;
  for (int i = 0; i <= 400; ++i) {
    const double mu = muH + 0.2 * (i / 400.0) * std::abs(muH);  // from the horizon upwards
    const RayPath p = traceRay(m, r, mu);
    ASSERT_TRUE(finite(p));
    if (previousDev >= 0.0) {
      EXPECT_LT(std::abs(p.deviationRad - previousDev), 1e-3) << "mu " << mu;
      EXPECT_LT(std::abs(p.contactAltitudeM - previousContact), 15.0) << "mu " << mu;
      if ((p.contactAltitudeM < 0.0) != (previousContact < 0.0)) ++crossings;
    }
    previousDev = p.deviationRad;
    previousContact = p.contactAltitudeM;
  }
  EXPECT_EQ(crossings, 1);
  double below = muH, above = muH + 0.2 * std::abs(muH);  // bisect the grazing ray
  for (int i = 0; i < 60 && above - below > 1e-13; ++i) {
    const double mid = 0.5 * (below + above);
    (traceRay(m, r, mid).hitGround ? below : above) = mid;
  }
  const RayPath under = traceRay(m, r, below), over = traceRay(m, r, above);
  EXPECT_TRUE(under.hitGround);
  EXPECT_FALSE(over.hitGround);
  EXPECT_NEAR(under.contactAltitudeM, 0.0, 1e-3);
  EXPECT_NEAR(over.contactAltitudeM, 0.0, 1e-3);
  EXPECT_NEAR(under.deviationRad, over.deviationRad, 1e-6);
}

TEST(Refraction, ExtremeRaysAreFinite) {
  const RefractiveMedium m = earth();
  std::vector<double> radii{kEarthBottomM, kEarthBottomM + 1.0, kEarthBottomM + 1e3,
                            kEarthTopM - 1.0, kEarthTopM, kEarthTopM + 1.0, 1e8, 1e11};
  for (double r : radii) {
    const double muH = horizonCosine(kEarthBottomM, r);
    const double muTop = r > kEarthTopM ? -std::sqrt(1.0 - std::pow(kEarthTopM / r, 2)) : 0.0;
    for (double mu : {-1.0, -0.7, muH, std::nextafter(muH, 1.0), std::nextafter(muH, -1.0), muTop,
                      std::nextafter(muTop, -1.0), -1e-12, 0.0, 1e-12, 0.5, 1.0}) {
      const RayPath p = traceRay(m, r, mu);
      SCOPED_TRACE(testing::Message() << "r " << r << " mu " << mu);
      EXPECT_TRUE(finite(p));
      EXPECT_TRUE(p.completed);
      EXPECT_GE(p.deviationRad, 0.0);
      EXPECT_LT(p.deviationRad, 2.0 * kDeg);
    }
  }
  // From far away the ray is the one that enters at the top.
  const double r = 1e11, aim = kEarthBottomM + 5e3;  // passes 5 km above the ground
  const double mu = -std::sqrt(1.0 - (aim / r) * (aim / r));
  const double p = r * std::sqrt((1.0 - mu) * (1.0 + mu));  // the impact parameter mu gives
  const double muEntry = -std::sqrt((kEarthTopM - p) * (kEarthTopM + p)) / kEarthTopM;
  EXPECT_NEAR(traceRay(m, r, mu).deviationRad, traceRay(m, kEarthTopM, muEntry).deviationRad, 1e-9);
  EXPECT_NEAR(traceRay(m, r, mu).contactAltitudeM, traceRay(m, kEarthTopM, muEntry).contactAltitudeM, 1.0);
}

TEST(Refraction, SegmentsFollowTheRefractedPath) {
  const RefractiveMedium m = earth();
  // The pieces add up to the path; under ground they are reported at altitude 0.
  for (double mu : {0.0, 0.5, -0.3}) {
    double total = 0.0;
    TraceOptions options;
    options.segmentsPerStep = 4;
    options.segment = [&](double altitudeM, double lengthM) {
      EXPECT_GE(altitudeM, 0.0);
      EXPECT_LE(altitudeM, kEarthTopM - kEarthBottomM);
      total += lengthM;
    };
    const RayPath p = traceRay(m, kEarthBottomM + 2e3, mu, options);
    EXPECT_NEAR(total, p.pathLengthM, 1e-6);
  }
  // Vertical optical depth of an 8 km scale height: H (1 - exp(-100 / 8)).
  double column = 0.0;
  TraceOptions options;
  options.segmentsPerStep = 16;
  options.segment = [&](double h, double len) { column += std::exp(-h / 8000.0) * len; };
  traceRay(m, kEarthBottomM, 1.0, options);
  EXPECT_NEAR(column, 8000.0 * (1.0 - std::exp(-12.5)), 8.0);  // midpoint rule, 625 m pieces
  // A refracted horizontal ray is longer in the dense layers than the straight one would be.
  double bent = 0.0, straight = 0.0;
  options.segment = [&](double h, double len) { bent += std::exp(-h / 8000.0) * len; };
  traceRay(m, kEarthBottomM, 0.0, options);
  RefractiveMedium vacuum{kEarthBottomM, kEarthTopM, [](double) { return 0.0; }, {}};
  options.segment = [&](double h, double len) { straight += std::exp(-h / 8000.0) * len; };
  traceRay(vacuum, kEarthBottomM, 0.0, options);
  EXPECT_GT(bent, 1.05 * straight);
  // Straight horizontal column: sqrt(pi R H / 2) to first order.
  EXPECT_NEAR(straight, std::sqrt(kPi * kEarthBottomM * 8000.0 / 2.0), 0.01 * straight);
}

// ---- the table ----------------------------------------------------------------------------

TEST(RefractionTable, EveryTexelIsFiniteAndTheEdgesAreTheExpectedRays) {
  const RefractiveMedium m = earth();
  double lastProgress = 0.0;
  int calls = 0;
  const RefractionTable t = buildRefractionTable(m, 48, 24, 10e3, [&](double f) {
    EXPECT_GE(f, lastProgress);
    lastProgress = f;
    ++calls;
  });
  EXPECT_EQ(lastProgress, 1.0);
  EXPECT_GE(calls, 1);
  ASSERT_EQ(t.deviationRad.size(), 48u * 24u);
  ASSERT_EQ(t.contactAltitudeM.size(), 48u * 24u);
  for (int y = 0; y < t.height; ++y) {
    for (int x = 0; x < t.width; ++x) {
      const float d = t.deviationRad[t.index(x, y)], c = t.contactAltitudeM[t.index(x, y)];
      ASSERT_TRUE(std::isfinite(d) && std::isfinite(c)) << x << ", " << y;
      EXPECT_GE(d, 0.0f);
      EXPECT_LT(d, 2.0f * kDeg);
      EXPECT_GE(c, -(kEarthTopM - kEarthBottomM)) << x << ", " << y;
    }
  }
  // x_mu = 0: straight up, no deviation, the contact is the observer's altitude.
  const double H = std::sqrt(kEarthTopM * kEarthTopM - kEarthBottomM * kEarthBottomM);
  for (int y = 0; y < t.height; ++y) {
    const double rho = H * y / (t.height - 1.0);
    EXPECT_NEAR(t.deviationRad[t.index(0, y)], 0.0, 1e-12);
    EXPECT_NEAR(t.contactAltitudeM[t.index(0, y)], std::sqrt(rho * rho + kEarthBottomM * kEarthBottomM) - kEarthBottomM, 0.05);
  }
  // x_mu = 1, x_r = 0: the horizontal ray on the ground, the largest unblocked deviation.
  const float corner = t.deviationRad[t.index(t.width - 1, 0)];
  EXPECT_NEAR(corner, traceRay(m, kEarthBottomM, 0.0).deviationRad, 1e-7);
  EXPECT_EQ(t.contactAltitudeM[t.index(t.width - 1, 0)], 0.0f);
  // x_mu = 1 above the ground: the geometric horizon, bent into the ground.
  for (int y = 1; y < t.height; ++y) EXPECT_LT(t.contactAltitudeM[t.index(t.width - 1, y)], 0.0f);
  // x_r = 1: observers on the top; looking up or along the top, nothing happens.
  EXPECT_EQ(t.deviationRad[t.index(0, t.height - 1)], 0.0f);
  EXPECT_NEAR(t.contactAltitudeM[t.index(0, t.height - 1)], kEarthTopM - kEarthBottomM, 0.01);
  // On the ground row no ray is blocked (all at or above the horizon).
  for (int x = 0; x < t.width; ++x) EXPECT_GE(t.contactAltitudeM[t.index(x, 0)], 0.0f);
}

TEST(RefractionTable, LookupsMatchTracedRays) {
  const RefractiveMedium m = earth();
  const RefractionTable t = buildRefractionTable(m, 128, 32, 10e3);
  // Between texels, away from the steep part near the horizon.
  for (double alt : {0.0, 2e3, 20e3, 70e3}) {
    const double r = kEarthBottomM + alt;
    for (double e : {3.0, 10.0, 40.0}) {
      const double mu = std::sin(e * kDeg);
      const double traced = traceRay(m, r, mu).deviationRad;
      EXPECT_NEAR(t.sample(r, mu).deviationRad, traced, 0.02 * traced + 1e-7) << alt << " " << e;
    }
  }
  // From far away: the entry point's ray; rays that miss: no deviation, straight contact.
  const double r = 1e11, p = kEarthBottomM + 20e3;
  const double mu = -std::sqrt(1.0 - (p / r) * (p / r));
  const RefractionSample far = t.sample(r, mu);
  EXPECT_NEAR(far.deviationRad, traceRay(m, r, mu).deviationRad, 0.03 * far.deviationRad);
  EXPECT_NEAR(far.contactAltitudeM, traceRay(m, r, mu).contactAltitudeM, 500.0);
  const RefractionSample miss = t.sample(r, -std::sqrt(1.0 - std::pow(kEarthTopM * 1.01 / r, 2)));
  EXPECT_EQ(miss.deviationRad, 0.0);
  EXPECT_NEAR(miss.contactAltitudeM, kEarthTopM * 1.01 - kEarthBottomM, 1.0);
  // Below the horizon: blocked.
  const double r5 = kEarthBottomM + 5e3;
  EXPECT_TRUE(t.sample(r5, horizonCosine(kEarthBottomM, r5) - 0.01).hitsGround());
  EXPECT_TRUE(t.sample(r5, -1.0).hitsGround());
  // Every lookup is finite, at the extremes too.
  for (double rr : {kEarthBottomM - 1.0, kEarthBottomM, kEarthTopM, 1e11}) {
    for (double mm : {-1.0, -0.1, 0.0, 0.1, 1.0}) {
      const RefractionSample s = t.sample(rr, mm);
      EXPECT_TRUE(std::isfinite(s.deviationRad) && std::isfinite(s.contactAltitudeM));
    }
  }
}

// A table of the top rows only: those rows are the whole table's to the bit, a lookup from
// the top of the atmosphere (or from far away) gives the whole table's answer, and a lookup
// lower down is refused with an error instead of reading untraced rows.
TEST(RefractionTable, TheTopRowsAloneAnswerTheLookupsFromTheTop) {
  const RefractiveMedium m = earth();
  const RefractionTable whole = buildRefractionTable(m, 64, 16, 10e3);
  const RefractionTable top = buildRefractionTable(m, 64, 16, 10e3, {}, 14);
  EXPECT_EQ(top.firstRow, 14);
  for (int y = 14; y < 16; ++y)
    for (int x = 0; x < 64; ++x) {
      EXPECT_EQ(top.deviationRad[top.index(x, y)], whole.deviationRad[whole.index(x, y)]) << x << ", " << y;
      EXPECT_EQ(top.contactAltitudeM[top.index(x, y)], whole.contactAltitudeM[whole.index(x, y)]) << x << ", " << y;
    }
  for (double mu : {-1.0, -0.3, -0.1, -0.05, 0.0, 0.5}) {
    for (double r : {kEarthTopM, 1e9}) {
      const RefractionSample a = top.sample(r, mu), b = whole.sample(r, mu);
      EXPECT_EQ(a.deviationRad, b.deviationRad) << r << " " << mu;
      EXPECT_EQ(a.contactAltitudeM, b.contactAltitudeM) << r << " " << mu;
    }
  }
  EXPECT_GT(whole.sample(kEarthTopM, -0.1).deviationRad, 0.0);  // a ray through the air: bent
  EXPECT_THROW(top.sample(kEarthBottomM + 10e3, 0.1), std::domain_error);
  EXPECT_THROW(buildRefractionTable(m, 64, 16, 10e3, {}, 15), std::invalid_argument);
  EXPECT_THROW(buildRefractionTable(m, 64, 16, 10e3, {}, -1), std::invalid_argument);
}

TEST(RefractionTable, RejectsUnusableArguments) {
  const RefractiveMedium m = earth();
  EXPECT_THROW(buildRefractionTable(m, 1, 16), std::invalid_argument);
  EXPECT_THROW(buildRefractionTable(m, 16, 16, 0.0), std::invalid_argument);
  EXPECT_THROW(buildRefractionTable(RefractiveMedium{kEarthTopM, kEarthBottomM, m.refractivity, {}}, 16, 16),
               std::invalid_argument);
  EXPECT_THROW(buildRefractionTable(RefractiveMedium{kEarthBottomM, kEarthTopM, {}, {}}, 16, 16),
               std::invalid_argument);
}
