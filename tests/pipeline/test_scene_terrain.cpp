// A scene's terrain as `umbra render` builds it (pipeline::addSceneTerrains,
// pipeline::placeSceneTerrains), against the CPU's shadow map and against itself at
// another time.
#include "RenderTestSupport.hpp"
#include "SceneTerrain.h"
#include "TerrainRendering.h"

#include "scene/Scene.hpp"
#include "scene/Time.hpp"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkMapper.h>
#include <vtkRenderer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <unistd.h>
#include <cstdio>
#include <vector>

using namespace umbra;

// The example scene (a synthetic crater field at the lunar south pole, the Sun 0.9 deg
// up) as `umbra render` builds it, at a small size: the terrain is drawn in front of the
// Moon's sphere; where the CPU map (terrain::visibleFraction at the samples around the
// pixel's surface point) says umbra the pixel is black, where it says lit (and the slope
// faces the Sun) it is not; no NaN.
TEST(TerrainScene, LunarSouthPoleShadowsWhereTheCpuMapSays) {
  const scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-south-pole-landing-site.json");
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  const int W = 160, H = 90;
  render::BodyView view(W, H, true);
  render::test::useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(in.sun, in.bodies, render::test::testLutImage());
  view.SetCamera(in.camera);
  const auto terrains = pipeline::addSceneTerrains(view, s, in, {});
  ASSERT_EQ(terrains.size(), 1u);
  render::TerrainRendering& t = *terrains.front();
  std::vector<float> full, alone, grid;
  int w = 0, h = 0;
  view.Render();
  view.ReadHdr(full, w, h);  // throws on a non-finite value
  // The terrain alone (the spheres hidden), as radiance and as (gx, gy, fraction).
  vtkActorCollection* actors = view.GetRenderer()->GetActors();
  actors->InitTraversal();
  while (vtkActor* a = actors->GetNextActor())
    if (a != t.GetActor()) a->VisibilityOff();
  view.Render();
  view.ReadHdr(alone, w, h);
  t.SetOutput(render::TerrainRendering::Output::GridAndFraction);
  view.Render();
  view.ReadHdr(grid, w, h);

  const terrain::HeightField& f = t.GetPatch().field;
  const terrain::SunDisc disc = t.GetSunDisc();
  const terrain::ShadowOptions dp;
  int terrainPixels = 0, hidden = 0, umbra = 0, umbraBlack = 0, lit = 0, litBright = 0;
  for (int k = 0; k < W * H; ++k) {
    const glm::dvec2 g(grid[3 * k], grid[3 * k + 1]);
    if (alone[3 * k] == 0.0f && grid[3 * k] == 0.0f && grid[3 * k + 1] == 0.0f) continue;  // no terrain
    if (!(g.x >= 1.0 && g.y >= 1.0 && g.x <= f.width - 2.0 && g.y <= f.height - 2.0)) continue;
    ++terrainPixels;
    hidden += full[3 * k] != alone[3 * k];
    // The CPU map at the four samples around the surface point.
    double lo = 1.0, hi = 0.0;
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        const double v = terrain::visibleFraction(f, t.GetMipmap(), int(g.x) + di, int(g.y) + dj, disc, dp);
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
    if (hi == 0.0) umbra += 1, umbraBlack += alone[3 * k] == 0.0f;
    if (lo == 1.0 && grid[3 * k + 2] == 1.0f) lit += 1, litBright += alone[3 * k] > 0.0f;
  }
  std::printf("  %d terrain pixels, %d covered by the sphere; umbra %d (black %d), lit %d (bright %d)\n", terrainPixels,
              hidden, umbra, umbraBlack, lit, litBright);
  EXPECT_GT(terrainPixels, W * H / 8);
  EXPECT_LE(hidden, terrainPixels / 100);
  EXPECT_GT(umbra, 100);
  EXPECT_EQ(umbraBlack, umbra);
  EXPECT_GT(lit, 20);
  EXPECT_GE(litBright, lit * 95 / 100);  // (a lit slope facing away from the Sun is black too)
}

