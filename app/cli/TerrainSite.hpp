#pragma once
// The terrain the `umbra terrain` commands work on: a DEM or a synthetic crater field on a
// body, and where its grid's centre lies; the options that name it.
#include "TerrainDem.hpp"

#include "scene/Bodies.hpp"

#include <CLI/CLI.hpp>

#include <glm/glm.hpp>

#include <cmath>
#include <functional>
#include <string>

class vtkImageData;

namespace umbra::cli {

inline constexpr double kTerrainDeg = 3.14159265358979323846 / 180.0;

/// What names the terrain: --dem or --synthetic (with --size, --spacing), --body,
/// --body-radius, --lat-deg, --lon-deg.
struct SiteOptions {
  std::string dem, body = "Moon", bodyRadius, spacing = "30m";
  long long seed = -1;
  int size = 512;
  double latitudeDeg = NAN, longitudeDeg = NAN;
};

/// The terrain (a DEM or a synthetic crater field), its body and its centre.
struct Site {
  Dem dem;
  std::string source;
  const scene::BodyPreset* body = nullptr;
  double latDeg = 0.0, lonDeg = 0.0;
};

/// Adds the site's options to `command`; the function returned checks them (--dem or
/// --synthetic given, a seed >= 0) and throws CommandError. `centreFor` ends the help of
/// --lat-deg and --lon-deg (e.g. " for --time").
std::function<void()> addSiteOptions(CLI::App* command, SiteOptions& o, const std::string& centreFor);

/// Reads or makes the terrain. Throws CommandError naming the option.
Site loadSite(const SiteOptions& o);

/// A body-fixed direction in the site's tangent frame (x east, y north, z up).
glm::dvec3 inTangentFrame(const Site& site, const glm::dvec3& bodyFixed);

/// A number for a file's header or a CSV cell (%.10g).
std::string terrainNumber(double v);

/// Writes `image` as a VTK XML image, atomically. Throws CommandError naming the path.
void writeVti(const std::string& path, vtkImageData* image);

} // namespace umbra::cli
