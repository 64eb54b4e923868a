// umbra render SCENE [--time ISO8601] [--size WxH] [--exposure EV] [--glare S] [--atmosphere-tables default|small] [--refraction]
//   [--limb-ring-threshold PX]
//   --output FILE.png|FILE.exr
// umbra render SCENE --from ISO8601 --to ISO8601 --step DURATION [...] --output DIR/frame-%04d.png
//   an animation: one frame per step from --from to --to (inclusive), numbered from 0
// A body with "atmosphere" in the scene is drawn with it (AtmosphereRendering); its tables
// come from vtkAtmosphereTablesSource through the cache (the first render of an atmosphere
// at default sizes precomputes them: about a minute on 2 cores).
#include "BodyView.h"
#include "EglRenderWindow.h"
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "SceneInputs.h"
#include "AtmosphereShadow.h"
#include "SceneTerrain.h"
#include "TerrainDem.hpp"
#include "Ranks.hpp"
#include "ShadowCommon.hpp"
#include "SolarDisc.hpp"
#include "vtkUmbraRenderPass.h"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"

#include "scene/Scene.hpp"
#include "scene/Time.hpp"
#include "scene/Units.hpp"
#include "umbra/tables/Exr.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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

/// The frames of an animation: --from, --to, --step and an --output with one %d / %0Nd.
struct Frame {
  scene::UtcTime time;
  std::string path;
};

std::vector<Frame> animationFrames(const std::string& from, const std::string& to, const std::string& step,
                                   const std::string& pattern) {
  const std::vector<scene::UtcTime> times = timeSteps(from, to, step);
  if (!std::regex_match(pattern, std::regex(R"([^%]*%0?\d{0,2}d[^%]*)")))
    throw CommandError("--output: an animation needs one frame number in the name (e.g. frames/frame-%04d.png), got '" +
                       pattern + "'");
  std::vector<Frame> frames;
  for (std::size_t k = 0; k < times.size(); ++k) {
    char path[4096];
    std::snprintf(path, sizeof path, pattern.c_str(), static_cast<int>(k));
    frames.push_back({times[k], path});
  }
  return frames;
}

/// "6.5": a magnitude with at most two decimals, trailing zeros dropped.
std::string formatMagnitude(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  std::string t = text;
  while (t.back() == '0') t.pop_back();
  if (t.back() == '.') t.pop_back();
  return t;
}

struct RenderOptions {
  std::string scene, time, size, output, from, to, step;
  std::optional<double> exposure;
  std::optional<double> limitingMagnitude;
  std::optional<double> glare;
  bool nightVision = false, noNightVision = false;
  std::string atmosphereTables = "default";
  bool refraction = false;
  double limbRingThresholdPx = 5.0;
  bool egl = false;
  std::string terrainShadows = "table";
  CacheOptions cache;
  bool animation() const { return !from.empty() || !to.empty() || !step.empty(); }
  bool smallTables() const { return atmosphereTables == "small"; }
};

