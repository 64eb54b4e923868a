// The Milky Way map's layout, star removal and calibration (sky/MilkyWay.hpp), on
// synthetic maps.
#include "MilkyWay.hpp"
#include "StarLight.hpp"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::sky;

namespace {

constexpr double kPi = 3.14159265358979323846, kDeg = kPi / 180.0;

glm::dvec3 raDec(double raDeg, double decDeg) { return icrsDirection(raDeg * kDeg, decDeg * kDeg); }

MilkyWayMap uniformMap(int width, int height, float value) {
  MilkyWayMap m;
  m.width = width;
  m.height = height;
  m.rgb.assign(static_cast<std::size_t>(width) * height * 3, value);
  return m;
}

// The texel (column, row) whose centre is nearest to a direction.
std::pair<int, int> texelOf(const MilkyWayMap& m, const glm::dvec3& d) {
  const glm::dvec2 uv = milkyWayMapCoord(d);
  return {static_cast<int>(std::floor(uv.x * m.width)), static_cast<int>(std::floor(uv.y * m.height))};
}

void setTexel(MilkyWayMap& m, int i, int j, float v) {
  for (int c = 0; c < 3; ++c) m.rgb[3 * (static_cast<std::size_t>(j) * m.width + i) + c] = v;
}

}  // namespace

// The layout: RA 90 deg at the left edge, decreasing to the right; Dec -90 deg at v = 0,
// +90 at v = 1; and the inverse gives the direction back.
TEST(MilkyWay, MapLayoutAndRoundTrip) {
  EXPECT_NEAR(milkyWayMapCoord(raDec(90.0 - 1e-9, 0.0)).x, 0.0, 1e-9);
  EXPECT_NEAR(milkyWayMapCoord(raDec(0.0, 0.0)).x, 0.25, 1e-12);
  EXPECT_NEAR(milkyWayMapCoord(raDec(270.0, 0.0)).x, 0.5, 1e-12);
  EXPECT_NEAR(milkyWayMapCoord(raDec(0.0, 0.0)).y, 0.5, 1e-12);
  EXPECT_NEAR(milkyWayMapCoord(raDec(0.0, 60.0)).y, 150.0 / 180.0, 1e-12);
  EXPECT_NEAR(milkyWayMapCoord(raDec(10.0, -89.0)).y, 1.0 / 180.0, 1e-12);
  for (double ra = 3.0; ra < 360.0; ra += 37.0)
    for (double dec = -87.0; dec < 90.0; dec += 29.0) {
      const glm::dvec3 d = raDec(ra, dec);
      EXPECT_LT(glm::length(milkyWayDirection(milkyWayMapCoord(d)) - d), 1e-12) << ra << ", " << dec;
    }
}

// 1 S10 (one V = 10 star per square degree) is 10 + 2.5 log10(3600^2) = 27.78 V mag per
// square arcsecond; 250 S10, 6.0 mag brighter.
TEST(MilkyWay, S10InMagnitudesPerSquareArcsecond) {
  EXPECT_NEAR(s10ToVMagPerArcsec2(1.0), 10.0 + 2.5 * std::log10(3600.0 * 3600.0), 1e-12);
  EXPECT_NEAR(s10ToVMagPerArcsec2(1.0), 27.782, 5e-4);
  EXPECT_NEAR(s10ToVMagPerArcsec2(kMilkyWayBrightestS10), 27.782 - 2.5 * std::log10(250.0), 5e-4);
}

// A star's dot takes its surroundings' value; a star fainter than the map shows, or one
// beyond the list, is left; a dot's ring ignores its neighbours' dot.
TEST(MilkyWay, RemoveStarsTakesOutTheirDotsOnly) {
  MilkyWayMap m = uniformMap(720, 360, 0.1f);
  const glm::dvec3 bright = raDec(100.0, 20.0), faint = raDec(200.0, -30.0), dim = raDec(300.0, 50.0);
  const auto [bi, bj] = texelOf(m, bright);
  const auto [fi, fj] = texelOf(m, faint);
  const auto [di, dj] = texelOf(m, dim);
  for (int dj2 = -1; dj2 <= 1; ++dj2)
    for (int di2 = -1; di2 <= 1; ++di2) setTexel(m, bi + di2, bj + dj2, 1.0f);
  setTexel(m, fi, fj, 1.0f);
  setTexel(m, di, dj, 0.7f);
  removeStars(m, {bright, faint, dim}, {0.5, kMilkyWayStarsShownToV + 0.5, 4.0});
  for (int dj2 = -1; dj2 <= 1; ++dj2)
    for (int di2 = -1; di2 <= 1; ++di2) EXPECT_FLOAT_EQ(m.at(bi + di2, bj + dj2).g, 0.1f);
  EXPECT_FLOAT_EQ(m.at(fi, fj).g, 1.0f);  // fainter than the map shows: left
  EXPECT_FLOAT_EQ(m.at(di, dj).g, 0.1f);
  EXPECT_THROW(removeStars(m, {bright}, {}), std::invalid_argument);
}

