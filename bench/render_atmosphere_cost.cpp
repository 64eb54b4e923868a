// Frame time of the atmosphere in the render pass (eclipse paper Tables 1-2:
// refraction +20 %): the earth-sunset example rendered without the atmosphere, with it,
// with refraction, and with the atmosphere and glare (strength 1), interleaved frame by frame, timed with GL timer queries
// (GL_TIME_ELAPSED around the frame) and with the wall clock (after glFinish); prints the
// medians. Tables from vtkAtmosphereTablesSource through the cache (the first run at
// default sizes precomputes them). Needs an X display (xvfb-run -a) or --egl; on llvmpipe the
// fragment work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-atmosphere [--frames 20] [--width 1920 --height 1080]
//       [--tables default|small]
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
#include "vtkUmbraRenderPass.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "scene/Scene.hpp"
#include "vtkAtmosphereTablesSource.h"

#include <CLI/CLI.hpp>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>

#include <cstdio>
#include <memory>
#include <vector>

using namespace umbra;

int main(int argc, char** argv) {
  CLI::App app{"Frame time without the atmosphere, with it and with refraction"};
  int frames = 20, width = 1920, height = 1080;
  std::string tables = "default";
  std::string scenePath = bench::exampleScene("earth-sunset.json");
  bool egl = false;
  app.add_option("--frames", frames, "Frames per configuration")->capture_default_str();
  app.add_option("--width", width)->capture_default_str();
  app.add_option("--height", height)->capture_default_str();
  app.add_option("--tables", tables, "Atmosphere table sizes: default or small")->capture_default_str();
  app.add_option("--scene", scenePath, "A scene with an atmosphere")->capture_default_str();
  bench::addEglOption(app, egl);
  CLI11_PARSE(app, argc, argv);
  if (!bench::startWindows(egl)) return 1;

  const scene::Scene s = scene::loadScene(scenePath);
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  if (!in.atmosphere) {
    std::fprintf(stderr, "%s: no body asks for an atmosphere\n", scenePath.c_str());
    return 1;
  }
  const auto lut = filters::toImageData(eclipse::buildAirlessShadowLut({64, 64}));
  constexpr int kConfigs = 4;
  const char* names[kConfigs] = {"no atmosphere", "atmosphere", "atmosphere + refraction", "atmosphere + glare 1"};
  std::vector<std::unique_ptr<render::BodyView>> views;
  for (int k = 0; k < kConfigs; ++k) {
    views.push_back(std::make_unique<render::BodyView>(width, height, true));
    render::BodyView& v = *views.back();
    v.SetBodies(in.sun, in.bodies, lut);
    if (k > 0) {
      vtkNew<vtkAtmosphereTablesSource> source;
      pipeline::applySceneAtmosphere(v, in, source, k == 2,
                                   tables == "small" ? pipeline::AtmosphereTableSizes::Small
                                                     : pipeline::AtmosphereTableSizes::Default);
    }
    v.SetCamera(in.camera);
    v.SetExposureEV(s.exposureEv);
    if (k == 3) v.GetRenderPass()->SetGlareStrength(1.0);
    v.Render();  // warm up: shaders, textures
  }
  bench::printRenderer(*views.front());
  const bench::FrameTimes times = bench::medianFrameTimes(views, frames);
  std::printf("| %dx%d, %d frames, %s tables, median | GL timer [ms] | wall [ms] | GL time vs no atmosphere | "
              "atmosphere stage [ms] |\n",
              width, height, frames, tables.c_str());
  std::printf("|---|---:|---:|---:|---:|\n");
  for (int k = 0; k < kConfigs; ++k)
    std::printf("| %s | %.3f | %.3f | %+.1f %% | %.3f |\n", names[k], times.glMs[k], times.wallMs[k],
                100.0 * (times.glMs[k] / times.glMs[0] - 1.0), times.atmosphereMs[k]);
  const double atm = times.glMs[1];
  std::printf("\nrefraction vs atmosphere without it: %+.1f %% (frame), %+.1f %% (atmosphere stage)\n",
              100.0 * (times.glMs[2] / atm - 1.0), 100.0 * (times.atmosphereMs[2] / times.atmosphereMs[1] - 1.0));
  std::printf("glare vs atmosphere without it: %+.1f %%\n", 100.0 * (times.glMs[3] / atm - 1.0));
  return 0;
}