void addRenderOptions(CLI::App* render, RenderOptions& o) {
  render->add_option("SCENE", o.scene, "Scene file (JSON, see docs/scene-format.md)")->required();
  render->add_option("--time", o.time, "UTC time, ISO 8601 (default: the scene's)");
  render->add_option("--size", o.size, "Image size WIDTHxHEIGHT (default: the scene's)");
  render->add_option("--exposure", o.exposure, "Exposure in EV (default: the scene's)")->check(CLI::Range(-60.0, 60.0));
  CLI::Option* nightOn = render->add_flag(
      "--night-vision", o.nightVision,
      "Show the PNG as the eye sees dim light: below about 5 cd/m^2 colour fades to the rods' grey, fully below 0.005 "
      "(CIE 191 mesopic adaptation at each pixel), with the glare of an eye (--glare 1 unless given). The default for "
      "a PNG of a night scene (the Sun below the camera's horizon); EXR output keeps the radiance");
  render->add_flag("--no-night-vision", o.noNightVision,
                   "Show the PNG in the camera's colours, also at night (and no glare unless --glare is given)")
      ->excludes(nightOn);
  render->add_option("--limiting-magnitude", o.limitingMagnitude,
                     "The faintest stars drawn, V magnitude (default: the scene's, 6.5; the catalogue ends at 9)")
      ->check(CLI::Range(-30.0, 30.0));
  render->add_option("--glare", o.glare,
                     "Glare strength in [0, 10] (default 0: none; 1 with night vision): halos of 0.03, 0.15, 0.75 deg "
                     "around bright pixels holding 4, 2, 1 % of their light per unit, so a source's halo follows its "
                     "brightness (the Moon's with its phase and eclipse); the frame's total radiance is kept")
      ->check(CLI::Range(0.0, 10.0));
  render->add_option("--output,-o", o.output,
                     "Image to write: FILE.png or FILE.exr; for an animation a name with a frame number, "
                     "e.g. frames/frame-%04d.png")
      ->required();
  render->add_option("--from", o.from, "Animation: UTC time of the first frame, ISO 8601");
  render->add_option("--to", o.to, "Animation: UTC time of the last frame at most, ISO 8601");
  render->add_option("--step", o.step, "Animation: time between frames, e.g. 30min (units s, min, h, d)");
  render->add_option("--atmosphere-tables", o.atmosphereTables,
                     "Atmosphere table sizes: default (" + atmosphere::brunetonSizesText(atmosphere::kDefaultTableSizes) +
                         ") or small (" + atmosphere::brunetonSizesText(atmosphere::kSmallTableSizes) +
                         ": quick looks and tests). From the ground in "
                     "twilight (the Sun from 1 deg down to night: Earth 30, Mars 35 deg) the scattering and irradiance "
                     "tables have 4 times the mu_s cells (default: 16,128,128,8 and 256x16) and reach 20 deg below the "
                     "Sun (docs/accuracy-vs-speed/atmosphere-tables.md, \"Twilight in the render pass\")")
      ->capture_default_str();
  render->add_flag("--refraction", o.refraction,
                   "Bend the rays through the atmosphere (eclipse paper, 4.2): a lifted, flattened Sun at the "
                   "horizon; the tables then follow refracted paths");
  render->add_option("--limb-ring-threshold", o.limbRingThresholdPx,
                     "Draw an atmosphere's ring from the limb-luminance LuT when it is thinner than this on screen "
                     "(pixels; eclipse paper, 5.4); 0: always ray march")
      ->check(CLI::Range(0.0, 1.0e6))
      ->capture_default_str();
  render->add_flag("--egl", o.egl,
                   "Render through EGL even when DISPLAY is set (without it, EGL is used anyway): a GPU machine's "
                   "EGL device (the first that is not Mesa's software one; UMBRA_EGL_DEVICE=N picks another), else "
                   "Mesa's llvmpipe");
  render->add_option("--terrain-shadows", o.terrainShadows,
                     "How a terrain patch finds the Sun's visible fraction: table (a shadow table per 0.01 deg of "
                     "the Sun's motion, made on demand and cached; each pixel searches only its first 17 texels) or "
                     "search (the whole DP search per pixel: the reference; docs/accuracy-vs-speed/terrain.md)")
      ->check(CLI::IsMember({"table", "search"}))
      ->capture_default_str();
  o.cache.addTo(render);
}

/// The scene file with the options' changes (time, size, exposure, stars), its notes
/// printed; the EGL choice made.
scene::Scene renderedScene(const RenderOptions& o, const std::vector<Frame>& frames) {
  scene::Scene s = scene::loadScene(o.scene);
  for (const std::string& note : s.notes) std::cerr << "umbra: " << note << "\n";
  if (!o.time.empty()) {
    try {
      scene::setTime(s, scene::parseUtc(o.time));
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("--time: ") + e.what());
    }
  }
  if (o.animation())
    noteTimesBeyondEphemeris({frames.front().time, frames.back().time});
  else if (s.hasTime)
    noteTimesBeyondEphemeris({s.time});
  if (!o.size.empty()) parseSize(o.size, s.width, s.height);
  if (o.exposure) s.exposureEv = *o.exposure;
  if (o.limitingMagnitude) {
    if (!s.stars) throw CommandError("--limiting-magnitude: the scene draws no stars (it has no time, or \"stars\": false)");
    s.stars->limitingMagnitude = *o.limitingMagnitude;
  }
  if (o.atmosphereTables != "default" && o.atmosphereTables != "small")
    throw CommandError("--atmosphere-tables: expected default or small, got '" + o.atmosphereTables + "'");
  if (o.egl) {
    std::string error;
    if (!render::useEglRenderWindows(error)) throw CommandError("--egl: " + error);
  } else if (render::useEglWithoutDisplay()) {
    std::cerr << "umbra: no X display: rendering through EGL\n";
  }
  return s;
}

