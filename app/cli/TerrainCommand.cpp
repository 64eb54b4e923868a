// umbra terrain shadow: the visible fraction of the solar disc over a DEM (terrain paper).
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "TerrainSite.hpp"

#include "SoftShadow.hpp"
#include "SolarDisc.hpp"
#include "TerrainImageData.h"
#include "scene/Bodies.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Time.hpp"
#include "umbra/tables/Exr.h"
#include "vtkTerrainHorizonShadowFilter.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedShortArray.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace umbra::cli {
namespace {

constexpr double kDeg = kTerrainDeg;

struct Options {
  SiteOptions site;
  std::string output, method = "dp", time;
  int levels = 6, uniformSteps = 128;
  double elevationDeg = NAN, azimuthDeg = NAN, limbDarkening = 0.0;
};

/// The Sun in the DEM's tangent frame and its angular radius.
struct SunSetting {
  glm::dvec3 direction;
  double angularRadiusRad;
};

SunSetting sunFromTime(const Options& o, const scene::BodyPreset& body, double latDeg, double lonDeg) {
  try {
    const scene::SunFromBody sun = scene::sunFromBody(body.name, scene::parseUtc(o.time));
    return {terrain::bodyFixedToTangent(latDeg, lonDeg) * sun.directionBodyFixed, sun.angularRadiusRad};
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--time: ") + e.what());
  }
}

void writePng(const std::string& path, vtkImageData* result) {
  vtkDataArray* fraction = result->GetPointData()->GetArray("visible_solar_fraction");
  vtkNew<vtkImageData> image;
  image->SetDimensions(result->GetDimensions());
  vtkNew<vtkUnsignedShortArray> gray;  // linear, 0 = umbra, 65535 = fully lit
  gray->SetNumberOfTuples(fraction->GetNumberOfTuples());
  for (vtkIdType k = 0; k < fraction->GetNumberOfTuples(); ++k)
    gray->SetValue(k, static_cast<unsigned short>(std::lround(65535.0 * fraction->GetTuple1(k))));
  image->GetPointData()->SetScalars(gray);
  // VTK's first row is the bottom of the picture: north up
  umbra::cli::writePng(image, path);
}

void writeExr(const std::string& path, vtkImageData* result, std::map<std::string, std::string> parameters) {
  vtkDataArray* fraction = result->GetPointData()->GetArray("visible_solar_fraction");
  int dims[3];
  result->GetDimensions(dims);
  tables::Table t;
  t.width = dims[0];
  t.height = dims[1];
  t.channels = {"visible_solar_fraction"};
  t.data.resize(static_cast<std::size_t>(dims[0]) * dims[1]);
  for (int j = 0; j < dims[1]; ++j)  // the top row is the DEM's last (+y, north)
    for (int i = 0; i < dims[0]; ++i)
      t.data[static_cast<std::size_t>(dims[1] - 1 - j) * dims[0] + i] =
          static_cast<float>(fraction->GetTuple1(static_cast<vtkIdType>(j) * dims[0] + i));
  parameters["rows"] = "top row = last DEM row (+y, north)";
  t.parameters = std::move(parameters);
  tables::writeExr(path, t);
}

int runShadow(const Options& o) {
  output::checkWritable(o.output, {".exr", ".png", ".vti"});
  const terrain::ShadowMethod method = [&] {
    try {
      return terrain::parseShadowMethod(o.method);
    } catch (const std::exception& e) {
      throw CommandError(std::string("--method: ") + e.what());
    }
  }();
  const Site site = loadSite(o.site);
  const Dem& dem = site.dem;
  const std::string& source = site.source;
  const scene::BodyPreset* body = site.body;
  const double latDeg = site.latDeg, lonDeg = site.lonDeg;

  // The Sun.
  SunSetting sun;
  const bool angles = !std::isnan(o.elevationDeg) || !std::isnan(o.azimuthDeg);
  if (angles == !o.time.empty())
    throw CommandError("give either --sun-elevation-deg and --sun-azimuth-deg, or --time");
  if (angles) {
    if (std::isnan(o.elevationDeg) || std::isnan(o.azimuthDeg))
      throw CommandError("give both --sun-elevation-deg and --sun-azimuth-deg");
    if (!(o.elevationDeg >= -90.0 && o.elevationDeg <= 90.0)) throw CommandError("--sun-elevation-deg: expected -90..90");
    if (!std::isfinite(o.azimuthDeg)) throw CommandError("--sun-azimuth-deg: expected a finite angle");
    const double distance = scene::meanDistanceFromSunM(*body);
    sun = {terrain::sunDirectionFromElevationAzimuth(o.elevationDeg * kDeg, o.azimuthDeg * kDeg),
           distance > 0.0 ? std::asin(eclipse::kSunRadiusM / distance) : terrain::kSunAngularRadiusAt1AuRad};
  } else {
    sun = sunFromTime(o, *body, latDeg, lonDeg);
  }
  const double elevationDeg = std::asin(std::clamp(sun.direction.z, -1.0, 1.0)) / kDeg;
  double azimuthDeg = std::atan2(sun.direction.x, sun.direction.y) / kDeg;
  if (azimuthDeg < 0.0) azimuthDeg += 360.0;

  // The shadow, through the filter.
  auto image = filters::imageFromHeightField(dem.field);
  vtkNew<vtkTerrainHorizonShadowFilter> filter;
  filter->SetInputData(image);
  filter->SetSunDirection(sun.direction.x, sun.direction.y, sun.direction.z);
  filter->SetSunAngularRadiusRad(sun.angularRadiusRad);
  filter->SetLimbDarkening(o.limbDarkening);
  filter->SetBodyRadiusM(dem.field.bodyRadiusM);
  filter->SetMethod(static_cast<int>(method));
  filter->SetLevels(o.levels);
  filter->SetUniformSteps(o.uniformSteps);
  ProgressLine progress("terrain shadow", filter);
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vtkImageData* result = filter->GetOutput();
  vtkDataArray* fraction = result->GetPointData()->GetArray("visible_solar_fraction");
  if (!fraction) throw CommandError("the shadow computation failed");

  const std::string ext = output::extensionOf(o.output);
  if (ext == ".png") writePng(o.output, result);
  else if (ext == ".vti") writeVti(o.output, result);
  else
    writeExr(o.output, result,
             {{"source", source}, {"method", o.method}, {"levels", std::to_string(o.levels)},
              {"uniformSteps", std::to_string(o.uniformSteps)}, {"spacingM", terrainNumber(dem.field.spacingM)},
              {"bodyRadiusM", terrainNumber(dem.field.bodyRadiusM)}, {"sunElevationDeg", terrainNumber(elevationDeg)},
              {"sunAzimuthDeg", terrainNumber(azimuthDeg)}, {"sunAngularRadiusRad", terrainNumber(sun.angularRadiusRad)},
              {"limbDarkening", terrainNumber(o.limbDarkening)}, {"time", o.time}});

  double sum = 0.0;
  long long umbra = 0, lit = 0;
  const vtkIdType n = fraction->GetNumberOfTuples();
  for (vtkIdType k = 0; k < n; ++k) {
    const double v = fraction->GetTuple1(k);
    sum += v, umbra += v == 0.0, lit += v == 1.0;
  }
  std::printf("wrote %s: %d x %d at %.6g m (%s), method %s, %.2f s\n", o.output.c_str(), dem.field.width,
              dem.field.height, dem.field.spacingM, source.c_str(), o.method.c_str(), seconds);
  std::printf("sun elevation %.9f deg, azimuth %.9f deg at the centre (lat %.6f, lon %.6f), radius %.6f deg\n",
              elevationDeg, azimuthDeg, latDeg, lonDeg, sun.angularRadiusRad / kDeg);
  std::printf("mean visible fraction %.4f; umbra %.1f %%, penumbra %.1f %%, fully lit %.1f %%\n", sum / n,
              100.0 * umbra / n, 100.0 * (n - umbra - lit) / n, 100.0 * lit / n);
  return 0;
}

} // namespace

