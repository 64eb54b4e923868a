// The eclipse-through-an-atmosphere examples through `umbra render` (small tables, small
// images, linear EXR): the Moon copper in the umbra (2015-09-28, Calbuco), Earth's thin
// red ring from the lunar north pole (limb-luminance LuT), Phobos lit in Mars' umbra.
#include "RenderCliSupport.hpp"

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace umbra;
using namespace umbra::test;

namespace {
// One table cache for the tests of this process: the atmosphere's tables are made once.
const TempDir& cacheDir() {
  static const TempDir dir;
  return dir;
}

tables::Table render(const TempDir& dir, const std::string& scene, const std::string& size,
                     const std::vector<std::string>& extra = {}) {
  return renderExr(dir, UMBRA_SOURCE_DIR "/examples/scenes/" + scene, size, extra, &cacheDir());
}
} // namespace

// Mid-eclipse (02:30 UTC, the Moon near the umbra's centre): copper, R > G > B, not black.
TEST(EclipseExamplesCli, MoonInTheUmbraIsCopper) {
  TempDir dir;
  const tables::Table img = render(dir, "lunar-eclipse-2015-09-28-moon.json", "64x48");
  const glm::dvec3 c = pixel(img, img.width / 2, img.height / 2);
  std::printf("  Moon's centre at 02:30: R G B = %.3g %.3g %.3g W m^-2 sr^-1\n", c.r, c.g, c.b);
  EXPECT_GT(c.r, c.g);
  EXPECT_GT(c.g, c.b);
  EXPECT_GT(c.r, 1e-3);
  // At 01:00 (penumbra) the Moon is far brighter and nearly white.
  const tables::Table early = render(dir, "lunar-eclipse-2015-09-28-moon.json", "64x48", {"--time", "2015-09-28T01:00:00Z"});
  const glm::dvec3 e = pixel(early, early.width / 2, early.height / 2);
  EXPECT_GT(e.g, 100.0 * c.g);
  EXPECT_LT(e.r / e.b, c.r / c.b);
}

// Earth from the lunar north pole at 02:30: a thin ring around a dark disc, red-dominant
// (the ring, under a pixel wide, from the limb-luminance LuT; the lunar ground in front,
// in the umbra too, is far dimmer than 1 W m^-2 sr^-1).
TEST(EclipseExamplesCli, EarthFromTheLunarPoleHasAThinRedRing) {
  TempDir dir;
  const tables::Table img = render(dir, "earth-from-lunar-north-pole-2015-09-28.json", "160x120");
  glm::dvec3 sum(0.0);
  int lit = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const glm::dvec3 p = pixel(img, x, y);
      if (p.r <= 1.0) continue;
      ++lit;
      sum += p;
    }
  std::printf("  %d lit pixels of %d, summed R G B = %.3g %.3g %.3g\n", lit, img.width * img.height, sum.r, sum.g, sum.b);
  EXPECT_GT(lit, 50);                              // a ring ...
  EXPECT_LT(lit, img.width * img.height / 10);     // ... a thin one
  EXPECT_EQ(pixel(img, img.width / 2, img.height / 2), glm::dvec3(0.0));  // Earth's night side
  EXPECT_GT(sum.r, 2.0 * sum.g);
  EXPECT_GT(sum.g, sum.b);
}

// Phobos in Mars' umbra lit through Mars' atmosphere: not black (the airless umbra is).
TEST(EclipseExamplesCli, PhobosInTheUmbraIsLitThroughMarsAtmosphere) {
  TempDir dir;
  const tables::Table img = render(dir, "phobos-in-mars-umbra-atmosphere.json", "48x36");
  const glm::dvec3 c = pixel(img, img.width / 2, img.height / 2);
  std::printf("  Phobos' centre: R G B = %.3g %.3g %.3g W m^-2 sr^-1\n", c.r, c.g, c.b);
  EXPECT_GT(c.r + c.g + c.b, 1e-3);
  EXPECT_LT(c.g, 0.05 * 0.068 / 3.14159 * 1361.0 / (1.524 * 1.524));  // < 5 % of full sunlight
}