// The brightest cap: a 0.8-deg patch of 1.0 on a 0.01 background, across the map's seam
// (RA 90 deg) and near a pole, is found within a texel, and its cap mean is the patch's
// share of the cap; the radiance scale gives that cap 250 S10.
TEST(MilkyWay, BrightestCapAndCalibration) {
  for (const glm::dvec3 centre : {raDec(90.0, -29.0), raDec(271.0, 75.0)}) {
    MilkyWayMap m = uniformMap(1440, 720, 0.01f);
    const double patchRad = 0.8 * kDeg;
    for (int j = 0; j < m.height; ++j)
      for (int i = 0; i < m.width; ++i) {
        const glm::dvec3 d = milkyWayDirection({(i + 0.5) / m.width, (j + 0.5) / m.height});
        if (glm::dot(d, centre) >= std::cos(patchRad)) setTexel(m, i, j, 1.0f);
      }
    const BrightestCap cap = brightestCap(m, kMilkyWayCalibrationCapRad);
    const double offRad = std::acos(std::min(1.0, glm::dot(cap.direction, centre)));
    EXPECT_LT(offRad, 0.5 * kDeg) << "found " << offRad / kDeg << " deg away";
    const double y1 = frameLuminance(glm::dvec3(1.0)), y0 = frameLuminance(glm::dvec3(0.01));
    const double share = (cap.meanLuminance - y0) / (y1 - y0);
    EXPECT_NEAR(share, 0.64, 0.06);  // (0.8 / 1.0)^2 of the cap, give or take the texels' ragged rims
    EXPECT_NEAR(capMeanLuminance(m, cap.direction, kMilkyWayCalibrationCapRad), cap.meanLuminance, 1e-12);
    const double scale = milkyWayRadianceScale(m, 1361.0);
    EXPECT_NEAR(scale * cap.meanLuminance,
                radianceOfSurfaceBrightnessWm2Sr(s10ToVMagPerArcsec2(kMilkyWayBrightestS10), 1361.0), 1e-18);
  }
  EXPECT_THROW(milkyWayRadianceScale(uniformMap(64, 32, 0.0f), 1361.0), std::invalid_argument);
}

// The night glow with a Milky Way drawn: less the map's mean over the sky, never below 0.
TEST(MilkyWay, NightGlowLessTheMapsMean) {
  const double glow = nightGlowAboveAirWm2Sr(0.125, 1361.0);
  EXPECT_DOUBLE_EQ(nightGlowAboveAirWm2Sr(0.125, 1361.0, 0.01 * glow), 0.99 * glow);
  EXPECT_EQ(nightGlowAboveAirWm2Sr(0.125, 1361.0, 2.0 * glow), 0.0);
  // The glow is the dark site's zenith above the air: 22.0 V mag per square arcsecond times e^tau.
  EXPECT_NEAR(glow, radianceOfSurfaceBrightnessWm2Sr(kDarkSkyZenithVMagPerArcsec2, 1361.0) * std::exp(0.125), 1e-20);
}

// The frames' luminance of white is 1 (the Sun's colour at unit luminance undone; its
// weights, Rec. 709's to 4 digits, within 1e-4).
TEST(MilkyWay, FrameLuminanceOfTheSunsWhite) {
  EXPECT_NEAR(frameLuminance(glm::dvec3(1.0)), 1.0, 1e-4);
  EXPECT_NEAR(sphereMeanLuminance(uniformMap(90, 45, 0.25f)), 0.25 * frameLuminance(glm::dvec3(1.0)), 1e-6);
}
