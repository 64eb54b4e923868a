// What the cloud layers cost in the render pass: three examples each with their clouds
// beside the same frames without them (the atmosphere stage draws the clouds: GL_TIMESTAMP
// around it), at the same size: partly-cloudy-afternoon (two layers, from the ground),
// earth-clouds-from-space (one layer over the disc), lunar-eclipse-2015-09-28-clouds (one
// layer lit by the Moon, the Moon's program). Tables through the cache (the first run
// precomputes them). Needs an X display (xvfb-run -a) or --egl; on llvmpipe the fragment
// work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-clouds [--frames 20] [--width 1920 --height 1080]
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "scene/Scene.hpp"
#include "vtkAtmosphereTablesSource.h"

#include <CLI/CLI.hpp>

#include <vtkImageData.h>
#include <vtkNew.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace umbra;

int main(int argc, char** argv) {
  CLI::App app{"What the cloud layers cost"};
  bench::FrameBenchOptions o;
  bench::addFrameBenchOptions(app, o);
  CLI11_PARSE(app, argc, argv);
  const int frames = o.frames, width = o.width, height = o.height;
  if (!bench::startWindows(o.egl)) return 1;

  const auto lut = filters::toImageData(eclipse::buildAirlessShadowLut({64, 64}));
  const std::vector<std::string> names = {"partly-cloudy-afternoon", "earth-clouds-from-space",
                                          "lunar-eclipse-2015-09-28-clouds"};
  std::vector<std::unique_ptr<render::BodyView>> views;
  std::vector<int> layers;
  for (const std::string& name : names) {
    const scene::Scene s = scene::loadScene(bench::exampleScene(name + ".json"));
    const render::SceneInputs cloudy = render::sceneInputs(s);
    render::SceneInputs clear = cloudy;
    clear.atmosphere->clouds.clear();
    layers.push_back(static_cast<int>(cloudy.atmosphere->clouds.size()));
    views.push_back(bench::sceneView(s, cloudy, width, height, lut));
    views.push_back(bench::sceneView(s, clear, width, height, lut));
  }
  bench::printRenderer(*views.front());
  const bench::FrameTimes t = bench::medianFrameTimes(views, frames);
  std::printf("| %dx%d, %d frames, median [ms] | frame (GL) | atmosphere stage | clouds (difference) | clouds / "
              "atmosphere stage |\n",
              width, height, frames);
  std::printf("|---|---:|---:|---:|---:|\n");
  for (std::size_t k = 0; k < names.size(); ++k) {
    const double clouds = t.atmosphereMs[2 * k] - t.atmosphereMs[2 * k + 1];
    std::printf("| %s, %d layer%s | %.2f | %.2f | %.2f | %.2f |\n", names[k].c_str(), layers[k], layers[k] == 1 ? "" : "s",
                t.glMs[2 * k], t.atmosphereMs[2 * k], clouds, clouds / t.atmosphereMs[2 * k + 1]);
    std::printf("| %s, no clouds | %.2f | %.2f | | |\n", names[k].c_str(), t.glMs[2 * k + 1], t.atmosphereMs[2 * k + 1]);
  }
  return 0;
}
