// What the cloud layers cost in the render pass: three examples each with their clouds
// beside the same frames without them (the atmosphere stage draws the clouds: GL_TIMESTAMP
// around it), at the same size: partly-cloudy-afternoon (two layers, from the ground),
// earth-clouds-from-space (one layer over the disc), lunar-eclipse-2015-09-28-clouds (one
// layer lit by the Moon, the Moon's program). Then clouds and the Milky Way together:
// milky-way-from-paranal with partly-cloudy-afternoon's two layers and the Milky Way
// (drawn in the stars stage) beside it with neither and with the Milky Way only, as
// differences of the frames (llvmpipe runs a stage's draws when a later one flushes them,
// so the stars stage's own timestamps show nothing there; on a GPU they do). Tables through the cache (the first
// run precomputes them). Needs an X display (xvfb-run -a) or --egl; on llvmpipe the fragment
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
    const pipeline::SceneInputs cloudy = pipeline::sceneInputs(s);
    pipeline::SceneInputs clear = cloudy;
    clear.atmosphere->clouds.clear();
    layers.push_back(static_cast<int>(cloudy.atmosphere->clouds.size()));
    views.push_back(bench::sceneView(s, cloudy, width, height, lut));
    views.push_back(bench::sceneView(s, clear, width, height, lut));
  }
  // Clouds and the Milky Way together, at night.
  const scene::Scene night = scene::loadScene(bench::exampleScene("milky-way-from-paranal.json"));
  pipeline::SceneInputs both = pipeline::sceneInputs(night);
  both.atmosphere->clouds = pipeline::sceneInputs(scene::loadScene(bench::exampleScene("partly-cloudy-afternoon.json")))
                                .atmosphere->clouds;
  pipeline::SceneInputs milkyWayOnly = pipeline::sceneInputs(night);
  milkyWayOnly.atmosphere->clouds.clear();
  pipeline::SceneInputs neither = milkyWayOnly;
  neither.milkyWay = nullptr;
  neither.milkyWayRadianceScale = 0.0;
  views.push_back(bench::sceneView(night, both, width, height, lut));
  views.push_back(bench::sceneView(night, neither, width, height, lut));
  views.push_back(bench::sceneView(night, milkyWayOnly, width, height, lut));
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
  const std::size_t b = 2 * names.size(), n = b + 1, m = b + 2;
  std::printf("\n| milky-way-from-paranal, median [ms] | frame (GL) | atmosphere stage | added (difference of the frames) "
              "| added / atmosphere stage |\n");
  std::printf("|---|---:|---:|---:|---:|\n");
  std::printf("| 2 cloud layers and the Milky Way%s | %.2f | %.2f | %.2f | %.2f |\n",
              both.milkyWay ? "" : " (not installed: clouds only)", t.glMs[b], t.atmosphereMs[b], t.glMs[b] - t.glMs[n],
              (t.glMs[b] - t.glMs[n]) / t.atmosphereMs[n]);
  std::printf("| the Milky Way only | %.2f | %.2f | %.2f | %.2f |\n", t.glMs[m], t.atmosphereMs[m], t.glMs[m] - t.glMs[n],
              (t.glMs[m] - t.glMs[n]) / t.atmosphereMs[n]);
  std::printf("| neither | %.2f | %.2f | | |\n", t.glMs[n], t.atmosphereMs[n]);
  return 0;
}
