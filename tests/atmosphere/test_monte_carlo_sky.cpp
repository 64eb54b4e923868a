// The Monte-Carlo sky (MonteCarloSky.hpp), the reference for eclipsed skies: single
// scattering along a vertical ray against its closed form, a uniform dimming of the Sun
// passed through exactly, the uneclipsed sky against the precomputed tables, determinism,
// and its errors.
#include "MonteCarloSky.hpp"

#include "ModelTestSupport.hpp"
#include "Sky.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

namespace umbra::atmosphere {
namespace {

using umbra::test::kPi;
constexpr double kDeg = kPi / 180.0;

/// A direction at zenith angle z and azimuth a (from the x axis) at the north pole of the
/// planet, where "up" is +z.
glm::dvec3 dir(double zenithRad, double azimuthRad) {
  return {std::sin(zenithRad) * std::cos(azimuthRad), std::sin(zenithRad) * std::sin(azimuthRad), std::cos(zenithRad)};
}

TEST(MonteCarloSky, SingleScatteringAtTheZenithUnderAZenithSunIsItsClosedForm) {
  // Sun and view both straight up from the ground (a radial ray: exact in the spherical
  // shell): sunlight travels down to altitude h and, scattered forward (nu = 1), on down to
  // the observer, so every height's light crosses the whole column once:
  //   L = sum_c p_c(1) tau_s,c exp(-tau).
  const Atmosphere atm = loadAtmosphere("earth-bruneton", test::threeWavelengthsNm());
  const glm::dvec3 observer(0.0, 0.0, atm.bottomRadiusM);
  MonteCarloSkyOptions o;
  o.maxOrders = 1;
  o.paths = 400000;
  const MonteCarloSky sky = monteCarloSkyRadiance(atm, observer, {dir(0, 0)}, dir(0, 0), {}, o);
  for (std::size_t w = 0; w < atm.wavelengthsNm.size(); ++w) {
    double expected = 0.0, tau = 0.0;
    for (const Component& c : atm.components) {
      const double column = c.density.integral(0.0, atm.thicknessM());
      expected += c.phase(w)(1.0) * c.scatteringPerM[w] * column;
      tau += c.extinctionPerM(w) * column;
    }
    expected *= std::exp(-tau);
    const double L = sky.directions[0].radiance[w], se = sky.directions[0].standardError[w];
    std::printf("%.0f nm: Monte-Carlo %.5e +- %.1e, closed form %.5e\n", atm.wavelengthsNm[w], L, se, expected);
    EXPECT_NEAR(L, expected, 4.0 * se) << atm.wavelengthsNm[w];
    EXPECT_LT(se, 0.03 * expected);
  }
}

TEST(MonteCarloSky, ASunDimmedEverywhereDimsTheSkyByTheSameFactorForTheSameSeed) {
  const Atmosphere atm = loadAtmosphere("earth-bruneton", test::threeWavelengthsNm());
  const glm::dvec3 observer(0.0, 0.0, atm.bottomRadiusM + 100.0);
  const std::vector<glm::dvec3> views{dir(0, 0), dir(70 * kDeg, 2.0)};
  MonteCarloSkyOptions o;
  o.paths = 3000;
  const MonteCarloSky full = monteCarloSkyRadiance(atm, observer, views, dir(40 * kDeg, 0.0), {}, o);
  const MonteCarloSky dim =
      monteCarloSkyRadiance(atm, observer, views, dir(40 * kDeg, 0.0), [](const glm::dvec3&) { return 0.37; }, o);
  for (std::size_t k = 0; k < views.size(); ++k)
    for (std::size_t w = 0; w < 3; ++w) {
      EXPECT_GT(full.directions[k].radiance[w], 0.0);
      EXPECT_NEAR(dim.directions[k].radiance[w] / full.directions[k].radiance[w], 0.37, 1e-12);
    }
  const MonteCarloSky dark =
      monteCarloSkyRadiance(atm, observer, views, dir(40 * kDeg, 0.0), [](const glm::dvec3&) { return 0.0; }, o);
  for (const MonteCarloRadiance& d : dark.directions)
    for (double L : d.radiance) EXPECT_EQ(L, 0.0);
}

TEST(MonteCarloSky, TheSameSeedGivesTheSameSkyOnAnyNumberOfThreads) {
  const Atmosphere atm = loadAtmosphere("earth-bruneton", {550.0});
  const glm::dvec3 observer(0.0, 0.0, atm.bottomRadiusM);
  MonteCarloSkyOptions o;
  o.paths = 2000;
  o.threads = 1;
  const MonteCarloSky one = monteCarloSkyRadiance(atm, observer, {dir(50 * kDeg, 1.0)}, dir(30 * kDeg, 0.0), {}, o);
  o.threads = 2;
  const MonteCarloSky two = monteCarloSkyRadiance(atm, observer, {dir(50 * kDeg, 1.0)}, dir(30 * kDeg, 0.0), {}, o);
  EXPECT_EQ(one.directions[0].radiance[0], two.directions[0].radiance[0]);
  o.seed = 2;
  const MonteCarloSky other = monteCarloSkyRadiance(atm, observer, {dir(50 * kDeg, 1.0)}, dir(30 * kDeg, 0.0), {}, o);
  EXPECT_NE(one.directions[0].radiance[0], other.directions[0].radiance[0]);
  EXPECT_NEAR(one.directions[0].radiance[0], other.directions[0].radiance[0],
              5.0 * std::hypot(one.directions[0].standardError[0], other.directions[0].standardError[0]));
}

TEST(MonteCarloSky, TheUneclipsedSkyAgreesWithThePrecomputedTables) {
  // Two independent computations of the same sky: the tables (Bruneton's method at the sky
  // command's sizes, 4 orders) and the Monte-Carlo (every order). They differ by the
  // tables' own error (a few per cent) and the fifth and later orders (< 1 %).
  const WavelengthSet set = WavelengthSet::rgb();
  const Atmosphere atm = loadAtmosphere("earth-bruneton", set.nm);
  const AtmosphereTables tables = precompute(atm, skyPrecomputeOptions(atm, 4));
  const double sunZenith = 30 * kDeg;
  const glm::dvec3 observer(0.0, 0.0, atm.bottomRadiusM);
  struct View {
    double zenith, azimuth;
  };
  const std::vector<View> views{{0, 0}, {60 * kDeg, 90 * kDeg}, {80 * kDeg, 180 * kDeg}, {45 * kDeg, 30 * kDeg}};
  std::vector<glm::dvec3> directions;
  for (const View& v : views) directions.push_back(dir(v.zenith, v.azimuth));
  MonteCarloSkyOptions o;
  o.paths = 100000;
  const MonteCarloSky sky = monteCarloSkyRadiance(atm, observer, directions, dir(sunZenith, 0.0), {}, o);
  for (std::size_t k = 0; k < views.size(); ++k) {
    const glm::dvec3 d = directions[k];
    const std::vector<double> table =
        skyRadiance(tables, atm, atm.bottomRadiusM, d.z, std::cos(sunZenith), glm::dot(d, dir(sunZenith, 0.0)));
    for (std::size_t w = 0; w < set.size(); ++w) {
      const double L = sky.directions[k].radiance[w], se = sky.directions[k].standardError[w];
      std::printf("Z %.0f A %.0f %.0f nm: Monte-Carlo %.5e +- %.1e, tables %.5e (%+.1f %%)\n", views[k].zenith / kDeg,
                  views[k].azimuth / kDeg, set.nm[w], L, se, table[w], 100.0 * (L / table[w] - 1.0));
      EXPECT_NEAR(L, table[w], 0.04 * table[w] + 4.0 * se) << k << " " << w;
    }
  }
}

TEST(MonteCarloSky, BadInputIsAClearError) {
  const Atmosphere atm = loadAtmosphere("earth-bruneton", {550.0});
  const glm::dvec3 ground(0.0, 0.0, atm.bottomRadiusM);
  EXPECT_THROW(monteCarloSkyRadiance(atm, ground * 0.99, {dir(0, 0)}, dir(0, 0)), std::invalid_argument);
  EXPECT_THROW(monteCarloSkyRadiance(atm, ground * 1.1, {dir(0, 0)}, dir(0, 0)), std::invalid_argument);
  EXPECT_THROW(monteCarloSkyRadiance(atm, ground, {glm::dvec3(0, 0, 2)}, dir(0, 0)), std::invalid_argument);
  EXPECT_THROW(monteCarloSkyRadiance(atm, ground, {dir(0, 0)}, glm::dvec3(0)), std::invalid_argument);
  MonteCarloSkyOptions o;
  o.paths = 0;
  EXPECT_THROW(monteCarloSkyRadiance(atm, ground, {dir(0, 0)}, dir(0, 0), {}, o), std::invalid_argument);
  o.paths = 100;
  int calls = 0;
  EXPECT_THROW(monteCarloSkyRadiance(atm, ground, {dir(0, 0)}, dir(0, 0), {}, o,
                                     [&](double) { return ++calls < 1; }),
               MonteCarloCancelled);
}

TEST(MonteCarloSky, TheMajorantBoundsTheExtinctionEverywhere) {
  for (const char* preset : {"earth-bruneton", "earth", "mars"}) {
    const Atmosphere atm = loadAtmosphere(preset, test::threeWavelengthsNm());
    const std::vector<double> m = extinctionMajorantPerM(atm);
    for (double h = 0.0; h <= atm.thicknessM(); h += 37.0) {
      const std::vector<double> e = atm.extinctionPerM(h);
      for (std::size_t w = 0; w < e.size(); ++w) ASSERT_LE(e[w], m[w]) << preset << " " << h;
    }
    // and not far above the largest (at the ground for these presets)
    const std::vector<double> e0 = atm.extinctionPerM(0.0);
    for (std::size_t w = 0; w < e0.size(); ++w) EXPECT_LT(m[w], 1.5 * e0[w]) << preset;
  }
}

}  // namespace
}  // namespace umbra::atmosphere
