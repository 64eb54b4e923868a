#include "ShadowLut.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

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

// The u range: [0, 1] is the table as before, bit for bit (texel centres and sampling).
TEST(ShadowLutURange, DefaultRangeIsTheWholeTableBitForBit) {
  ShadowLutParams p{48, 40};
  const ShadowLut a = buildAirlessShadowLut(p);
  p.uMin = 0.0, p.uMax = 1.0;
  const ShadowLut b = buildAirlessShadowLut(p);
  EXPECT_EQ(a.rgb, b.rgb);
  ASSERT_EQ(a.rgb.size(), 3u * 48 * 40);
  EXPECT_EQ(a.rgb[3 * (7 * 48 + 5)], static_cast<float>(airlessShadow({5.5 / 48, 7.5 / 40})));
  for (double u : {0.0, 0.013, 0.4, 0.77, 1.0})
    for (double v : {0.0, 0.31, 0.99}) {
      const double x = std::clamp(u * 48 - 0.5, 0.0, 47.0), y = std::clamp(v * 40 - 0.5, 0.0, 39.0);
      const int i = std::min(static_cast<int>(x), 46), j = std::min(static_cast<int>(y), 38);
      const double fx = x - i, fy = y - j;
      const double expected = (1 - fy) * ((1 - fx) * a.texel(i, j).r + fx * a.texel(i + 1, j).r) +
                              fy * ((1 - fx) * a.texel(i, j + 1).r + fx * a.texel(i + 1, j + 1).r);
      EXPECT_EQ(a.sample({u, v}).r, expected);
    }
  EXPECT_THROW(buildAirlessShadowLut({8, 8, kDefaultLimbDarkening, 1e-10, 0.5, 0.5}), std::invalid_argument);
  EXPECT_THROW(buildAirlessShadowLut({8, 8, kDefaultLimbDarkening, 1e-10, 0.0, 1.0, 0.2, 0.1}), std::invalid_argument);
  EXPECT_THROW(buildAirlessShadowLut({8, 8, kDefaultLimbDarkening, 1e-10, -0.1, 0.5}), std::invalid_argument);
}

// A ranged LuT's texels hold the shadow function at their centres in the range.
TEST(ShadowLutURange, TexelsHoldTheShadowFunctionAtTheirCentresInTheRanges) {
  const ShadowLut lut = buildAirlessShadowLut({16, 16, kDefaultLimbDarkening, 1e-10, 0.002, 0.004, 0.99, 1.0});
  for (int i : {0, 7, 15})
    for (int j : {0, 9, 15}) {
      const double u = 0.002 + 0.002 * (i + 0.5) / 16, v = 0.99 + 0.01 * (j + 0.5) / 16;
      EXPECT_FLOAT_EQ(lut.texel(i, j).r, static_cast<float>(airlessShadow({u, v})));
      EXPECT_NEAR(lut.sample({u, v}).r, lut.texel(i, j).r, 1e-12);
    }
  // A split v axis: rows [0, 4) over [0, 0.6], [4, 16) over [0.6, 1]; texels at the centres.
  const ShadowLut split = buildAirlessShadowLut({16, 16, kDefaultLimbDarkening, 1e-10, 0.3, 0.4, 0.6, 1.0, 0.25});
  for (int j = 0; j < 16; ++j) {
    const double t = (j + 0.5) / 16, v = t < 0.25 ? 0.6 * t / 0.25 : 0.6 + 0.4 * (t - 0.25) / 0.75;
    EXPECT_NEAR(split.texelV(j), v, 1e-15);
    EXPECT_NEAR(split.textureV(v), t, 1e-15);
    EXPECT_FLOAT_EQ(split.texel(3, j).r, static_cast<float>(airlessShadow({split.texelU(3), v})));
    EXPECT_NEAR(split.sample({split.texelU(3), v}).r, split.texel(3, j).r, 1e-12);
  }
  EXPECT_THROW(buildAirlessShadowLut({8, 8, kDefaultLimbDarkening, 1e-10, 0.0, 1.0, 0.0, 1.0, 0.25}), std::invalid_argument);
}

