#include "ShadowCommon.hpp"
#include "vtkAtmosphereTablesSource.h"

#include "ShadowLutData.h"
#include "scene/Bodies.hpp"
#include "umbra/tables/Exr.h"
#include "scene/Scene.hpp"
#include "scene/Time.hpp"
#include "scene/Units.hpp"
#include "Atmosphere.hpp"
#include "EclipseAtmosphere.hpp"
#include "Spectrum.hpp"
#include "vtkEclipseShadowLutSource.h"

#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkTable.h>

#include <cstdio>
#include <regex>
#include <iostream>

namespace umbra::cli {

double lengthOption(const std::string& option, const std::string& text) {
  try {
    return scene::parseLengthM(text);
  } catch (const std::exception& e) {
    throw CommandError(option + ": " + e.what());
  }
}

double lengthOption(const std::string& option, const std::string& text, double minM, double maxM) {
  const double m = lengthOption(option, text);
  if (!(m >= minM && m <= maxM)) {
    char range[96];
    std::snprintf(range, sizeof range, "a length from %.6g m to %.6g m", minM, maxM);
    throw CommandError(option + ": expected " + range + ", got " + text);
  }
  return m;
}

SceneShadow sceneShadow(const std::string& scenePath, const std::string& time) {
  scene::Scene s = scene::loadScene(scenePath);
  if (!time.empty()) {
    try {
      scene::setTime(s, scene::parseUtc(time));
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("--time: ") + e.what());
    }
  }
  SceneShadow out;
  out.geometry = scene::receiverShadow(s);
  if (!out.geometry.valid) throw CommandError(scenePath + ": " + out.geometry.why);
  const scene::Body& occ = *s.find(out.geometry.occluder);
  out.occluder = {occ.name, occ.radiusM, out.geometry.sunOccluderDistanceM, occ.hasAtmosphere};
  out.lutSize = s.shadowLutSize;
  return out;
}

OccluderChoice chooseOccluder(const std::string& name, const std::string& radius, const std::string& sunDistance) {
  const scene::BodyPreset* preset = scene::findPreset(name);
  if (!preset) throw CommandError("--occluder: unknown body '" + name + "' (known: " + scene::presetNameList() + ")");
  if (preset->name == "Sun") throw CommandError("--occluder: the Sun cannot occlude itself");
  OccluderChoice c{preset->name, preset->meanRadiusM, scene::meanDistanceFromSunM(*preset), preset->hasAtmosphere};
  if (!radius.empty()) {
    if (!(lengthOption("--occluder-radius", radius) > 0.0))
      throw CommandError("--occluder-radius: expected a positive length, got " + radius);
    c.radiusM = lengthOption("--occluder-radius", radius, 1.0, kMaxRadiusM);
  }
  if (!sunDistance.empty()) {
    if (!(lengthOption("--sun-distance", sunDistance) > 0.0))
      throw CommandError("--sun-distance: expected a positive length, got " + sunDistance);
    // Beyond the Sun's surface and the occluder's.
    c.sunDistanceM = lengthOption("--sun-distance", sunDistance, eclipse::kSunRadiusM + c.radiusM, kMaxDistanceM);
  }
  return c;
}

void EclipseAtmosphereChoice::addTo(CLI::App* command) {
  std::string presets;
  for (const auto& p : atmosphere::presetNames()) presets += (presets.empty() ? "" : ", ") + p;
  command->add_option("--atmosphere", atmosphere,
                      "The occluder's atmosphere: a preset (" + presets +
                          ") or a JSON file; refracted and scattered light then reach into the shadow");
  command->add_option("--limb-size", limbSize, "Rows and columns of the limb view rendered per shadow-LuT texel")
      ->capture_default_str()->check(CLI::Range(4, 4096));
  command->add_option("--scattering-cells", scatteringCells,
                      "Cells (a side) of a limb view on which the in-scattered light is sampled")
      ->capture_default_str()->check(CLI::Range(1, 1024));
  command->add_option("--orders", orders, "Scattering orders of the atmosphere tables")
      ->capture_default_str()->check(CLI::Range(1, atmosphere::kMaxOrders));
  const atmosphere::TableSizes& small = atmosphere::kSmallTableSizes;
  command->add_flag("--draft-tables", draftTables,
                    "Small atmosphere tables (transmittance " + atmosphere::sizeText(small.transmittance) +
                        ", scattering " + atmosphere::sizeText(small.scattering) + ", irradiance " +
                        atmosphere::sizeText(small.irradiance) + ", refraction " + atmosphere::sizeText(small.refraction) +
                        "): seconds instead of minutes, for quick looks and tests");
  command->add_option("--scattering-nu", scatteringNu,
                      "Cells in nu (cosine of the view-sun angle) of the scattering tables (default " +
                          std::to_string(atmosphere::kDefaultTableSizes.scattering[3]) + ", draft " +
                          std::to_string(small.scattering[3]) + "; "
                      "32 for Mars, whose forward-peaked dust needs them: with 8 the multiple scattering at "
                      "~20 degrees is interpolated from the forward peak, docs/eclipse-shadows.md)")
      ->check(CLI::Range(2, 256));
}

