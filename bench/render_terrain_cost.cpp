// Frame time of the terrain patch with soft horizon shadows (terrain paper, section 4):
// the example scene examples/scenes/lunar-south-pole-landing-site.json (a 512 x 512
// synthetic crater field at the lunar south pole, Sun 0.9 deg up, camera 2.5 km up
// looking across it towards the Sun), rendered as `umbra render` does, once with the
// terrain and once without it (the Moon's sphere only), interleaved; median frame times.
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

#include <cstdio>
#include <vector>

using namespace umbra;

int main(int argc, char** argv) {
  CLI::App app{"Frame time of the terrain patch with soft shadows"};
  bench::SceneBenchOptions o;
  o.frames = 5;
  o.scenePath = bench::exampleScene("lunar-south-pole-landing-site.json");
  bench::addSceneBenchOptions(app, o);
  CLI11_PARSE(app, argc, argv);
  if (!bench::startWindows(o.egl)) return 1;
  const int frames = o.frames, width = o.width, height = o.height;
  const std::string& scenePath = o.scenePath;

  const scene::Scene s = scene::loadScene(scenePath);
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  const auto lut = filters::toImageData(eclipse::buildAirlessShadowLut({64, 64}));
  render::BodyView withTerrain(width, height, true), without(width, height, true);
  std::vector<std::unique_ptr<render::TerrainRendering>> terrains;
  for (render::BodyView* v : {&withTerrain, &without}) {
    v->SetBodies(in.sun, in.bodies, lut);
    v->SetCamera(in.camera);
    v->SetExposureEV(s.exposureEv);
    if (v == &withTerrain) terrains = pipeline::addSceneTerrains(*v, s, in, {});
    v->Render();  // warm up: shader compilation, textures
  }
  bench::printRenderer(withTerrain);
  const std::vector<double> median = bench::medianFrameWallMs({&withTerrain, &without}, frames);
  std::printf("| frame | with the terrain [ms] | sphere only [ms] |\n|---|---:|---:|\n");
  std::printf("| %dx%d, %d frames, median | %.0f | %.0f |\n", width, height, frames, median[0], median[1]);
  return 0;
}