// A later frame of an animation (`umbra render --from/--to/--step`): the patch built for
// the first frame and moved to the new time by placeSceneTerrains (its mesh kept) renders
// the frame that a patch built at the new time renders, value for value; 6 hours on, the
// Sun has moved (the Moon turned by 3.3 deg) and the frame differs from the first.
TEST(TerrainScene, PatchMovedToAnotherTimeRendersAsOneBuiltThere) {
  scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-south-pole-landing-site.json");
  const int W = 64, H = 36;
  auto frame = [](render::BodyView& view) {
    std::vector<float> hdr;
    int w = 0, h = 0;
    view.Render();
    view.ReadHdr(hdr, w, h);
    return hdr;
  };
  auto show = [](render::BodyView& view, const pipeline::SceneInputs& in) {
    view.SetBodies(in.sun, in.bodies, render::test::testLutImage());
    view.SetCamera(in.camera);
  };
  render::BodyView moved(W, H, true), built(W, H, true);
  render::test::useSharedDisplay(moved.GetRenderWindow());
  render::test::useSharedDisplay(built.GetRenderWindow());

  const pipeline::SceneInputs first = pipeline::sceneInputs(s);
  show(moved, first);
  const auto terrains = pipeline::addSceneTerrains(moved, s, first, {});
  ASSERT_EQ(terrains.size(), 1u);
  vtkDataObject* mesh = terrains.front()->GetActor()->GetMapper()->GetInputDataObject(0, 0);
  const std::vector<float> firstFrame = frame(moved);

  scene::setTime(s, scene::addSeconds(s.time, 6.0 * 3600.0));
  const pipeline::SceneInputs later = pipeline::sceneInputs(s);
  show(moved, later);
  pipeline::placeSceneTerrains(terrains, moved, s, later);
  EXPECT_EQ(terrains.front()->GetActor()->GetMapper()->GetInputDataObject(0, 0), mesh);
  const std::vector<float> movedFrame = frame(moved);

  show(built, later);
  const auto rebuilt = pipeline::addSceneTerrains(built, s, later, {});
  const std::vector<float> builtFrame = frame(built);

  ASSERT_EQ(movedFrame.size(), builtFrame.size());
  EXPECT_EQ(movedFrame, builtFrame);
  std::size_t changed = 0;
  for (std::size_t k = 0; k < firstFrame.size(); ++k) changed += firstFrame[k] != movedFrame[k];
  std::printf("  %zu of %zu values changed in 6 hours\n", changed, firstFrame.size());
  EXPECT_GT(changed, firstFrame.size() / 20);
}

namespace {
// Of every column of an image's lower half (rows from H/2 + 8, below a Sun at the centre),
// the count of rows where the pixel's radiance (R + G + B) stands out of both its
// neighbours two columns away (above 1.5 times the brighter and by more than 2 % of the
// lower half's median): a seam drawn down the image is such a column from top to bottom;
// texture and relief make a few scattered ones.
int mostOutstandingRowsInAColumn(const std::vector<float>& hdr, int W, int H, int* column) {
  auto at = [&](int x, int y) { return hdr[3 * (y * W + x)] + hdr[3 * (y * W + x) + 1] + hdr[3 * (y * W + x) + 2]; };
  std::vector<float> lower;
  for (int y = H / 2 + 8; y < H; ++y)
    for (int x = 0; x < W; ++x) lower.push_back(at(x, y));
  std::nth_element(lower.begin(), lower.begin() + lower.size() / 2, lower.end());
  const double median = lower[lower.size() / 2];
  int most = 0;
  for (int x = 2; x + 2 < W; ++x) {
    int count = 0;
    for (int y = H / 2 + 8; y < H; ++y) {
      const double side = std::max(at(x - 2, y), at(x + 2, y));
      count += at(x, y) > 1.5 * side && at(x, y) - side > 0.02 * median;
    }
    if (count > most) most = count, *column = x;
  }
  return most;
}
} // namespace