atmosphere::AtmosphereModelPtr EclipseAtmosphereChoice::model() const {
  try {
    return atmosphere::modelNamed(atmosphere, read);
  } catch (const std::exception& e) {
    throw CommandError(std::string("--atmosphere: ") + e.what());
  }
}

double EclipseAtmosphereChoice::bottomRadiusM() const {
  const atmosphere::AtmosphereModelPtr m = model();
  if (!m) throw CommandError("--atmosphere: none given");
  return m->rgb().bottomRadiusM;
}

void EclipseAtmosphereChoice::configure(vtkEclipseAtmosphereSource* source, const OccluderChoice& occ) const {
  source->SetOccluderName(occ.name.c_str());
  source->SetOccluderRadiusM(occ.radiusM);
  source->SetSunOccluderDistanceM(occ.sunDistanceM);
  source->SetAtmosphereModel(model());
  source->SetOrders(orders);
  const atmosphere::TableSizes& s = draftTables ? atmosphere::kSmallTableSizes : atmosphere::kDefaultTableSizes;
  if (draftTables) {
    source->SetTransmittanceSize(s.transmittance[0], s.transmittance[1]);
    source->SetIrradianceSize(s.irradiance[0], s.irradiance[1]);
    source->SetRefractionSize(s.refraction[0], s.refraction[1]);
  }
  // 0: the occluder's default (eclipse::defaultScatteringNu; the draft tables' where it is
  // the default tables').
  const int nu = scatteringNu > 0 ? scatteringNu : draftTables ? eclipse::defaultScatteringNu(occ.name, s.scattering[3]) : 0;
  source->SetScatteringSize(s.scattering[0], s.scattering[1], s.scattering[2], nu);
}

void updateEclipseSource(vtkEclipseAtmosphereSource* source, const std::string& what, const CacheOptions& cache) {
  source->SetCacheDirectory(cache.directory.c_str());
  source->SetUseCache(!cache.disabled);
  source->SetSpreadOverRanks(cache.overRanks);
  // The Bruneton and refraction tables from their cache; a failure there is the reason.
  auto* tables = vtkAtmosphereTablesSource::SafeDownCast(source->ConnectAtmosphereTables());
  if (tables) tables->SetSpreadOverRanks(cache.overRanks);  // their wavelengths shared too
  ProgressLine progress(what, source);
  source->Update();
  if (source->GetOutput()->GetNumberOfPoints() == 0) {
    std::string why = source->GetLastError();
    if (why.empty() && tables && !tables->GetLastError().empty()) why = "atmosphere tables: " + tables->GetLastError();
    throw CommandError("the " + what + " could not be computed" + (why.empty() ? std::string() : ": " + why));
  }
  if (source->GetLastUpdateWasCacheHit())
    std::cerr << "cache hit: " << source->GetCachePath() << "\n";
  else if (!cache.disabled && source->GetCacheWarning().empty())
    std::cerr << "cached: " << source->GetCachePath() << "\n";
  if (!source->GetCacheWarning().empty())
    std::cerr << "umbra: warning: could not cache the table: " << source->GetCacheWarning() << "\n";
}

vtkSmartPointer<vtkTable> atmosphericProfile(const EclipseAtmosphereChoice& atmosphere, const OccluderChoice& occ,
                                             double distanceM, double maxOffsetM, int samples, double limbDarkening) {
  return filters::profileTable(atmosphericProfileSamples(atmosphere, occ, distanceM, maxOffsetM, samples, limbDarkening));
}

std::vector<eclipse::ProfileSample> atmosphericProfileSamples(const EclipseAtmosphereChoice& atmosphere,
                                                              const OccluderChoice& occ, double distanceM,
                                                              double maxOffsetM, int samples, double limbDarkening) {
  auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  atmosphere.configure(source, occ);
  ProgressLine progress("atmosphere tables " + atmosphere.atmosphere, source);
  std::shared_ptr<const eclipse::EclipseAtmosphere> prepared;
  try {
    prepared = source->GetPreparedAtmosphere();
  } catch (const std::exception& e) {
    throw CommandError(std::string("--atmosphere: ") + e.what());
  }
  eclipse::AtmosphericShadowModel model = prepared->model;
  model.limbDarkening = limbDarkening;
  if (atmosphere.cloudCover > 0.0) eclipse::screenByClouds(model.rays, atmosphere.cloudTopM, atmosphere.cloudCover);
  if (!(maxOffsetM > 0.0)) maxOffsetM = 1.25 * eclipse::shadowConeRadii(model.system, distanceM).penumbraRadiusM;
  const eclipse::LimbViewParams limb{atmosphere.limbSize, atmosphere.limbSize, atmosphere.scatteringCells,
                                     atmosphere.scatteringCells};
  return eclipse::atmosphericShadowProfile(model, distanceM, maxOffsetM, samples, nullptr, limb);
}

