// Albedo maps (sky/AlbedoMap.hpp): sampling, the disc mean that keeps the geometric
// albedo, and the filling of a mosaic's marks.
#include "AlbedoMap.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::sky;

namespace {
constexpr double kPi = 3.14159265358979323846;

AlbedoMap uniformMap(int w, int h, float v) { return {w, h, std::vector<float>(static_cast<std::size_t>(w) * h, v)}; }
}  // namespace

// Bilinear between texel centres: exact on a map linear in longitude over its middle;
// longitude wraps (texels 0 and w-1 are neighbours), latitude clamps.
TEST(AlbedoMap, SampleIsBilinearAndWraps) {
  AlbedoMap m = uniformMap(8, 4, 0.0f);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i) m.values[j * 8 + i] = static_cast<float>(i + 10 * j);
  const double lonOf = 2.0 * kPi / 8, latOf = kPi / 4;
  auto lon = [&](double i) { return (i + 0.5) * lonOf - kPi; };
  auto lat = [&](double j) { return (j + 0.5) * latOf - 0.5 * kPi; };
  EXPECT_DOUBLE_EQ(sample(m, lon(3), lat(1)), 13.0);
  EXPECT_NEAR(sample(m, lon(3.25), lat(1.5)), 18.25, 1e-12);
  EXPECT_NEAR(sample(m, lon(7.5), lat(0)), 3.5, 1e-12);     // half way from column 7 back to 0
  EXPECT_NEAR(sample(m, lon(-0.5), lat(0)), 3.5, 1e-12);    // the same point, from the west
  EXPECT_NEAR(sample(m, lon(2), 0.5 * kPi), 32.0, 1e-12);   // the pole: the top row
  EXPECT_NEAR(sample(m, lon(2), -0.5 * kPi), 2.0, 1e-12);
}

// The disc mean of a uniform map is its value; the far side does not count, and the limb
// counts less than the centre (projected area).
TEST(AlbedoMap, NearSideDiscMean) {
  EXPECT_NEAR(nearSideDiscMean(uniformMap(360, 180, 0.3f)), 0.3, 1e-6);
  AlbedoMap m = uniformMap(360, 180, 0.2f);
  for (int j = 0; j < 180; ++j)
    for (int i = 0; i < 360; ++i)
      if (std::abs(i + 0.5 - 180.0) > 90.0) m.values[j * 360 + i] = 5.0f;  // far side
  EXPECT_NEAR(nearSideDiscMean(m), 0.2, 1e-6);
  // Bright within 30 deg of the centre: the weight cos(lat) cos(lon) dS over the cap is
  // the disc's area within sin(30 deg) of its centre, a quarter of it.
  AlbedoMap c = uniformMap(720, 360, 0.0f);
  for (int j = 0; j < 360; ++j)
    for (int i = 0; i < 720; ++i) {
      const double lon = ((i + 0.5) / 720 - 0.5) * 2 * kPi, lat = ((j + 0.5) / 360 - 0.5) * kPi;
      if (std::cos(lat) * std::cos(lon) > std::cos(kPi / 6)) c.values[j * 720 + i] = 1.0f;
    }
  EXPECT_NEAR(nearSideDiscMean(c), 0.25, 0.003);
}

// A planted black mark (with a ring of JPEG-like ringing) is found and filled from around
// it; a large dark area and the map's own texture are left alone.
TEST(AlbedoMap, DarkSpotsAreFilled) {
  AlbedoMap m = uniformMap(64, 32, 0.5f);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 64; ++i) m.values[j * 64 + i] = 0.5f + 0.05f * ((i + j) % 3);
  for (int j = 4; j < 20; ++j)
    for (int i = 26; i < 56; ++i) m.values[j * 64 + i] = 0.04f;  // a dark sea, 16 x 30
  m.values[24 * 64 + 10] = 0.0f;
  m.values[24 * 64 + 11] = 0.02f;
  const AlbedoMap before = m;
  const std::vector<char> spots = darkSpots(m);
  EXPECT_TRUE(spots[24 * 64 + 10]);
  EXPECT_TRUE(spots[24 * 64 + 11]);
  EXPECT_FALSE(spots[12 * 64 + 40]);  // inside the sea
  int marked = 0;
  for (char s : spots) marked += s;
  EXPECT_LE(marked, 12);  // the mark and its neighbours
  EXPECT_EQ(fillGaps(m, spots), marked);
  EXPECT_GT(m.values[24 * 64 + 10], 0.45f);
  EXPECT_LT(m.values[24 * 64 + 10], 0.65f);
  EXPECT_EQ(m.values[12 * 64 + 40], before.values[12 * 64 + 40]);
  EXPECT_EQ(m.values[2 * 64 + 2], before.values[2 * 64 + 2]);
  // All gap: left as it is.
  AlbedoMap none = uniformMap(4, 4, 0.0f);
  EXPECT_EQ(fillGaps(none, std::vector<char>(16, 1)), 0);
}

TEST(AlbedoMap, Validate) {
  EXPECT_NO_THROW(validate(uniformMap(2, 2, 0.1f), "m"));
  EXPECT_THROW(validate(uniformMap(1, 2, 0.1f), "m"), std::invalid_argument);
  EXPECT_THROW(validate(uniformMap(4, 4, 0.0f), "m"), std::invalid_argument);
  AlbedoMap bad = uniformMap(4, 4, 0.1f);
  bad.values[3] = std::nanf("");
  EXPECT_THROW(validate(bad, "m"), std::invalid_argument);
  bad.values.pop_back();
  EXPECT_THROW(validate(bad, "m"), std::invalid_argument);
}
