// Frame time of the Moon's photometry in the receivers' shader (DESIGN.md: "Hapke Moon
// <= +20 % of Lambert's stage"). Renders the 2015-09-28 scene's Moon filling a Full-HD
// frame (Earth present as an occluder, so all shade the eclipse) four ways, interleaved:
// Lambert's law with a uniform albedo (the Moon before its photometry), the
// Hapke–Lommel–Seeliger reflectance with a uniform albedo (and earthshine when the scene
// has some), Hapke with the albedo map, and Hapke with the albedo map and the relief's
// normal map as the scene draws it; prints the median frame and receivers-stage times
// (GL_TIMESTAMP around the stage) and their cost over Lambert's.
// Needs an X display (xvfb-run -a) or --egl (EGL, no X); on llvmpipe the fragment work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-moon [--frames 40] [--width 1920 --height 1080]
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "scene/Scene.hpp"

#include <CLI/CLI.hpp>

#include <vtkImageData.h>

#include <cstdio>
#include <string>
#include <vector>

using namespace umbra;

int main(int argc, char** argv) {
  CLI::App app{"Frame time of the Moon's Hapke photometry and albedo map against Lambert's law"};
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
  std::vector<render::SphereBody> lambert = in.bodies, uniform = in.bodies, mapOnly = in.bodies;
  std::string map, normals;  // the files the scene's maps are read from
  for (const scene::Body& b : s.bodies)
    if (b.photometry.law == sky::Photometry::Law::Hapke) {
      if (!b.albedoMapPath.empty()) map = b.albedoMapPath;
      if (!b.normalMapPath.empty()) normals = b.normalMapPath;
    }
  for (std::size_t k = 0; k < in.bodies.size(); ++k) {
    if (in.bodies[k].photometry.law != sky::Photometry::Law::Hapke) continue;
    lambert[k].photometry = {};
    lambert[k].albedoMap.reset();
    lambert[k].normalMap.reset();
    lambert[k].earthshineWm2 = glm::dvec3(0.0);
    uniform[k].albedoMap.reset();
    uniform[k].normalMap.reset();
    mapOnly[k].normalMap.reset();
  }
  if (map.empty()) std::fprintf(stderr, "note: the scene's bodies have no albedo map (marble-qt-data not installed?)\n");
  if (normals.empty()) std::fprintf(stderr, "note: the scene's bodies have no relief (stellarium-data not installed?)\n");

  render::BodyView withRelief(width, height, true), withMap(width, height, true), hapke(width, height, true),
      plain(width, height, true);
  withRelief.SetBodies(in.sun, in.bodies, lut);
  withMap.SetBodies(in.sun, mapOnly, lut);
  hapke.SetBodies(in.sun, uniform, lut);
  plain.SetBodies(in.sun, lambert, lut);
  for (render::BodyView* v : {&withRelief, &withMap, &hapke, &plain}) {
    v->SetCamera(in.camera);
    v->SetExposureEV(s.exposureEv);
    v->Render();  // warm up: shader compilation, texture upload
  }
  bench::printRenderer(withMap);
  const bench::FrameTimes t = bench::medianFrameTimes({&withRelief, &withMap, &hapke, &plain}, frames);
  auto cost = [](double a, double b) { return 100.0 * (a / b - 1.0); };
  std::printf("| %dx%d, %d frames, median | Lambert [ms] | Hapke [ms] | cost | Hapke + albedo map [ms] | cost | "
              "Hapke + albedo map + relief [ms] | cost |\n|---|---:|---:|---:|---:|---:|---:|---:|\n",
              width, height, frames);
  auto row = [&](const char* what, const std::vector<double>& ms) {
    std::printf("| %s | %.2f | %.2f | %+.1f %% | %.2f | %+.1f %% | %.2f | %+.1f %% |\n", what, ms[3], ms[2],
                cost(ms[2], ms[3]), ms[1], cost(ms[1], ms[3]), ms[0], cost(ms[0], ms[3]));
  };
  row("frame (wall)", t.wallMs);
  if (t.receiversMs[3] > 0.0) row("receivers stage (GL)", t.receiversMs);
  if (!map.empty()) std::printf("albedo map: %s\n", map.c_str());
  if (!normals.empty()) std::printf("normal map: %s\n", normals.c_str());
  return 0;
}
