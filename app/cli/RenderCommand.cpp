// umbra render SCENE [--time ISO8601] [--size WxH] [--exposure EV] [--atmosphere-tables default|small] [--refraction]
//   --output FILE.png|FILE.exr
// A body with "atmosphere" in the scene is drawn with it (AtmosphereRendering); its tables
// come from vtkAtmosphereTablesSource through the cache (the first render of an atmosphere
// at default sizes precomputes them: about a minute on 2 cores).
#include "BodyView.h"
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "SceneInputs.h"
#include "SceneTerrain.h"
#include "TerrainDem.hpp"
#include "ShadowCommon.hpp"
#include "SolarDisc.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"

#include "scene/Scene.hpp"
#include "scene/Time.hpp"
#include "umbra/tables/Exr.h"

#include <vtkImageData.h>
#include <vtkNew.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>

namespace umbra::cli {
namespace {

void parseSize(const std::string& text, int& width, int& height) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,5})x(\d{1,5}))")))
    throw CommandError("--size: expected WIDTHxHEIGHT (e.g. 1280x720), got '" + text + "'");
  width = std::stoi(m[1]);
  height = std::stoi(m[2]);
  if (width < 16 || height < 16 || width > 16384 || height > 16384)
    throw CommandError("--size: width and height must be within 16..16384, got '" + text + "'");
}

} // namespace

void addRenderCommand(CLI::App& app, Action& action) {
  CLI::App* render = app.add_subcommand(
      "render", "Render a scene offscreen: PNG (tone-mapped) or EXR (linear radiance, W m^-2 sr^-1). Needs an X "
                "display: run under xvfb-run -a on a headless machine");
  struct Options {
    std::string scene, time, size, output;
    std::optional<double> exposure;
    std::string atmosphereTables = "default";
    bool refraction = false;
    CacheOptions cache;
  };
  auto o = std::make_shared<Options>();
  render->add_option("SCENE", o->scene, "Scene file (JSON, see docs/scene-format.md)")->required();
  render->add_option("--time", o->time, "UTC time, ISO 8601 (default: the scene's)");
  render->add_option("--size", o->size, "Image size WIDTHxHEIGHT (default: the scene's)");
  render->add_option("--exposure", o->exposure, "Exposure in EV (default: the scene's)");
  render->add_option("--output,-o", o->output, "Image to write: FILE.png or FILE.exr")->required();
  render->add_option("--atmosphere-tables", o->atmosphereTables,
                     "Atmosphere table sizes: default (vtkAtmosphereTablesSource's: 256x64, 32,128,32,8, 64x16, "
                     "4 orders) or small (64x16, 8,32,8,4, 16x4, 3 orders: quick looks and tests)")
      ->capture_default_str();
  render->add_flag("--refraction", o->refraction,
                   "Bend the rays through the atmosphere (eclipse paper, 4.2): a lifted, flattened Sun at the "
                   "horizon; the tables then follow refracted paths");
  o->cache.addTo(render);

  render->callback([&action, o] {
    action = [o] {
      output::checkWritable(o->output, {".png", ".exr"});
      scene::Scene s = scene::loadScene(o->scene);
      if (!o->time.empty()) {
        try {
          scene::setTime(s, scene::parseUtc(o->time));
        } catch (const std::invalid_argument& e) {
          throw CommandError(std::string("--time: ") + e.what());
        }
      }
      if (!o->size.empty()) parseSize(o->size, s.width, s.height);
      if (o->exposure) s.exposureEv = *o->exposure;
      if (o->atmosphereTables != "default" && o->atmosphereTables != "small")
        throw CommandError("--atmosphere-tables: expected default or small, got '" + o->atmosphereTables + "'");
      if (!std::getenv("DISPLAY")) throw CommandError("rendering needs an X display: run under xvfb-run -a");

      const render::SceneInputs in = render::sceneInputs(s);
      auto lut = updateShadowLut(s.shadowLutSize, eclipse::kDefaultLimbDarkening, o->cache);

      render::BodyView view(s.width, s.height, /*offscreen=*/true);
      view.SetBodies(in.sun, in.bodies, lut->GetOutput());
      if (in.atmosphere) {
        vtkNew<vtkAtmosphereTablesSource> tables;
        tables->SetCacheDirectory(o->cache.directory.c_str());
        tables->SetUseCache(!o->cache.disabled);
        if (o->atmosphereTables == "small") render::useSmallAtmosphereTables(tables);
        try {
          render::applySceneAtmosphere(view, in, tables, o->refraction);
        } catch (const std::runtime_error& e) {
          throw CommandError(e.what());
        }
        if (tables->GetLastCacheHits() > 0) std::cerr << "atmosphere tables: cache hit\n";
      }
      view.SetCamera(in.camera);
      std::vector<std::unique_ptr<render::TerrainRendering>> terrains;  // (drawn by the view)
      try {
        terrains = render::addSceneTerrains(view, s, in, [](const std::string& path, double spacingM, double radiusM) {
          return readDem(path, spacingM, radiusM).field;
        });
      } catch (const std::invalid_argument& e) {
        throw CommandError(o->scene + ": " + e.what());
      }
      view.SetExposureEV(s.exposureEv);
      view.Render();

      if (output::extensionOf(o->output) == ".exr") {
        tables::Table t;
        t.channels = {"R", "G", "B"};
        view.ReadHdr(t.data, t.width, t.height);
        t.parameters = {{"kind", "radiance-image"},
                        {"units", "W m^-2 sr^-1 (linear, per channel)"},
                        {"scene", o->scene},
                        {"time", scene::formatUtc(s.time)},
                        {"exposureEV", std::to_string(s.exposureEv)}};
        tables::writeExr(o->output, t);
      } else {
        view.WritePng(o->output);
      }
      std::cout << "wrote " << o->output << " (" << s.width << "x" << s.height << ", " << s.name
                << (s.hasTime ? ", " + scene::formatUtc(s.time) : std::string()) << ")\n";
      return 0;
    };
  });
}

} // namespace umbra::cli
