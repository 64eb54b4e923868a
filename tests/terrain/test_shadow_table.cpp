// Shadow tables (terrain/ShadowTable.hpp): the Sun's rounding and the cache key, the
// lookup against the per-pixel DP search, a flat site against Eq. 7, and the extremes.
#include "TerrainTestSupport.hpp"

#include "CraterField.hpp"
#include "ShadowTable.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace umbra;
using namespace umbra::terrain;

using test::sunAt;

// The rounded Sun lies within half a step of the Sun in elevation and azimuth, and every
// Sun within the same step gets the same table key; a step on, another.
TEST(ShadowTable, SunsWithinAStepShareATable) {
  const HeightField f = test::flatField(8);
  const double step = kDefaultSunStepRad;
  const SunDisc a = sunAt(0.9403, 37.2101);
  const SunDisc r = roundedSun(a, step);
  const glm::dvec3 d = glm::normalize(r.direction);
  EXPECT_NEAR(std::asin(d.z), 0.9403 * test::kDeg, 0.5 * step + 1e-12);
  EXPECT_NEAR(std::atan2(d.x, d.y), 37.2101 * test::kDeg, 0.5 * step + 1e-12);
  EXPECT_NEAR(r.angularRadiusRad, a.angularRadiusRad, step / 40.0 + 1e-15);
  const ShadowOptions o;
  const auto key = shadowTableKey(f, r, step, o, kDefaultNearTexels);
  const SunDisc nearby = roundedSun(sunAt(0.9403 + 0.2 * step / test::kDeg, 37.2101 - 0.2 * step / test::kDeg), step);
  EXPECT_EQ(shadowTableKey(f, nearby, step, o, kDefaultNearTexels), key);
  const SunDisc stepOn = roundedSun(sunAt(0.9403 + step / test::kDeg, 37.2101), step);
  EXPECT_NE(shadowTableKey(f, stepOn, step, o, kDefaultNearTexels), key);
  // Another height field (one sample changed), another key.
  HeightField g = f;
  g.heightsM[3] = 1.0;
  EXPECT_NE(shadowTableKey(g, r, step, o, kDefaultNearTexels), key);
  EXPECT_THROW(roundedSun(a, 0.0), std::invalid_argument);
}

// A flat site (the bare sphere): the horizon is the sphere's own, so with the Sun's centre
// e above the local horizontal the fraction is Eq. 7's segment at d = e / radius, at
// samples and between them; the Sun exactly on the horizon gives half the disc.
TEST(ShadowTable, FlatSiteGivesTheSegmentOfEq7) {
  const HeightField f = test::flatField(65);
  const MaximumMipmap mip(f);
  for (double elevationDeg : {0.0, 0.1, -0.15, 0.3}) {
    const SunDisc sun = sunAt(elevationDeg, 120.0);
    const ShadowTable t = makeShadowTable(f, mip, sun, ShadowOptions{});
    for (glm::dvec2 g : {glm::dvec2(32.0, 32.0), glm::dvec2(10.25, 50.5), glm::dvec2(0.0, 64.0)}) {
      const glm::dvec3 up = f.direction(g.x, g.y);
      const double e = std::asin(glm::dot(glm::normalize(sun.direction), up));
      const double fraction = t.fractionAt(f, mip, g);
      EXPECT_NEAR(fraction, test::segmentFraction(e / sun.angularRadiusRad), 1e-4)
          << elevationDeg << " deg at " << g.x << ", " << g.y;
    }
  }
}

// The lookup against the per-pixel DP search (the renderer's reference path) at random
// points between samples of a crater field, the Sun rounded to the default step: mean
// |difference| 1.2e-3 here, below the 2e-3 asked of a table (the near stretch searched
// exactly, cell by cell; docs/accuracy-vs-speed/terrain.md, "Shadow tables"), and every
// lookup finite.
TEST(ShadowTable, LookupAgreesWithTheSearchPerPixel) {
  CraterFieldOptions co;
  co.seed = 7;
  co.size = 160;
  const HeightField f = makeCraterField(co);
  const MaximumMipmap mip(f);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double sum = 0.0;
  int n = 0, penumbra = 0;
  for (const SunDisc& sun : {sunAt(1.3, 140.0), sunAt(4.0, 253.0)}) {
    const ShadowTable t = makeShadowTable(f, mip, roundedSun(sun, kDefaultSunStepRad), ShadowOptions{});
    for (int k = 0; k < 3000; ++k) {
      const glm::dvec2 g(unit(rng) * (f.width - 1), unit(rng) * (f.height - 1));
      const double dp = discFractionAboveHorizon(horizonTowardsSunAt(f, mip, g, f.bilinear(g.x, g.y), sun, {}), sun);
      const double table = t.fractionAt(f, mip, g);
      ASSERT_TRUE(std::isfinite(table));
      sum += std::abs(table - dp);
      ++n;
      penumbra += dp > 1e-3 && dp < 1.0 - 1e-3;
    }
  }
  std::printf("  mean |table - DP| %.5f over %d points (%d in the penumbra)\n", sum / n, n, penumbra);
  EXPECT_GT(penumbra, 50);
  EXPECT_LT(sum / n, 2e-3);
}

// Extremes: no-data holes, the smallest field, the Sun at the zenith and below the
// horizon: finite offsets, fractions in [0, 1]; a field too small is refused by name.
TEST(ShadowTable, ExtremesGiveFiniteFractions) {
  HeightField holes = test::flatField(33);
  for (int k = 0; k < 33; ++k) holes.heightsM[static_cast<std::size_t>(k) * 33 + 16] = std::nan("");
  holes.heightsM[5] = 200.0;
  HeightField smallest = test::flatField(2);
  smallest.heightsM = {0.0, 50.0, 10.0, 0.0};
  for (const HeightField* f : {&holes, &smallest}) {
    const MaximumMipmap mip(*f);
    for (const SunDisc& sun : {sunAt(90.0, 0.0), sunAt(0.0, 45.0), sunAt(-30.0, 200.0), sunAt(2.0, 90.0)}) {
      const ShadowTable t = makeShadowTable(*f, mip, roundedSun(sun, kDefaultSunStepRad), ShadowOptions{});
      for (float d : t.offsets) ASSERT_TRUE(std::isfinite(d));
      for (glm::dvec2 g : {glm::dvec2(0.0), glm::dvec2(0.5, 0.7), glm::dvec2(f->width - 1.0, f->height - 1.0)}) {
        const double v = t.fractionAt(*f, mip, g);
        EXPECT_GE(v, 0.0);
        EXPECT_LE(v, 1.0);
      }
    }
  }
  HeightField one = test::flatField(1);
  EXPECT_THROW(MaximumMipmap{one}, std::invalid_argument);
}