/// The view of the frames and its table sources (each from the cache, with its progress
/// line), kept from frame to frame: a table is made again only when a frame needs another.
class FrameRenderer {
public:
  FrameRenderer(const RenderOptions& o, const scene::Scene& s) : o(o), view(s.width, s.height, /*offscreen=*/true) {
    tables->SetCacheDirectory(o.cache.directory.c_str());
    tables->SetUseCache(!o.cache.disabled);
    shadow->SetCacheDirectory(o.cache.directory.c_str());
    shadow->SetUseCache(!o.cache.disabled);
    limb->SetCacheDirectory(o.cache.directory.c_str());
    limb->SetUseCache(!o.cache.disabled);
    if (o.smallTables()) {
      pipeline::useSmallEclipseShadowTables(shadow);
      pipeline::useSmallLimbLuminanceTables(limb);
    }
    view.GetAtmosphere().SetLimbRingThresholdPixels(o.limbRingThresholdPx);
  }

  /// Sets the view up for `s` at its present time (frame k): the bodies with the airless
  /// LuT, the sky, the atmosphere with its tables and eclipse LuTs, the camera, the terrains.
  void show(const scene::Scene& s, std::size_t k) {
    const pipeline::SceneInputs in = pipeline::sceneInputs(s);
    starCount = in.stars.size();
    // Near an occluder (Phobos by Mars) a whole LuT is too coarse: one over the
    // receivers' u and v ranges (pipeline::sceneLutRange), as the atmospheric one's.
    const auto range = pipeline::sceneLutRange(in.sun, in.bodies, in.bodies, /*darkUmbra=*/true, s.shadowLutSize);
    if (!lut || range != lutRange) {
      lut = updateShadowLut(s.shadowLutSize, eclipse::kDefaultLimbDarkening, o.cache, nullptr, nullptr,
                            range ? &*range : nullptr, range ? pipeline::rangedLutWidth(*range, s.shadowLutSize) : 0);
      lutRange = range;
    }
    view.SetBodies(in.sun, in.bodies, lut->GetOutput());
    pipeline::showSceneSky(view, in);
    if (in.atmosphere) {
      try {
        pipeline::applySceneAtmosphere(view, in, tables, o.refraction,
                                       o.smallTables() ? pipeline::AtmosphereTableSizes::Small
                                                       : pipeline::AtmosphereTableSizes::Default);
        // The other bodies in its shadow: the atmospheric shadow LuT (their columns only);
        // its ring, when thin on screen: the limb-luminance LuT (eclipse paper, 5.4).
        pipeline::applySceneAtmosphereShadow(view.GetShading(), in, shadow);
        pipeline::applySceneLimbLuminance(view.GetAtmosphere(), in, limb);  // (none at threshold 0)
      } catch (const std::runtime_error& e) {
        throw CommandError(e.what());
      }
      if (k == 0 && tables->GetLastCacheHits() > 0) std::cerr << "atmosphere tables: cache hit\n";
    }
    view.SetCamera(in.camera);
    try {
      // The patches (mesh, mipmap, textures; a DEM read once) are built for the first
      // frame; later frames only move them with their bodies and the Sun.
      pipeline::TerrainShadowSettings shadows;
      shadows.tables = o.terrainShadows == "table";
      shadows.cacheDirectory = o.cache.directory;
      shadows.useCache = !o.cache.disabled;
      if (k == 0)
        terrains = pipeline::addSceneTerrains(
            view, s, in,
            [](const std::string& path, double spacingM, double radiusM) { return readDem(path, spacingM, radiusM).field; },
            shadows);
      else
        pipeline::placeSceneTerrains(terrains, view, s, in, shadows);
    } catch (const std::invalid_argument& e) {
      throw CommandError(o.scene + ": " + e.what());
    }
    view.SetExposureEV(s.exposureEv);
  }

