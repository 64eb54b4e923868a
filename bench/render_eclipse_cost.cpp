// Frame time of the eclipse shadow in a receiver's shader (DESIGN.md: "eclipse shadow in
// the Moon's shader", paper Table 1: +8 %). Renders the 2015-09-28 scene's Moon filling a
// Full-HD frame, once with Earth present as an occluder (one LuT lookup per fragment)
// and once without any occluder, interleaved, and prints the median frame times.
// Needs an X display (xvfb-run -a) or --egl (EGL, no X); on llvmpipe the fragment work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-eclipse [--frames 40] [--width 1920 --height 1080]
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
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
  CLI::App app{"Frame time with and without the eclipse shadow lookup"};
  bench::SceneBenchOptions o;
  o.frames = 40;
  o.scenePath = bench::exampleScene("lunar-eclipse-2015-09-28.json");
  bench::addSceneBenchOptions(app, o);
  CLI11_PARSE(app, argc, argv);
  if (!bench::startWindows(o.egl)) return 1;
  const int frames = o.frames, width = o.width, height = o.height;
  const std::string& scenePath = o.scenePath;

  const scene::Scene s = scene::loadScene(scenePath);
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  const auto lut = filters::toImageData(eclipse::buildAirlessShadowLut({256, 256}));
  std::vector<render::SphereBody> moonOnly;
  for (const auto& b : in.bodies)
    if (b.name == s.camera.targetBody) moonOnly.push_back(b);

  render::BodyView withShadow(width, height, true), without(width, height, true);
  withShadow.SetBodies(in.sun, in.bodies, lut);
  without.SetBodies(in.sun, moonOnly, lut);
  for (render::BodyView* v : {&withShadow, &without}) {
    v->SetCamera(in.camera);
    v->SetExposureEV(s.exposureEv);
    v->Render();  // warm up: shader compilation
  }
  bench::printRenderer(withShadow);
  const std::vector<double> median = bench::medianFrameWallMs({&withShadow, &without}, frames);
  std::printf("| frame | with the eclipse shadow [ms] | without [ms] | cost |\n|---|---:|---:|---:|\n");
  std::printf("| %dx%d, %d frames, median | %.2f | %.2f | %+.1f %% |\n", width, height, frames, median[0], median[1],
              100.0 * (median[0] / median[1] - 1.0));
  return 0;
}
