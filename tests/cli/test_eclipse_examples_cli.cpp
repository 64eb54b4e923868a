// The eclipse-through-an-atmosphere examples through `umbra render` (small tables, small
// images, linear EXR): the Moon copper in the umbra (2015-09-28, Calbuco), Earth's thin
// red ring from the lunar north pole (limb-luminance LuT), Phobos lit in Mars' umbra.
#include "RenderCliSupport.hpp"

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
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
// The shadow LuTs of `kind` in the cache directory `cache`, read.
std::vector<tables::Table> cachedLuts(const std::string& cache, const std::string& kind) {
  std::vector<tables::Table> out;
  for (const auto& e : std::filesystem::directory_iterator(cache))
    if (e.path().filename().string().rfind(kind + "-", 0) == 0) out.push_back(tables::readExr(e.path().string(), {"R", "G", "B"}));
  return out;
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
  EXPECT_GT(c.r + c.g + c.b, 1e-4);  // ~2e-5 of full sunlight, 1500 km off the axis
  EXPECT_LT(c.g, 0.05 * 0.068 / 3.14159 * 1361.0 / (1.524 * 1.524));  // < 5 % of full sunlight
  // The atmospheric shadow LuT was made over Phobos' ranges only (u ~ 0.0083, 2 columns).
  int ranged = 0;
  for (const tables::Table& t : cachedLuts(cacheDir() / "cache", "eclipse-shadow-atmosphere"))
    if (t.parameters.count("uMin") && std::stod(t.parameters.at("uMin")) < 0.01) {
      ++ranged;
      EXPECT_EQ(t.width, 2);
      EXPECT_GT(std::stod(t.parameters.at("vLowFraction")), 0.0);
    }
  EXPECT_EQ(ranged, 1);
}

// Phobos across the umbra's edge (airless): `umbra render` makes the LuT over Phobos' u and
// v ranges by itself (2 x 256 texels, v from the umbra's edge), not the whole 256^2.
TEST(EclipseExamplesCli, PhobosInThePenumbraGetsARangedLut) {
  TempDir dir;
  renderExr(dir, UMBRA_SOURCE_DIR "/examples/scenes/phobos-in-mars-shadow.json", "64x48");  // its own cache
  const std::vector<tables::Table> luts = cachedLuts(dir / "cache", "eclipse-shadow-airless");
  int ranged = 0;
  for (const tables::Table& t : luts) {
    if (!t.parameters.count("uMin")) continue;
    ++ranged;
    EXPECT_EQ(t.width, 2);
    EXPECT_EQ(t.height, 256);
    EXPECT_NEAR(std::stod(t.parameters.at("uMin")), 0.00872, 0.00002);  // 9376 km - 11 km behind Mars
    EXPECT_GT(std::stod(t.parameters.at("vMin")), 0.98);
  }
  EXPECT_EQ(ranged, 1);
}
