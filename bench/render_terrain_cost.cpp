// Frame time of the terrain patch with soft horizon shadows (terrain paper, section 4):
// the example scene examples/scenes/lunar-south-pole-landing-site.json (a 512 x 512
// synthetic crater field at the lunar south pole, Sun 0.9 deg up, camera 2.5 km up
// looking across it towards the Sun), rendered as `umbra render` does: with the shadow
// table (the default), with the whole DP search per pixel (`--terrain-shadows search`),
// and without the terrain (the Moon's sphere only), interleaved; median frame times. The
// table is made (or read from the cache) before the timing, once: the time to make it is
// printed apart (umbra-bench-terrain-table times it too).
// Needs an X display (xvfb-run -a) or --egl (EGL, no X); on llvmpipe the fragment work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-terrain [--frames 5] [--width 1920 --height 1080]
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
#include "SceneTerrain.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "scene/Scene.hpp"

#include <CLI/CLI.hpp>

#include <vtkImageData.h>
#include <vtkRenderWindow.h>

#include <chrono>
#include <cstdio>
#include <vector>

using namespace umbra;

int main(int argc, char** argv) {
  CLI::App app{"Frame time of the terrain patch with soft shadows"};
  bench::SceneBenchOptions o;
  o.frames = 5;
  o.scenePath = bench::exampleScene("lunar-south-pole-landing-site.json");
  bench::addSceneBenchOptions(app, o);
  pipeline::TerrainShadowSettings table;
  app.add_option("--near-texels", table.nearTexels, "The stretch each pixel searches itself [texels]")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (!bench::startWindows(o.egl)) return 1;
  const int frames = o.frames, width = o.width, height = o.height;
  const std::string& scenePath = o.scenePath;

  const scene::Scene s = scene::loadScene(scenePath);
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  const auto lut = filters::toImageData(eclipse::buildAirlessShadowLut({64, 64}));
  render::BodyView withTable(width, height, true), withSearch(width, height, true), without(width, height, true);
  std::vector<std::unique_ptr<render::TerrainRendering>> tableTerrains, searchTerrains;
  pipeline::TerrainShadowSettings search;
  search.tables = false;
  double tableSeconds = 0.0;
  for (render::BodyView* v : {&withTable, &withSearch, &without}) {
    v->SetBodies(in.sun, in.bodies, lut);
    v->SetCamera(in.camera);
    v->SetExposureEV(s.exposureEv);
    const auto t0 = std::chrono::steady_clock::now();
    if (v == &withTable) tableTerrains = pipeline::addSceneTerrains(*v, s, in, {}, table);
    tableSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (v == &withSearch) searchTerrains = pipeline::addSceneTerrains(*v, s, in, {}, search);
    v->Render();  // warm up: shader compilation, textures
  }
  bench::printRenderer(withTable);
  std::printf("the terrain patch with its shadow table (made or read from the cache): %.2f s\n\n", tableSeconds);
  const std::vector<double> median = bench::medianFrameWallMs({&withTable, &withSearch, &without}, frames);
  std::printf("| frame | with the shadow table [ms] | searched per pixel [ms] | sphere only [ms] | search / table |\n"
              "|---|---:|---:|---:|---:|\n");
  std::printf("| %dx%d, %d frames, median | %.0f | %.0f | %.0f | %.1fx |\n", width, height, frames, median[0], median[1],
              median[2], median[1] / median[0]);
  return 0;
}
