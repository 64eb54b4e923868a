#include "ShadowCommon.hpp"

#include "ShadowLutData.h"
#include "scene/Bodies.hpp"
#include "umbra/tables/Exr.h"
#include "scene/Scene.hpp"
#include "scene/Time.hpp"
#include "scene/Units.hpp"
#include "vtkEclipseShadowLutSource.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>

#include <iostream>

namespace umbra::cli {

double lengthOption(const std::string& option, const std::string& text) {
  try {
    return scene::parseLengthM(text);
  } catch (const std::exception& e) {
    throw CommandError(option + ": " + e.what());
  }
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
  if (!radius.empty()) c.radiusM = lengthOption("--occluder-radius", radius);
  if (!sunDistance.empty()) c.sunDistanceM = lengthOption("--sun-distance", sunDistance);
  if (!(c.radiusM > 0.0)) throw CommandError("--occluder-radius: expected a positive length, got " + radius);
  if (!(c.sunDistanceM > 0.0)) throw CommandError("--sun-distance: expected a positive length, got " + sunDistance);
  return c;
}

vtkSmartPointer<vtkEclipseShadowLutSource> updateShadowLut(int size, double limbDarkening, const CacheOptions& cache,
                                                           const OccluderChoice* occluder) {
  auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  source->SetWidth(size);
  source->SetHeight(size);
  source->SetLimbDarkening(limbDarkening);
  if (occluder) {
    source->SetOccluderName(occluder->name.c_str());
    source->SetOccluderRadiusM(occluder->radiusM);
    source->SetSunOccluderDistanceM(occluder->sunDistanceM);
  }
  source->SetCacheDirectory(cache.directory.c_str());
  source->SetUseCache(!cache.disabled);

  ProgressLine progress("shadow LuT " + std::to_string(size) + "x" + std::to_string(size));
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&progress);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
    static_cast<ProgressLine*>(client)->update(*static_cast<double*>(data));
  });
  source->AddObserver(vtkCommand::ProgressEvent, onProgress);
  source->Update();
  if (source->GetOutput()->GetNumberOfPoints() == 0) throw CommandError("the shadow LuT could not be computed");
  if (source->GetLastUpdateWasCacheHit())
    std::cerr << "cache hit: " << source->GetCachePath() << "\n";
  else if (!cache.disabled && source->GetCacheWarning().empty())
    std::cerr << "cached: " << source->GetCachePath() << "\n";
  if (!source->GetCacheWarning().empty())
    std::cerr << "umbra: warning: could not cache the table: " << source->GetCacheWarning() << "\n";
  return source;
}

vtkSmartPointer<vtkImageData> readShadowLut(const std::string& path) {
  const tables::Table table = tables::readExr(path, {"R", "G", "B"});
  const auto kind = table.parameters.find("kind");
  if (kind == table.parameters.end() || kind->second != filters::kAirlessShadowLutKind)
    throw CommandError(path + ": not a shadow LuT (its header has no kind=" + filters::kAirlessShadowLutKind + ")");
  auto image = filters::toImageData(filters::fromTable(table, path));
  filters::setFieldParameters(image, table.parameters);
  return image;
}

} // namespace umbra::cli
