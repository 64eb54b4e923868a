// Frame time of the eclipse through an atmosphere in the render pass (eclipse paper
// 6.2): two scenes of the 2015-09-28 eclipse at 1920x1080, every
// configuration interleaved frame by frame in one run, timed with GL timer queries
// (GL_TIME_ELAPSED around the frame) and the wall clock (after glFinish); prints medians.
//   The Moon from Earth (no sky drawn): shadow off (no occluder), airless shadow LuT,
//     atmospheric shadow LuT (RGB, the Moon's columns only).
//   Earth from the lunar north pole: atmosphere ray marched without refraction, with
//     refraction, and with the ring from the limb-luminance LuT (5.4).
// Tables from the cache (small sizes by default: the frame cost depends on the lookups,
// not the table sizes). Needs an X display (xvfb-run -a), or --egl (EGL, no X: a GPU
// machine, scripts/device-checks.sh); on llvmpipe the fragment work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-eclipse-atmosphere [--frames 10]
//       [--width 1920 --height 1080] [--tables small|default] [--part moon|earth|all] [--egl]
#include "AtmosphereShadow.h"
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "scene/Scene.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"

#include <CLI/CLI.hpp>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace umbra;

int main(int argc, char** argv) {
  CLI::App app{"Frame time of the eclipse through an atmosphere: shadow on/off, refraction, limb-luminance LuT"};
  int frames = 10, width = 1920, height = 1080;
  std::string tables = "small", part = "all";
  bool egl = false;
  app.add_option("--frames", frames, "Frames per configuration")->capture_default_str();
  app.add_option("--width", width)->capture_default_str();
  app.add_option("--height", height)->capture_default_str();
  app.add_option("--tables", tables, "Table sizes: small or default")->check(CLI::IsMember({"small", "default"}))
      ->capture_default_str();
  app.add_option("--part", part, "The Moon's configurations (shadow), Earth's (ring) or all")
      ->check(CLI::IsMember({"moon", "earth", "all"}))
      ->capture_default_str();
  bench::addEglOption(app, egl);
  CLI11_PARSE(app, argc, argv);
  if (!bench::startWindows(egl)) return 1;
  const bool small = tables == "small";

  const scene::Scene moonScene = scene::loadScene(bench::exampleScene("lunar-eclipse-2015-09-28-moon.json"));
  const scene::Scene earthScene =
      scene::loadScene(bench::exampleScene("earth-from-lunar-north-pole-2015-09-28.json"));
  const pipeline::SceneInputs moon = pipeline::sceneInputs(moonScene);
  const pipeline::SceneInputs earth = pipeline::sceneInputs(earthScene);
  const auto airless = filters::toImageData(eclipse::buildAirlessShadowLut({256, 256}));

  struct Config {
    const char* name;
    const pipeline::SceneInputs* in;
    double exposureEv;
    std::function<void(render::BodyView&)> setUp;
  };
  auto atmosphereShadow = [&](render::BodyView& v) {
    vtkNew<vtkEclipseShadowLutSource> s;
    if (small) pipeline::useSmallEclipseShadowTables(s);
    pipeline::applySceneAtmosphereShadow(v.GetShading(), moon, s);
  };
  auto sky = [&](render::BodyView& v, bool refraction, double thresholdPx) {
    vtkNew<vtkAtmosphereTablesSource> t;
    pipeline::applySceneAtmosphere(v, earth, t, refraction,
                                 small ? pipeline::AtmosphereTableSizes::Small : pipeline::AtmosphereTableSizes::Default);
    vtkNew<vtkLimbLuminanceSource> limb;
    if (small) pipeline::useSmallLimbLuminanceTables(limb);
    pipeline::applySceneLimbLuminance(v.GetAtmosphere(), earth, limb);
    v.GetAtmosphere().SetLimbRingThresholdPixels(thresholdPx);
  };
  const std::vector<Config> configs = {
      {"Moon: shadow off", &moon, moonScene.exposureEv, [](render::BodyView& v) { v.GetShading().SetOccluders({}); }},
      {"Moon: airless shadow LuT", &moon, moonScene.exposureEv, [](render::BodyView&) {}},
      {"Moon: atmospheric shadow LuT", &moon, moonScene.exposureEv, atmosphereShadow},
      {"Earth ring: ray marched, no refraction", &earth, earthScene.exposureEv,
       [&](render::BodyView& v) { sky(v, false, 0.0); }},
      {"Earth ring: ray marched, refraction", &earth, earthScene.exposureEv,
       [&](render::BodyView& v) { sky(v, true, 0.0); }},
      // At 1920x1080 the ring is 6.7 px wide: above the default 5 px threshold, so the LuT
      // is forced here (threshold 1000 px) to time it.
      {"Earth ring: limb-luminance LuT", &earth, earthScene.exposureEv,
       [&](render::BodyView& v) { sky(v, true, 1000.0); }},
  };
  // configs[first, last): the Moon's are 0..2, Earth's 3..5.
  const std::size_t first = part == "earth" ? 3 : 0, last = part == "moon" ? 3 : configs.size();
  std::vector<std::unique_ptr<render::BodyView>> views;
  for (std::size_t k = first; k < last; ++k) {
    const Config& c = configs[k];
    views.push_back(std::make_unique<render::BodyView>(width, height, true));
    render::BodyView& v = *views.back();
    v.SetBodies(c.in->sun, c.in->bodies, airless);
    c.setUp(v);
    v.SetCamera(c.in->camera);
    v.SetExposureEV(c.exposureEv);
    v.Render();  // warm up: shaders, textures
  }
  bench::printRenderer(*views.front());
  if (last == configs.size()) {
    const render::AtmosphereRendering& limbView = views.back()->GetAtmosphere();
    std::printf("ring width on screen: %.2f px (limb-luminance LuT used: %s)\n", limbView.GetLastRingWidthPixels(),
                limbView.GetLastDrawUsedLimbLuminance() ? "yes" : "no");
  }
  const bench::FrameTimes times = bench::medianFrameTimes(views, frames);
  // The stage the paper times: the lunar surface (Table 1), the atmosphere (Table 2).
  std::printf("| %dx%d, %d frames, %s tables, median | GL timer [ms] | wall [ms] | CPU [ms] | GL time ratio | CPU time "
              "ratio | stage [ms] | stage ratio |\n",
              width, height, frames, tables.c_str());
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t k = first; k < last; ++k) {
    const std::size_t i = k - first, base = (k < 3 ? 0 : 3) - first;  // vs shadow off / vs no refraction
    const std::vector<double>& stage = k < 3 ? times.receiversMs : times.atmosphereMs;
    std::printf("| %s | %.3f | %.3f | %.2f | %.2f | %.2f | %s %.3f | %.2f |\n", configs[k].name, times.glMs[i],
                times.wallMs[i], times.cpuMs[i], times.glMs[i] / times.glMs[base], times.cpuMs[i] / times.cpuMs[base],
                k < 3 ? "receivers" : "atmosphere", stage[i], stage[i] / stage[base]);
  }
  return 0;
}