// From 4 km off the lunar south pole the meridian opposite the camera's runs down the
// middle of the view: the Moon's maps must not show it (a quad of pixels astride the
// longitude's jump would take the map's coarsest level, a bright line 2 pixels wide from
// the horizon down). Neither must the terrain patch's edges. Checked on the example scene
// with and without its terrain, at the scene's 960 x 540 (where the line stands out in
// over 200 of the 262 rows without the terrain, some 60 with it; at some sizes the pixel quads do not
// straddle it).
TEST(TerrainScene, NoLineDownTheViewFromNearThePole) {
  const scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-south-pole-landing-site.json");
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  const auto moon = std::find_if(in.bodies.begin(), in.bodies.end(), [](const render::SphereBody& b) { return b.name == "Moon"; });
  ASSERT_NE(moon, in.bodies.end());
  ASSERT_TRUE(moon->albedoMap) << "the Moon's albedo map (the set-up scripts install it) is needed here";
  const int W = 960, H = 540;
  for (const bool withTerrain : {false, true}) {
    render::BodyView view(W, H, true);
    render::test::useSharedDisplay(view.GetRenderWindow());
    view.SetBodies(in.sun, in.bodies, render::test::testLutImage());
    view.SetCamera(in.camera);
    std::vector<std::unique_ptr<render::TerrainRendering>> terrains;
    if (withTerrain) terrains = pipeline::addSceneTerrains(view, s, in, {});
    std::vector<float> hdr;
    int w = 0, h = 0;
    view.Render();
    view.ReadHdr(hdr, w, h);
    int column = -1;
    const int rows = mostOutstandingRowsInAColumn(hdr, W, H, &column);
    std::printf("  %s: at most %d of %d rows stand out in one column (column %d)\n",
                withTerrain ? "with the terrain" : "the sphere alone", rows, H - H / 2 - 8, column);
    EXPECT_LE(rows, 20) << (withTerrain ? "with the terrain" : "the sphere alone") << ", column " << column;
  }
}

// The shadow table of a scene's terrain goes through the table cache: made and stored for
// the first view, read back (the same values) for a second; a Sun within the table's step
// keeps the held table, one an hour later (0.55 deg on at the pole) gets another.
TEST(TerrainScene, ShadowTablesAreCachedAndFollowTheSun) {
  scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-south-pole-landing-site.json");
  pipeline::SceneInputs in = pipeline::sceneInputs(s);
  render::BodyView view(32, 18, true);
  render::test::useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(in.sun, in.bodies, render::test::testLutImage());
  view.SetCamera(in.camera);
  pipeline::TerrainShadowSettings shadows;
  const std::filesystem::path cacheDir =
      std::filesystem::temp_directory_path() / ("umbra-terrain-shadow-cache-" + std::to_string(::getpid()));
  std::filesystem::remove_all(cacheDir);
  shadows.cacheDirectory = cacheDir.string();
  const auto terrains = pipeline::addSceneTerrains(view, s, in, {}, shadows);
  render::TerrainRendering& t = *terrains.front();
  ASSERT_NE(t.GetShadowTable(), nullptr);
  const std::vector<float> made = t.GetShadowTable()->offsets;

  render::TerrainRendering again;
  again.SetTerrain(t.GetPatch());
  again.SetSun(in.sun);
  EXPECT_TRUE(pipeline::updateShadowTable(again, shadows));  // read from the cache
  EXPECT_EQ(again.GetShadowTable()->offsets, made);
  const terrain::ShadowTable* held = again.GetShadowTable();
  EXPECT_FALSE(pipeline::updateShadowTable(again, shadows));
  EXPECT_EQ(again.GetShadowTable(), held);  // the same Sun: the table kept

  scene::setTime(s, scene::addSeconds(s.time, 3600.0));
  in = pipeline::sceneInputs(s);
  view.SetCamera(in.camera);
  pipeline::placeSceneTerrains(terrains, view, s, in, shadows);
  ASSERT_NE(t.GetShadowTable(), nullptr);
  EXPECT_NE(t.GetShadowTable()->offsets, made);
  const double movedDeg = std::acos(std::min(1.0, glm::dot(glm::normalize(t.GetShadowTable()->sun.direction),
                                                           glm::normalize(held->sun.direction)))) * 180.0 / 3.14159265358979;
  std::printf("  the table's Sun moved %.3f deg in an hour\n", movedDeg);
  EXPECT_GT(movedDeg, 0.3);
  shadows.tables = false;
  pipeline::placeSceneTerrains(terrains, view, s, in, shadows);
  EXPECT_EQ(t.GetShadowTable(), nullptr);  // the search per pixel
  std::filesystem::remove_all(cacheDir);
}