namespace {
// Mars' shadow at Phobos (a = 9376 km, radius 11.1 km) or Deimos (23 463 km, 6.2 km):
// the largest |LuT - exact| over arcs at the receiver's nearest, mean and farthest
// distance from Mars' centre, from the axis to 1.1 x the penumbra's angular radius.
double marsShadowError(const ShadowLut& lut, double orbitM, double radiusM) {
  const SunOccluderSystem mars{kSunRadiusM, 3389.5e3, 1.523679 * kAu};
  const glm::dvec3 sun(-mars.sunOccluderDistanceM, 0, 0);
  const Occluder occ{{0, 0, 0}, mars.occluderRadiusM};
  double worst = 0.0;
  for (double d : {orbitM - radiusM, orbitM, orbitM + radiusM}) {
    const double maxAngle = 1.1 * std::asin(shadowConeRadii(mars, d).penumbraRadiusM / d);
    for (int k = 0; k <= 400; ++k) {
      const double a = maxAngle * k / 400;
      const glm::dvec3 p(d * std::cos(a), d * std::sin(a), 0.0);
      const double exact = eclipseFactor(p, sun, kSunRadiusM, occ, nullptr).r;
      worst = std::max(worst, std::abs(eclipseFactor(p, sun, kSunRadiusM, occ, &lut).r - exact));
    }
  }
  return worst;
}
} // namespace

// Near the occluder Eq. 4 crowds the shadow into the first u texels: at Phobos a whole
// 64^2 LuT is far off, one over Phobos' distances only is accurate (docs/eclipse-shadows.md).
TEST(ShadowLutURange, ARangeOverPhobosDistancesResolvesItsShadow) {
  const SunOccluderSystem mars{kSunRadiusM, 3389.5e3, 1.523679 * kAu};
  for (const auto& [orbitM, radiusM] : {std::pair{9376e3, 11.1e3}, std::pair{23463e3, 6.2e3}}) {
    const LutRange r = lutRangeForDistances(mars, orbitM - radiusM, orbitM + radiusM, true, 64);
    ASSERT_LT(r.uMin, r.uMax);
    // The range holds every point of the shadow at these distances (on and off the axis).
    for (double d : {orbitM - radiusM, orbitM + radiusM})
      for (double a : {0.0, 0.999 * std::asin(shadowConeRadii(mars, d).penumbraRadiusM / d)}) {
        const glm::dvec3 p(d * std::cos(a), d * std::sin(a), 0.0);
        const LutCoords c = lutCoords(shadowAngles(p, {-mars.sunOccluderDistanceM, 0, 0}, kSunRadiusM, {0, 0, 0}, 3389.5e3));
        EXPECT_GE(c.u, r.uMin);
        EXPECT_LE(c.u, r.uMax);
      }
    const ShadowLut whole = buildAirlessShadowLut({64, 64});
    const ShadowLut ranged = buildAirlessShadowLut({64, 64, kDefaultLimbDarkening, 1e-10, r.uMin, r.uMax, r.vMin, r.vMax});
    const ShadowLut uOnly = buildAirlessShadowLut({64, 64, kDefaultLimbDarkening, 1e-10, r.uMin, r.uMax});
    const double before = marsShadowError(whole, orbitM, radiusM), after = marsShadowError(ranged, orbitM, radiusM);
    std::printf("  Mars' shadow at %.0f km, 64^2: max |LuT - exact| %.3g whole, %.3g u range only, %.3g ranged "
                "u [%.6g, %.6g] v [%.6g, 1]\n",
                orbitM / 1e3, before, marsShadowError(uOnly, orbitM, radiusM), after, r.uMin, r.uMax, r.vMin);
    // Row 0 is in the umbra for every u of the range: clamping below it reads 0.
    for (int i = 0; i < 64; ++i) EXPECT_EQ(ranged.texel(i, 0).r, 0.0);
    EXPECT_LT(after, 1e-3);
    EXPECT_LT(after, before / 10.0);
  }
  EXPECT_THROW(lutRangeForDistances(mars, 0.0, 1e6), std::invalid_argument);
  EXPECT_THROW(lutRangeForDistances(mars, 2e6, 1e6), std::invalid_argument);
}