eclipse::LutRange distanceRangeOption(const std::string& text, const OccluderChoice& occ, bool darkUmbra, int size) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw CommandError("--distance-range: expected MIN:MAX (e.g. 9000km:9800km), got " + text);
  const double lo = lengthOption("--distance-range", text.substr(0, colon));
  const double hi = lengthOption("--distance-range", text.substr(colon + 1));
  try {
    return eclipse::lutRangeForDistances({eclipse::kSunRadiusM, occ.radiusM, occ.sunDistanceM}, lo, hi, darkUmbra, size);
  } catch (const std::invalid_argument& e) {
    throw CommandError("--distance-range: " + std::string(e.what()) + " (got " + text + ")");
  }
}

void addDistanceRangeOption(CLI::App* command, std::string& text) {
  command->add_option("--distance-range", text,
                      "Receivers' distances from the occluder's centre, MIN:MAX (e.g. 9000km:9800km for Phobos): "
                      "the LuT covers only their u and v ranges, at full resolution (docs/eclipse-shadows.md)");
}

vtkSmartPointer<vtkEclipseShadowLutSource> updateShadowLut(int size, double limbDarkening, const CacheOptions& cache,
                                                           const OccluderChoice* occluder,
                                                           const EclipseAtmosphereChoice* atmosphere,
                                                           const eclipse::LutRange* range, int width) {
  auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  source->SetWidth(width > 0 ? width : size);
  source->SetHeight(size);
  source->SetLimbDarkening(limbDarkening);
  if (range) source->SetLutRange(*range);
  if (occluder) {
    source->SetOccluderName(occluder->name.c_str());
    source->SetOccluderRadiusM(occluder->radiusM);
    source->SetSunOccluderDistanceM(occluder->sunDistanceM);
  }
  std::string what = "shadow LuT " + std::to_string(source->GetWidth()) + "x" + std::to_string(size);
  if (range) {
    char u[64];
    std::snprintf(u, sizeof u, " (u %.6g..%.6g)", range->uMin, range->uMax);
    what += u;
  }
  if (atmosphere && !atmosphere->atmosphere.empty()) {
    if (!occluder) throw CommandError("an atmosphere needs an occluder");
    atmosphere->configure(source, *occluder);
    source->SetLimbSize(atmosphere->limbSize);
    source->SetScatteringCells(atmosphere->scatteringCells);
    what += " through the atmosphere " + atmosphere->atmosphere;
  }
  const bool warnings = vtkObject::GetGlobalWarningDisplay() != 0;
  vtkObject::GlobalWarningDisplayOff();  // a failure comes back as one line
  try {
    updateEclipseSource(source, what, cache);
  } catch (...) {
    vtkObject::SetGlobalWarningDisplay(warnings ? 1 : 0);
    throw;
  }
  vtkObject::SetGlobalWarningDisplay(warnings ? 1 : 0);
  return source;
}

vtkSmartPointer<vtkImageData> readShadowLut(const std::string& path) {
  const tables::Table table = tables::readExr(path, {"R", "G", "B"});
  const auto kind = table.parameters.find("kind");
  if (kind == table.parameters.end() ||
      (kind->second != filters::kAirlessShadowLutKind && kind->second != filters::kAtmosphereShadowLutKind))
    throw CommandError(path + ": not a shadow LuT (its header has no kind=" + filters::kAirlessShadowLutKind + " or " +
                       filters::kAtmosphereShadowLutKind + ")");
  auto image = filters::toImageData(filters::fromTable(table, path));
  filters::setFieldParameters(image, table.parameters);
  return image;
}

scene::Observer parseObserver(const std::string& text) {
  const std::string number = R"(\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*)";
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(number + "," + number + "(?:,([^,]+))?")))
    throw CommandError("--observer: expected LAT,LON[,ALT] (degrees north and east, an altitude such as 120m), got '" +
                       text + "'");
  scene::Observer o;
  o.body = "Earth";
  o.latDeg = std::stod(m[1]);
  o.lonDeg = std::stod(m[2]);
  if (!(o.latDeg >= -90.0 && o.latDeg <= 90.0))
    throw CommandError("--observer: latitude must be within -90..90 deg, got '" + m[1].str() + "'");
  if (!(o.lonDeg >= -360.0 && o.lonDeg <= 360.0))
    throw CommandError("--observer: longitude must be within -360..360 deg, got '" + m[2].str() + "'");
  if (m[3].matched) {
    std::string alt = m[3].str();
    if (std::regex_match(alt, std::regex(number))) alt += "m";  // a bare number: metres
    o.altM = lengthOption("--observer (altitude)", alt);
    if (!(o.altM >= -1.0e4 && o.altM <= 1.0e8))
      throw CommandError("--observer: altitude must be within -10 km..100000 km, got '" + m[3].str() + "'");
  }
  return o;
}

} // namespace umbra::cli