  /// Renders the frame with night vision and glare as asked for (night vision: asked for,
  /// or a PNG of a night scene unless refused; it brings the eye's glare unless a strength
  /// is given; an EXR keeps the radiance) and writes it to `path`.
  void renderTo(const scene::Scene& s, std::size_t k, const std::string& path) {
    const bool png = output::extensionOf(path) != ".exr";
    const bool nightVision = png && (o.nightVision || (!o.noNightVision && scene::nightAtCamera(s)));
    const double glare = o.glare ? *o.glare : nightVision ? 1.0 : 0.0;
    if (nightVision && !o.nightVision && !nightNoted) {
      std::cerr << "umbra: night vision on, glare " << glare << " (" << scene::describeSunElevation(*scene::sunElevationDeg(s))
                << "): the eye's view; --no-night-vision for the camera's colours\n";
      nightNoted = true;
    }
    view.GetRenderPass()->SetNightVision(nightVision);
    view.GetRenderPass()->SetGlareStrength(glare);
    view.Render();
    if (k == 0 && render::usingEglRenderWindows())
      std::cerr << "umbra: EGL: " << render::glRendererString(view.GetRenderWindow()) << "\n";  // GPU or llvmpipe
    if (png) {
      view.WritePng(path);
      return;
    }
    tables::Table t;
    t.channels = {"R", "G", "B"};
    view.ReadHdr(t.data, t.width, t.height);
    t.parameters = {{"kind", "radiance-image"},
                    {"units", "W m^-2 sr^-1 (linear, per channel)"},
                    {"scene", o.scene},
                    {"time", scene::formatUtc(s.time)},
                    {"exposureEV", std::to_string(s.exposureEv)},
                    {"glare", std::to_string(glare)}};
    tables::writeExr(path, t);
  }

  std::size_t stars() const { return starCount; }

private:
  const RenderOptions& o;
  render::BodyView view;
  vtkNew<vtkAtmosphereTablesSource> tables;
  vtkNew<vtkEclipseShadowLutSource> shadow;
  vtkNew<vtkLimbLuminanceSource> limb;
  // Tables made on demand (none from the cache) can take minutes: their progress.
  const ProgressLine tablesProgress{"atmosphere tables", tables};
  const ProgressLine shadowProgress{"atmospheric shadow LuT", shadow};
  const ProgressLine limbProgress{"limb-luminance LuT", limb};
  vtkSmartPointer<vtkEclipseShadowLutSource> lut;  // the airless LuT, per frame when its ranges change
  std::optional<eclipse::LutRange> lutRange;
  std::vector<std::unique_ptr<render::TerrainRendering>> terrains;  // (drawn by the view)
  std::size_t starCount = 0;
  bool nightNoted = false;  // the note on night vision, at its first frame
};

/// Where frame `path` is written until the animation is done: beside it, hidden, with its
/// extension (the writers go by it).
std::string partPathOf(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / ("." + p.stem().string() + ".part" + p.extension().string())).string();
}

