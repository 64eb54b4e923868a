#include "TerrainSite.hpp"

#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"  // lengthOption

#include "CraterField.hpp"
#include "HeightField.hpp"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataWriter.h>

#include <cstdio>

namespace umbra::cli {

std::function<void()> addSiteOptions(CLI::App* command, SiteOptions& o, const std::string& centreFor) {
  auto* dem = command->add_option("--dem", o.dem, "DEM raster (GeoTIFF or any GDAL raster; heights in m, projected CRS)");
  auto* synthetic = command->add_option("--synthetic", o.seed, "Synthetic crater field with this seed (>= 0)");
  dem->excludes(synthetic);
  command->add_option("--size", o.size, "Synthetic field: samples per side")->capture_default_str()->check(CLI::Range(2, 8192));
  command->add_option("--spacing", o.spacing, "Sample spacing (synthetic field, or a DEM without georeferencing)")
      ->capture_default_str();
  command->add_option("--body", o.body, "Body (radius; ephemeris and rotation for the Sun's times)")->capture_default_str();
  command->add_option("--body-radius", o.bodyRadius, "Override the body radius (units m, km)");
  command->add_option("--lat-deg", o.latitudeDeg, "Latitude of the DEM centre" + centreFor + " (default: georeferencing, else -90)");
  command->add_option("--lon-deg", o.longitudeDeg, "Longitude of the DEM centre" + centreFor + " (default: georeferencing, else 0)");
  return [&o, dem, synthetic] {
    if (dem->count() == 0 && synthetic->count() == 0) throw CommandError("give --dem FILE or --synthetic SEED");
    if (synthetic->count() && o.seed < 0) throw CommandError("--synthetic: expected a seed >= 0");
  };
}

Site loadSite(const SiteOptions& o) {
  Site site;
  site.body = scene::findPreset(o.body);
  if (!site.body) throw CommandError("--body: unknown body '" + o.body + "' (known: " + scene::presetNameList() + ")");
  const scene::BodyPreset* body = site.body;
  const double radiusOverride = o.bodyRadius.empty() ? 0.0 : lengthOption("--body-radius", o.bodyRadius, 1.0, kMaxRadiusM);
  const double spacingM = lengthOption("--spacing", o.spacing);
  if (!(spacingM > 0.0)) throw CommandError("--spacing: expected a positive length, got " + o.spacing);
  Dem& dem = site.dem;
  if (!o.dem.empty()) {
    dem = readDem(o.dem, spacingM, radiusOverride > 0.0 ? radiusOverride : (body->name == "Moon" ? 0.0 : body->meanRadiusM));
    site.source = o.dem;
  } else {
    terrain::CraterFieldOptions c;
    c.seed = static_cast<std::uint64_t>(o.seed);
    c.size = o.size;
    c.spacingM = spacingM;
    c.bodyRadiusM = radiusOverride > 0.0 ? radiusOverride : body->meanRadiusM;
    try {
      dem.field = terrain::makeCraterField(c);
      dem.field.validate();
    } catch (const std::exception& e) {
      throw CommandError(std::string("--synthetic with --size and --spacing: ") + e.what());
    }
    site.source = "synthetic crater field, seed " + std::to_string(o.seed);
  }
  site.latDeg = !std::isnan(o.latitudeDeg) ? o.latitudeDeg : dem.centreLatitudeDeg.value_or(-90.0);
  site.lonDeg = !std::isnan(o.longitudeDeg) ? o.longitudeDeg : dem.centreLongitudeDeg.value_or(0.0);
  if (!(site.latDeg >= -90.0 && site.latDeg <= 90.0)) throw CommandError("--lat-deg: expected -90..90");
  return site;
}

glm::dvec3 inTangentFrame(const Site& site, const glm::dvec3& bodyFixed) {
  return terrain::bodyFixedToTangent(site.latDeg, site.lonDeg) * bodyFixed;
}

std::string terrainNumber(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

void writeVti(const std::string& path, vtkImageData* result) {
  output::OutputFile out(path);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(result);
  writer->SetFileName(out.tempPath().c_str());
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) throw CommandError(path + ": cannot write");
  out.commit();
}

} // namespace umbra::cli