void addTerrainCommand(CLI::App& app, Action& action) {
  CLI::App* terrainCmd = app.add_subcommand("terrain", "Terrain: soft horizon shadows of the Sun on a DEM");
  terrainCmd->require_subcommand(1);
  CLI::App* shadow = terrainCmd->add_subcommand(
      "shadow", "Visible fraction of the solar disc (0 = umbra, 1 = fully lit) at every sample of a DEM");
  auto o = std::make_shared<Options>();
  const auto checkSite = addSiteOptions(shadow, o->site, " for --time");
  shadow->add_option("--sun-elevation-deg", o->elevationDeg, "Sun elevation at the DEM centre [deg]");
  shadow->add_option("--sun-azimuth-deg", o->azimuthDeg, "Sun azimuth at the DEM centre, from north (+y) to east (+x) [deg]");
  shadow->add_option("--time", o->time, "UTC instant (ISO 8601): the Sun from the ephemeris and the body's rotation");
  shadow->add_option("--method", o->method, "dp (maximum mipmap, Algorithm 1), uniform, cells (every cell crossed, exact: slow over long footprints) or reference")->capture_default_str();
  shadow->add_option("--levels", o->levels, "DP: mip levels N' per concatenated interval")->capture_default_str()->check(CLI::Range(1, 30));
  shadow->add_option("--uniform-steps", o->uniformSteps, "uniform: steps along each shadow ray")->capture_default_str()->check(CLI::Range(1, 1 << 20));
  shadow->add_option("--limb-darkening", o->limbDarkening, "Linear limb darkening of the disc (0: uniform)")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  shadow->add_option("--output", o->output, "Output: .exr (float), .png (16-bit linear gray), .vti (heights + fraction)")->required();
  addTerrainLightingCommand(terrainCmd, action);
  shadow->callback([&action, o, checkSite] {
    action = [o, checkSite] {
      checkSite();
      return runShadow(*o);
    };
  });
}

} // namespace umbra::cli
