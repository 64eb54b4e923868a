#include "ShadowLut.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::eclipse;

namespace {
constexpr double kAu = 149597870700.0;
const ShadowLut& smallLut() {
  static const ShadowLut lut = buildAirlessShadowLut({64, 64});
  return lut;
}
} // namespace

TEST(ShadowLut, TexelsHoldTheShadowFunctionAtTheirCentres) {
  const ShadowLut& lut = smallLut();
  ASSERT_EQ(lut.rgb.size(), 3u * 64 * 64);
  for (int j = 0; j < 64; j += 7) {
    for (int i = 0; i < 64; i += 5) {
      const LutCoords c{(i + 0.5) / 64, (j + 0.5) / 64};
      const glm::dvec3 t = lut.texel(i, j);
      EXPECT_NEAR(t.r, airlessShadow(c), 1e-7);
      EXPECT_EQ(t.r, t.g);
      EXPECT_EQ(t.r, t.b);
      EXPECT_NEAR(lut.sample(c).r, t.r, 1e-7);  // sampling at a centre returns the texel
    }
  }
}

TEST(ShadowLut, UmbraIsDarkPenumbraEdgeIsLitAntumbraIsAnnular) {
  const ShadowLut& lut = smallLut();
  EXPECT_EQ(lut.texel(5, 5).r, 0.0);                 // u < 0.5, v < 1 - 2u: umbra
  EXPECT_GT(lut.texel(5, 63).r, 0.98);               // v -> 1: penumbra's outer edge
  // u > 0.5, v = 0: the occluder sits inside the solar disc, annular eclipse
  const NormalisedDiscs n = normalisedDiscs(LutCoords{60.5 / 64, 0.5 / 64});
  EXPECT_LT(n.occluderRadius + n.separation, 1.0);
  EXPECT_NEAR(lut.texel(60, 0).r, visibleFractionLimbDarkened(n.occluderRadius, n.separation, 0.6).value, 1e-6);
  EXPECT_GT(lut.texel(60, 0).r, 0.9);
}

TEST(ShadowLut, ValuesIncreaseMonotonicallyAcrossThePenumbra) {
  const ShadowLut& lut = smallLut();
  for (int i = 0; i < 64; i += 3) {
    for (int j = 1; j < 64; ++j) EXPECT_GE(lut.texel(i, j).r + 1e-7, lut.texel(i, j - 1).r);
  }
}

TEST(ShadowLut, BuildCanBeCancelled) {
  int calls = 0;
  const ShadowLut lut = buildAirlessShadowLut({32, 32}, [&](double) { return ++calls < 3; });
  EXPECT_TRUE(lut.rgb.empty());
}

TEST(ShadowLut, OccluderBehindTheSunCastsNoShadow) {
  // The point is beyond the Sun, with the occluder right behind the Sun.
  const Occluder occ{{0, 0, 0}, 6371e3};
  const glm::dvec3 sun(-kAu, 0, 0), point(-2 * kAu, 0, 0);
  EXPECT_EQ(eclipseFactor(point, sun, kSunRadiusM, occ, nullptr).r, 1.0);
  EXPECT_EQ(eclipseFactor({384400e3, 0, 0}, sun, kSunRadiusM, occ, nullptr).r, 0.0);
}

TEST(ShadowLut, FluxRemovedFromTheCrossSectionEqualsWhatTheOccluderIntercepts) {
  // Energy: integral over a plane behind the occluder of (1 - I/I_sun) dA equals
  // pi R^2 times the ratio of the irradiance at the occluder to that at the plane.
  const SunOccluderSystem earth{kSunRadiusM, 6371e3, kAu};
  const double x = 384400e3;
  const double rMax = 1.05 * shadowConeRadii(earth, x).penumbraRadiusM;
  const int n = 4001;  // Simpson
  const auto profile = shadowProfile(earth, x, rMax, n, nullptr);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double w = (k == 0 || k == n - 1) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * (1.0 - profile[k].luminance) * 2.0 * 3.14159265358979 * profile[k].offsetM;
  }
  sum *= rMax / (n - 1) / 3.0;
  const double expected = 3.14159265358979 * 6371e3 * 6371e3 * std::pow((kAu + x) / kAu, 2);
  EXPECT_NEAR(sum, expected, 2e-4 * expected);
}

TEST(ShadowLut, StableAtTheExtremes) {
  const glm::dvec3 sun(-kAu, 0, 0);
  const Occluder earth{{0, 0, 0}, 6371e3};
  // 1 m above the ground at midnight and at noon
  EXPECT_EQ(eclipseFactor({6371e3 + 1.0, 0, 0}, sun, kSunRadiusM, earth, nullptr).r, 0.0);
  EXPECT_EQ(eclipseFactor({-6371e3 - 1.0, 0, 0}, sun, kSunRadiusM, earth, nullptr).r, 1.0);
  // 1 m above the ground on the terminator: the Sun's centre sits on the horizontal, and
  // the horizon dips acos(R / (R + 1 m)) = 5.6e-4 rad = 0.12 solar radii below it, so a
  // little more than half of the (limb-darkened) disc shows.
  const double half = eclipseFactor({0, 6371e3 + 1.0, 0}, sun, kSunRadiusM, earth, nullptr).r;
  EXPECT_GT(half, 0.5);
  EXPECT_LT(half, 0.5 + 2.0 * 0.12 / 3.14159 * 1.25);  // strip of width 0.12 at the centre's luminance

  // 1e11 m behind Earth on the axis: the Sun's centre covered by a disc of
  // phi_occ / phi_sun ~ R_occ / R_sun (1 + d / x) -> transit depth R^2 L(0)
  const glm::dvec3 far(1e11, 0, 0);
  const double ratio = std::asin(6371e3 / 1e11) / std::asin(kSunRadiusM / (kAu + 1e11));
  const double depth = 1.0 - eclipseFactor(far, sun, kSunRadiusM, earth, nullptr).r;
  EXPECT_NEAR(depth, ratio * ratio * limbDarkenedLuminance(0.0, kDefaultLimbDarkening), 1e-3 * depth);

  // An occluder of angular radius 1e-7 rad in front of the Sun's centre
  const Occluder pebble{{-1e8, 0, 0}, 10.0};
  const double tiny = 1.0 - eclipseFactor({0, 0, 0}, sun, kSunRadiusM, pebble, nullptr).r;
  const double r = std::asin(10.0 / 1e8) / std::asin(kSunRadiusM / kAu);
  EXPECT_NEAR(tiny, r * r * limbDarkenedLuminance(0.0, kDefaultLimbDarkening), 1e-3 * tiny);
  EXPECT_GT(tiny, 0.0);

  // Through the LuT, the same points give finite values in [0, 1]
  const ShadowLut lut = buildAirlessShadowLut({64, 64});
  for (const glm::dvec3& p : {glm::dvec3(6371e3 + 1.0, 0, 0), glm::dvec3(0, 6371e3 + 1.0, 0), far}) {
    const double f = eclipseFactor(p, sun, kSunRadiusM, earth, &lut).r;
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
  }
}
