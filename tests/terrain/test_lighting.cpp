// Lighting over time: the sweep's visible fractions (terrain/HorizonSweep.hpp) against
// Eq. 7 on a bare sphere, against a ridge's shadow in closed form and against the DP
// search; the statistics (terrain/LightingStatistics.hpp) of known series.
#include "TerrainTestSupport.hpp"

#include "CraterField.hpp"
#include "HorizonSweep.hpp"
#include "LightingStatistics.hpp"

#include <gtest/gtest.h>

using namespace umbra;
using namespace umbra::terrain;

using test::sunAt;

// On the bare sphere nothing rises above a receiver's horizontal but the sphere itself
// (its drop over the first step of the search, 15^2 / 2R = 0.06 mm): Eq. 7's segment at
// the Sun's own elevation at each sample, to 1e-3, for the Sun high, grazing, exactly on
// the horizon (half the disc), below it and at the zenith. (At the grid's edge, where the
// footprint leaves the grid at once, the strip's samples further along stand in: the
// horizon drops by up to 2e-5 rad there.)
TEST(HorizonSweep, BareSphereGivesTheSegmentAtEachSample) {
  const HeightField f = test::flatField(65);
  for (const auto& [e, az] : std::vector<std::pair<double, double>>{{20.0, 30.0}, {0.1, 200.0}, {0.0, 91.0}, {-0.2, 315.0}, {90.0, 0.0}}) {
    const SunDisc sun = sunAt(e, az);
    const std::vector<float> map = sweepVisibleFractionMap(f, sun);
    for (int j = 4; j < 62; j += 8)
      for (int i = 4; i < 62; i += 8) {
        const double local = test::localElevation(f, i, j, sun.direction);
        EXPECT_NEAR(map[static_cast<std::size_t>(j) * 65 + i], test::segmentFraction(local / sun.angularRadiusRad), 1e-3)
            << e << " deg up, sample " << i << ", " << j;
      }
  }
}

// A straight ridge across the grid (rows 40 and 41, 20 m high) with the Sun due north,
// 2 deg up: a receiver t metres south of the ridge sees its crest at
// atan(20 / t - t / 2R); it is in umbra where that is above the disc's top, lit where below
// its bottom (the samples within a quarter of the disc's width of the edge left out).
TEST(HorizonSweep, RidgeShadowEndsWhereTheCrestMeetsTheDisc) {
  HeightField f = test::flatField(64);
  for (int i = 0; i < 64; ++i) f.heightsM[40 * 64 + i] = f.heightsM[41 * 64 + i] = 20.0;
  const SunDisc sun = sunAt(2.0, 0.0);
  const std::vector<float> map = sweepVisibleFractionMap(f, sun);
  int umbra = 0, lit = 0;
  for (int j = 0; j < 40; ++j) {
    const double t = (40 - j) * f.spacingM;  // to the crest's near row
    const double crest = std::atan(20.0 / t - t / (2.0 * f.bodyRadiusM));
    const double e = test::localElevation(f, 32, j, sun.direction);
    const double d = (e - crest) / sun.angularRadiusRad;
    const float v = map[static_cast<std::size_t>(j) * 64 + 32];
    if (d < -1.25) {
      EXPECT_EQ(v, 0.0f) << "row " << j;
      ++umbra;
    }
    if (d > 1.25) {
      EXPECT_EQ(v, 1.0f) << "row " << j;
      ++lit;
    }
  }
  EXPECT_GT(umbra, 5);
  EXPECT_GT(lit, 5);
}

// Against the DP search at every sample of a crater field (the reference of the docs'
// table): the mean difference 0.022-0.023 here (0.01 on 512^2 and more: the grid's edges
// weigh less), and the sweep never returns NaN, also over no-data holes.
TEST(HorizonSweep, AgreesWithTheDpSearchOnACraterField) {
  CraterFieldOptions co;
  co.seed = 3;
  co.size = 128;
  HeightField f = makeCraterField(co);
  const MaximumMipmap mip(f);
  for (const SunDisc& sun : {sunAt(1.5, 140.0), sunAt(5.0, 20.0)}) {
    const std::vector<float> sweep = sweepVisibleFractionMap(f, sun);
    const std::vector<double> dp = visibleFractionMap(f, mip, sun, ShadowOptions{});
    double sum = 0.0;
    for (std::size_t k = 0; k < dp.size(); ++k) sum += std::abs(sweep[k] - dp[k]);
    std::printf("  Sun %.1f deg up: mean |sweep - DP| %.4f\n", std::asin(sun.direction.z) / test::kDeg, sum / dp.size());
    EXPECT_LT(sum / dp.size(), 0.03);
  }
  for (int k = 0; k < 128; ++k) f.heightsM[static_cast<std::size_t>(k) * 128 + 64] = std::nan("");
  for (float v : sweepVisibleFractionMap(f, sunAt(2.0, 95.0))) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
}

