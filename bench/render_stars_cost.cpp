// What the stars cost: the catalogue read (the text, then its binary copy in a fresh cache
// directory under the system's temporary one, then from the process's memo), the
// apparent places of every star, and in the render pass the orion-night-sky example with
// every catalogue star to V 9 beside the same view without stars, with the stars and the
// atmosphere stages of the same frames (GL_TIMESTAMP between the stages; Mesa's llvmpipe
// runs the point draws when the next stage flushes them, so there the difference of the
// frames is the stars' cost); and the moonlit-night example with the Moon's light and
// without it. Tables through the cache (the first run precomputes them). Needs an X display
// (xvfb-run -a) or --egl; on llvmpipe the fragment work runs on the CPU.
//
//   xvfb-run -a build/bench/umbra-bench-render-stars [--frames 20] [--width 1920 --height 1080]
#include "BodyView.h"
#include "RenderBenchSupport.hpp"
#include "SceneInputs.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "StarCatalogue.hpp"
#include "StarCatalogueCache.h"
#include "scene/Scene.hpp"
#include "scene/Stars.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "vtkUmbraRenderPass.h"

#include <CLI/CLI.hpp>

#include <vtkImageData.h>
#include <vtkNew.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <unistd.h>

using namespace umbra;

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"What the stars and the moonlit sky cost"};
  bench::FrameBenchOptions o;
  bench::addFrameBenchOptions(app, o);
  CLI11_PARSE(app, argc, argv);
  const int frames = o.frames, width = o.width, height = o.height;
  if (!std::filesystem::exists(sky::kKStarsCatalogue)) {
    std::fprintf(stderr, "%s is not installed (Debian package kstars-data)\n", sky::kKStarsCatalogue);
    return 1;
  }
  if (!bench::startWindows(o.egl)) return 1;

  // The catalogue and the places.
  const std::filesystem::path cache =
      std::filesystem::temp_directory_path() / ("umbra-bench-stars-" + std::to_string(::getpid()));
  auto t0 = std::chrono::steady_clock::now();
  pipeline::readStarCatalogue(sky::kKStarsCatalogue, cache.string());
  const double textMs = msSince(t0);
  t0 = std::chrono::steady_clock::now();
  pipeline::readStarCatalogue(sky::kKStarsCatalogue, cache.string());
  const double copyMs = msSince(t0);
  std::filesystem::remove_all(cache);
  const auto all = pipeline::starCatalogue(sky::kKStarsCatalogue);
  t0 = std::chrono::steady_clock::now();
  pipeline::starCatalogue(sky::kKStarsCatalogue);
  const double memoMs = msSince(t0);
  scene::Scene orion = scene::loadScene(bench::exampleScene("orion-night-sky.json"));
  orion.stars->limitingMagnitude = 9.0;
  t0 = std::chrono::steady_clock::now();
  const std::vector<glm::dvec3> places =
      scene::apparentStarDirections(*all, orion.time, scene::starObserverOf(orion));
  const double placesMs = msSince(t0);
  std::printf("catalogue: %zu stars; from the text %.1f ms (and its binary copy written), from the copy %.1f ms, "
              "again in the same process %.3f ms; apparent places of all %.1f ms\n\n",
              all->size(), textMs, copyMs, memoMs, placesMs);

  const auto lut = filters::toImageData(eclipse::buildAirlessShadowLut({64, 64}));
  const pipeline::SceneInputs starry = pipeline::sceneInputs(orion);
  pipeline::SceneInputs starless = starry;
  starless.stars.clear();
  const scene::Scene moonlit = scene::loadScene(bench::exampleScene("moonlit-night-2026-10-26.json"));
  pipeline::SceneInputs lit = pipeline::sceneInputs(moonlit), unlit = lit;
  unlit.atmosphere->moonIrradianceWm2 = glm::dvec3(0.0);
  std::vector<std::unique_ptr<render::BodyView>> views;
  views.push_back(bench::sceneView(orion, starry, width, height, lut));
  views.push_back(bench::sceneView(orion, starless, width, height, lut));
  views.push_back(bench::sceneView(moonlit, lit, width, height, lut));
  views.push_back(bench::sceneView(moonlit, unlit, width, height, lut));
  bench::printRenderer(*views.front());
  const bench::FrameTimes t = bench::medianFrameTimes(views, frames);
  std::printf("| %dx%d, %d frames, median [ms] | frame (GL) | stars stage | atmosphere stage |\n", width, height,
              frames);
  std::printf("|---|---:|---:|---:|\n");
  std::printf("| orion-night-sky, %zu stars to V 9 | %.2f | %.2f | %.2f |\n", starry.stars.size(), t.glMs[0],
              t.starsMs[0], t.atmosphereMs[0]);
  std::printf("| orion-night-sky, no stars | %.2f | %.2f | %.2f |\n", t.glMs[1], t.starsMs[1], t.atmosphereMs[1]);
  std::printf("| moonlit-night, %zu stars, the Moon's light | %.2f | %.2f | %.2f |\n", lit.stars.size(), t.glMs[2],
              t.starsMs[2], t.atmosphereMs[2]);
  std::printf("| moonlit-night, without the Moon's light | %.2f | %.2f | %.2f |\n", t.glMs[3], t.starsMs[3],
              t.atmosphereMs[3]);
  const double starsMs = std::max(t.starsMs[0], t.glMs[0] - t.glMs[1]);
  std::printf("\nthe stars to V 9: %.2f ms a frame, %.3f of the atmosphere stage (%.2f ms); the Moon's light: %+.1f %% "
              "on the atmosphere stage\n",
              starsMs, starsMs / t.atmosphereMs[1], t.atmosphereMs[1],
              100.0 * (t.atmosphereMs[2] / t.atmosphereMs[3] - 1.0));
  return 0;
}
