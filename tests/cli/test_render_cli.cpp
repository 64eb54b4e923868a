// `umbra render` on the example scene (needs an X display: runs under xvfb-run).
// The frame must be finite and not black, and the Moon darker on its umbral side.
#include "CliRunner.hpp"

#include "scene/Scene.hpp"
#include "umbra/tables/Exr.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace umbra;
using namespace umbra::test;

namespace {
const std::string kScene = UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json";
}

TEST(RenderCli, ExampleSceneShowsTheMoonDarkerOnItsUmbralSide) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"render", kScene, "--output", dir / "moon.exr"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const tables::Table img = tables::readExr(dir / "moon.exr", {"R", "G", "B"});
  const scene::Scene s = scene::loadScene(kScene);
  ASSERT_EQ(img.width, s.width);
  ASSERT_EQ(img.height, s.height);
  for (float v : img.data) ASSERT_TRUE(std::isfinite(v));

  // Where the shadow axis passes at the Moon's distance, projected into the image: the
  // umbral side of the Moon is the one facing it.
  const scene::Body& earth = *s.find("Earth");
  const scene::Body& moon = *s.find("Moon");
  const glm::dvec3 antiSun = glm::normalize(earth.positionM - s.sun().positionM);
  const glm::dvec3 axisPoint = earth.positionM + antiSun * glm::length(moon.positionM - earth.positionM);
  const glm::dvec3 view = glm::normalize(s.camera.targetM - s.camera.positionM);
  const glm::dvec3 up = glm::normalize(s.camera.up - view * glm::dot(s.camera.up, view));
  const glm::dvec3 right = glm::cross(view, up);
  const glm::dvec2 towardsAxis(glm::dot(axisPoint - moon.positionM, right), glm::dot(axisPoint - moon.positionM, up));

  // The Moon's disc in pixels (camera aimed at its centre).
  const double distance = glm::length(moon.positionM - s.camera.positionM);
  const double radiusPx = std::tan(std::asin(moon.radiusM / distance)) /
                          std::tan(0.5 * s.camera.fovDeg * M_PI / 180.0) * 0.5 * s.height;
  double sums[2] = {0, 0};
  int counts[2] = {0, 0};
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const glm::dvec2 p(x + 0.5 - 0.5 * img.width, 0.5 * img.height - (y + 0.5));  // row 0 = top
      if (glm::length(p) > 0.9 * radiusPx) continue;
      const int side = glm::dot(p, towardsAxis) > 0.0 ? 0 : 1;  // 0: umbral side
      sums[side] += img.at(x, y, 1);
      ++counts[side];
    }
  }
  ASSERT_GT(counts[0], 1000);
  ASSERT_GT(counts[1], 1000);
  const double umbral = sums[0] / counts[0], other = sums[1] / counts[1];
  EXPECT_GT(other, 0.1);            // lit (W m^-2 sr^-1); not an all-black frame
  EXPECT_LT(umbral, 0.5 * other);   // the umbral side is much darker
}

TEST(RenderCli, PngIsWrittenAndNotBlank) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"render", kScene, "--size", "320x240", "--output", dir / "moon.png"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("wrote"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(dir.path / "moon.png"), 1000u);
  EXPECT_EQ(dir.fileCount(), 2);  // the PNG and the cache folder, no temporary
}

TEST(RenderCli, ProfilePlotAsPng) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"profile", "shadow", "--occluder", "Earth", "--no-atmosphere", "--distance",
                                      "384400km", "--samples", "200", "--csv", dir / "p.csv", "--plot", dir / "p.png"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(dir.path / "p.png"), 2000u);
}