// The statistics of a known series at one sample: lit, dark, dark, half, dark, lit, an
// hour each: lit 3 of 6 hours, the longest shadow 2 hours, the mean fraction 2.5 / 6.
TEST(LightingStatistics, KnownSeries) {
  LightingAccumulator acc(1, 1);
  for (float v : {1.0f, 0.0f, 0.0f, 0.5f, 0.0f, 1.0f}) acc.add({v}, 3600.0);
  const LightingMaps m = acc.maps();
  EXPECT_EQ(acc.steps(), 6u);
  EXPECT_DOUBLE_EQ(m.totalS, 6 * 3600.0);
  EXPECT_NEAR(m.litTimeFraction[0], 0.5, 1e-7);
  EXPECT_NEAR(m.longestShadowS[0], 7200.0, 1e-3);
  EXPECT_NEAR(m.meanVisibleFraction[0], 2.5 / 6.0, 1e-7);
  // A shadow to the end of the range counts too; an instant (no time) takes its step's values.
  LightingAccumulator tail(1, 1);
  for (float v : {1.0f, 0.0f, 0.0f, 0.0f}) tail.add({v}, 60.0);
  EXPECT_NEAR(tail.maps().longestShadowS[0], 180.0, 1e-4);
  LightingAccumulator instant(2, 1);
  instant.add({0.25f, 0.0f}, 0.0);
  EXPECT_NEAR(instant.maps().meanVisibleFraction[0], 0.25, 1e-7);
  EXPECT_NEAR(instant.maps().litTimeFraction[0], 1.0, 1e-7);
  EXPECT_EQ(instant.maps().longestShadowS[1], 0.0f);
  EXPECT_THROW(instant.add({0.5f}, 1.0), std::invalid_argument);
  EXPECT_THROW(instant.add({0.5f, std::nanf("")}, 1.0), std::invalid_argument);
  EXPECT_THROW(LightingAccumulator(0, 1), std::invalid_argument);
}

// On a flat plain the share of the time lit follows from the Sun's elevation series alone:
// lit wherever the disc's top is above the sample's horizontal. A Sun circling the sky at
// the pole, its elevation swinging through +-1.5 deg, 200 steps: exact at every sample
// (but where the disc's top is within 1e-5 rad of the horizontal: the sphere's drop over
// the nearest sample, 30 m, is 8.6e-6 rad).
TEST(LightingStatistics, FlatPlainFollowsTheSunsElevationExactly) {
  const HeightField f = test::flatField(33);
  LightingAccumulator acc(33, 33);
  std::vector<int> litSteps(33 * 33, 0), edgeSteps(33 * 33, 0);
  for (int k = 0; k < 200; ++k) {
    const double e = 1.5 * std::sin(2.0 * test::kPi * k / 61.3), az = 360.0 * k / 200.0;
    const SunDisc sun = sunAt(e, az);
    acc.add(sweepVisibleFractionMap(f, sun), 3600.0);
    for (int j = 0; j < 33; ++j)
      for (int i = 0; i < 33; ++i) {
        const double e = test::localElevation(f, i, j, sun.direction) + sun.angularRadiusRad;  // the disc's top
        litSteps[static_cast<std::size_t>(j) * 33 + i] += e > 0.0;
        // Within the sphere's drop over a sample of the horizontal: either way.
        edgeSteps[static_cast<std::size_t>(j) * 33 + i] += std::abs(e) < 1e-5;
      }
  }
  const LightingMaps m = acc.maps();
  int edges = 0;
  for (std::size_t k = 0; k < litSteps.size(); ++k) {
    ASSERT_NEAR(m.litTimeFraction[k], litSteps[k] / 200.0, 1e-6 + edgeSteps[k] / 200.0) << k;
    edges += edgeSteps[k];
  }
  EXPECT_LT(edges, 100);  // (of 217 800 sample-steps)
}

// Statistics made in two parts (the ranks' shares of the time) and joined equal those made
// in one, wherever the series is cut: shadows across the cut, parts all dark or all lit,
// an empty part; through state() and fromState() as the ranks send them.
TEST(LightingStatistics, PartsJoinedEqualTheWhole) {
  const std::vector<std::vector<float>> series{{1, 0, 0, 0.5f, 0, 0, 0, 1, 0},
                                               {0, 0, 0, 0, 0, 0, 0, 0, 0},
                                               {1, 1, 0.2f, 1, 1, 1, 0.7f, 1, 1},
                                               {0, 0, 1, 0, 0, 0, 0, 0, 0.3f}};
  const int n = static_cast<int>(series.size());  // one sample a series
  const std::size_t steps = series.front().size();
  auto stepValues = [&](std::size_t k) {
    std::vector<float> v;
    for (const auto& s : series) v.push_back(s[k]);
    return v;
  };
  auto duration = [](std::size_t k) { return 600.0 + 60.0 * k; };
  LightingAccumulator whole(n, 1);
  for (std::size_t k = 0; k < steps; ++k) whole.add(stepValues(k), duration(k));
  for (std::size_t cut = 0; cut <= steps; ++cut) {
    LightingAccumulator first(n, 1), second(n, 1);
    for (std::size_t k = 0; k < steps; ++k) (k < cut ? first : second).add(stepValues(k), duration(k));
    const std::vector<double> state = second.state();
    first.append(LightingAccumulator::fromState(n, 1, state.data(), state.size()));
    const LightingMaps a = whole.maps(), b = first.maps();
    EXPECT_EQ(first.steps(), steps);
    EXPECT_DOUBLE_EQ(b.totalS, a.totalS);
    for (int s = 0; s < n; ++s) {
      EXPECT_NEAR(b.litTimeFraction[s], a.litTimeFraction[s], 1e-6) << "cut " << cut << ", series " << s;
      EXPECT_NEAR(b.meanVisibleFraction[s], a.meanVisibleFraction[s], 1e-6) << "cut " << cut << ", series " << s;
      EXPECT_EQ(b.longestShadowS[s], a.longestShadowS[s]) << "cut " << cut << ", series " << s;
    }
  }
  EXPECT_EQ(whole.maps().longestShadowS[1], static_cast<float>(9 * 600.0 + 60.0 * 36));  // all dark: the whole time
  const std::vector<double> bad(5, 0.0);
  EXPECT_THROW(LightingAccumulator::fromState(n, 1, bad.data(), bad.size()), std::invalid_argument);
}