/// An animation: each rank renders its share of the frames (parallel::share: consecutive
/// frames, so that tables and LuTs carry over from frame to frame) into hidden part files;
/// when every rank has succeeded they take the frames' names, else they go: an animation
/// is written whole or not at all. Tables come from the shared cache (one rank makes a
/// missing one, the others wait for it: TableCache::lock). Rank 0 reports progress.
int renderAnimation(const RenderOptions& o, const std::vector<Frame>& frames, scene::Scene s) {
  parallel::Ranks& ranks = parallel::Ranks::world();
  const auto [begin, end] = parallel::share(frames.size(), ranks.rank(), ranks.size());
  std::vector<std::string> parts;  // written by this rank
  std::string error;
  const auto start = std::chrono::steady_clock::now();
  try {
    FrameRenderer renderer(o, s);
    std::optional<ProgressLine> progress;
    if (ranks.root()) progress.emplace("frames (" + std::to_string(frames.size()) + ")");
    int lastTenth = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const Frame& f = frames[k];
      try {
        scene::setTime(s, f.time);
      } catch (const scene::SceneError& e) {
        throw CommandError("--from/--to: at " + scene::formatUtc(f.time) + ": " + e.what());
      }
      renderer.show(s, k - begin);
      const std::string part = partPathOf(f.path);
      try {
        renderer.renderTo(s, k - begin, part);
      } catch (const std::exception& e) {
        throw CommandError("frame " + std::to_string(k) + " (" + scene::formatUtc(f.time) + ", " + f.path +
                           "): " + e.what());
      }
      parts.push_back(part);
      if (!progress) continue;
      const double done = static_cast<double>(k + 1 - begin) / static_cast<double>(end - begin);
      progress->update(done);
      // Under mpirun stderr is no terminal: a line every tenth of rank 0's share.
      if (ranks.size() > 1 && static_cast<int>(done * 10.0) > lastTenth && done < 1.0) {
        lastTenth = static_cast<int>(done * 10.0);
        std::cerr << "umbra: frames: " << lastTenth * 10 << "% of rank 0's " << end - begin << " (" << ranks.size()
                  << " ranks, " << frames.size() << " frames)\n";
      }
    }
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::string errors = ranks.finish(error);
  std::size_t renamed = 0;
  std::error_code ec;
  if (errors.empty()) {
    for (; renamed < parts.size(); ++renamed) {
      std::filesystem::rename(parts[renamed], frames[begin + renamed].path, ec);
      if (ec) {
        error = frames[begin + renamed].path + ": cannot write: " + ec.message();
        break;
      }
    }
    errors = ranks.finish(error);
  }
  if (!errors.empty()) {
    for (const std::string& p : parts) std::filesystem::remove(p, ec);
    for (std::size_t k = begin; k < begin + renamed; ++k) std::filesystem::remove(frames[k].path, ec);
    throw CommandError(errors);
  }
  std::cout << "wrote " << frames.size() << " frames " << frames.front().path << " .. " << frames.back().path << " ("
            << s.width << "x" << s.height << ", " << s.name << ", " << o.from << " .. "
            << scene::formatUtc(frames.back().time) << " every " << o.step << ")" << ranksNote(start) << "\n";
  return 0;
}

int runRender(const RenderOptions& o) {
  const bool animation = o.animation();
  if (animation && !o.time.empty()) throw CommandError("--time: not with --from/--to/--step");
  const std::vector<Frame> frames =
      animation ? animationFrames(o.from, o.to, o.step, o.output) : std::vector<Frame>{{{}, o.output}};
  for (const Frame& f : frames) output::checkWritable(f.path, {".png", ".exr"});
  scene::Scene s = renderedScene(o, frames);
  if (animation) return renderAnimation(o, frames, s);
  if (!parallel::Ranks::world().root()) return 0;  // one frame: rank 0's
  FrameRenderer renderer(o, s);
  renderer.show(s, 0);
  renderer.renderTo(s, 0, o.output);
  const std::optional<double> sunDeg = scene::sunElevationDeg(s);
  std::cout << "wrote " << o.output << " (" << s.width << "x" << s.height << ", " << s.name
            << (s.hasTime ? ", " + scene::formatUtc(s.time) : std::string())
            << (sunDeg ? ", " + scene::describeSunElevation(*sunDeg) : std::string())
            << (s.stars ? ", " + std::to_string(renderer.stars()) + " stars to V " +
                              formatMagnitude(s.stars->limitingMagnitude)
                        : std::string())
            << ")\n";
  return 0;
}

} // namespace

void addRenderCommand(CLI::App& app, Action& action) {
  CLI::App* render = app.add_subcommand(
      "render", "Render a scene offscreen: PNG (tone-mapped) or EXR (linear radiance, W m^-2 sr^-1). On the X "
                "display when DISPLAY is set, else (or with --egl) through EGL");
  auto o = std::make_shared<RenderOptions>();
  addRenderOptions(render, *o);
  render->callback([&action, o] { action = [o] { return runRender(*o); }; });
}

} // namespace umbra::cli