// LutRange::textureMap (the shader's form) gives textureU and textureV, split axis included.
TEST(ShadowLutURange, TextureMapIsTextureUAndV) {
  for (const LutRange& r : {LutRange{}, LutRange{0.2, 0.3, 0.4, 0.9, 0.0}, LutRange{0.006, 0.0061, 0.95, 1.0, 0.25}}) {
    const LutRange::TextureMap m = r.textureMap();
    for (int k = 0; k <= 200; ++k) {
      const double x = k / 200.0;
      EXPECT_NEAR((x - m.uOrigin) * m.uScale, r.textureU(x), 1e-9 * (1.0 + std::abs(r.textureU(x))));
      const bool low = x < m.vSplit;
      EXPECT_NEAR((x - (low ? m.vLowOrigin : m.vOrigin)) * (low ? m.vLowScale : m.vScale), r.textureV(x),
                  1e-9 * (1.0 + std::abs(r.textureV(x))));
    }
  }
}

namespace umbra::eclipse {
namespace {

// Three processes' shares of a LuT (the ranks of an MPI run): each texel in exactly one
// share, with the whole LuT's value to the bit; the others 0.
TEST(ShadowLut, TexelSharesTogetherAreTheWholeLut) {
  const ShadowLutParams params{24, 20};
  const ShadowLut whole = buildAirlessShadowLut(params);
  std::vector<int> owners(whole.rgb.size() / 3, 0);
  for (int index = 0; index < 3; ++index) {
    const TexelShare share{index, 3};
    const ShadowLut part = buildAirlessShadowLut(params, {}, share);
    ASSERT_EQ(part.rgb.size(), whole.rgb.size());
    for (std::size_t k = 0; k < owners.size(); ++k)
      for (int q = 0; q < 3; ++q) {
        const float v = part.rgb[3 * k + q];
        if (share.owns(static_cast<long long>(k))) {
          EXPECT_EQ(v, whole.rgb[3 * k + q]) << k;
        } else {
          EXPECT_EQ(v, 0.0f) << k;
        }
      }
    for (std::size_t k = 0; k < owners.size(); ++k) owners[k] += share.owns(static_cast<long long>(k)) ? 1 : 0;
    EXPECT_EQ(share.texels(static_cast<int>(owners.size())),
              static_cast<int>((owners.size() + 2 - static_cast<std::size_t>(index)) / 3));
  }
  for (int n : owners) EXPECT_EQ(n, 1);
  EXPECT_THROW(buildAirlessShadowLut(params, {}, TexelShare{3, 3}), std::invalid_argument);
}

}  // namespace
}  // namespace umbra::eclipse

// Light time (occluderSeenBy): an occluder at rest stays; a moving one goes back along its
// velocity by the light time from its centre to the receiver's near surface, plus the
// receiver's own delay, less the delay it is given at; the distances are the Moon's.
TEST(LightTime, AMovingOccluderGoesBackByItsLightTimeToTheReceiversSurface) {
  const glm::dvec3 earth(1.5e11, 0.0, 0.0), moonAt(1.5e11, 3.844e8, 0.0);
  const double earthRadius = 6.371e6;
  const Occluder still{moonAt, 1.7374e6};
  EXPECT_EQ(occluderSeenBy(still, earth, earthRadius, 2.0).centreM, moonAt);

  const glm::dvec3 v(0.0, 0.0, 3.0e4);
  const double toSurfaceS = (3.844e8 - earthRadius) / kLightSpeedMps;
  EXPECT_NEAR(lightTimeToSurfaceS(moonAt, earth, earthRadius), toSurfaceS, 1e-12);
  EXPECT_EQ(lightTimeToSurfaceS(earth + glm::dvec3(1.0, 0.0, 0.0), earth, earthRadius), 0.0);  // inside
  const Occluder moving{moonAt, 1.7374e6, {}, v};
  const Occluder seen = occluderSeenBy(moving, earth, earthRadius, 0.0);
  EXPECT_NEAR(seen.centreM.z, -3.0e4 * toSurfaceS, 1e-6);  // 37.8 km
  EXPECT_NEAR(seen.lightDelayS, toSurfaceS, 1e-12);
  // Drawn 0.5 s back already, seen by a receiver drawn 2 s back: 2 + 1.26 - 0.5 s more.
  const Occluder drawn{moonAt, 1.7374e6, {}, v, 0.5};
  EXPECT_NEAR(occluderSeenBy(drawn, earth, earthRadius, 2.0).centreM.z, -3.0e4 * (2.0 + toSurfaceS - 0.5), 1e-6);
  // Seen again by the same receiver, it stays (the delay it carries is the receiver's).
  EXPECT_NEAR(occluderSeenBy(seen, earth, earthRadius, 0.0).centreM.z, seen.centreM.z, 1e-3);
}
