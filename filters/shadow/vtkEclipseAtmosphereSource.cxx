#include "vtkEclipseAtmosphereSource.h"

#include "EclipseAtmosphere.hpp"
#include "Spectrum.hpp"
#include "umbra/tables/TableCache.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <mutex>
#include <stdexcept>

namespace {

std::vector<double> wavelengthsOf(int n) {
  using umbra::atmosphere::WavelengthSet;
  return n == 3 ? WavelengthSet::rgb().nm : WavelengthSet::uniform(n).nm;
}

std::string keyOf(const std::map<std::string, std::string>& parameters) {
  std::string key;
  for (const auto& [k, v] : parameters) key += k + "=" + v + "\n";
  return key;
}

} // namespace

vtkEclipseAtmosphereSource::vtkEclipseAtmosphereSource() { this->SetNumberOfInputPorts(0); }

void vtkEclipseAtmosphereSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Occluder: " << this->OccluderName << " (" << this->OccluderRadiusM << " m)\n"
     << indent << "Atmosphere: " << (this->Atmosphere.empty() ? "(none)" : this->Atmosphere) << "\n"
     << indent << "Refraction: " << this->Refraction << "\n"
     << indent << "UseCache: " << this->UseCache << " " << this->CacheDirectory << "\n";
}

umbra::eclipse::EclipseAtmosphereOptions vtkEclipseAtmosphereSource::Options() const {
  umbra::eclipse::EclipseAtmosphereOptions o;
  o.tables.orders = this->Orders;
  o.tables.transmittanceWidth = this->TransmittanceSize[0];
  o.tables.transmittanceHeight = this->TransmittanceSize[1];
  o.tables.scatteringR = this->ScatteringSize[0];
  o.tables.scatteringMu = this->ScatteringSize[1];
  o.tables.scatteringMuS = this->ScatteringSize[2];
  o.tables.scatteringNu = this->ScatteringSize[3];
  o.tables.irradianceWidth = this->IrradianceSize[0];
  o.tables.irradianceHeight = this->IrradianceSize[1];
  o.refraction = this->Refraction;
  o.refractionWidth = this->RefractionSize[0];
  o.refractionHeight = this->RefractionSize[1];
  o.refractionStepM = this->RefractionStepM;
  o.terrainMeanElevationM = this->TerrainMeanElevationM;
  if (const std::string e = o.tables.validate(); !e.empty()) throw std::invalid_argument("atmosphere tables: " + e);
  return o;
}

std::map<std::string, std::string> vtkEclipseAtmosphereSource::AtmosphereParameters() const {
  const umbra::atmosphere::Atmosphere atm = umbra::atmosphere::loadAtmosphere(this->Atmosphere, wavelengthsOf(this->Wavelengths));
  return umbra::eclipse::eclipseAtmosphereParameters(atm, this->OccluderName, this->SunOccluderDistanceM, this->Options());
}

std::shared_ptr<const umbra::eclipse::EclipseAtmosphere> vtkEclipseAtmosphereSource::PrepareAtmosphere(double from,
                                                                                                      double to) {
  using namespace umbra;
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<const eclipse::EclipseAtmosphere>> prepared;
  const atmosphere::Atmosphere atm = atmosphere::loadAtmosphere(this->Atmosphere, wavelengthsOf(this->Wavelengths));
  const eclipse::EclipseAtmosphereOptions options = this->Options();
  const std::string key =
      keyOf(eclipse::eclipseAtmosphereParameters(atm, this->OccluderName, this->SunOccluderDistanceM, options));
  std::lock_guard<std::mutex> lock(mutex);
  if (auto kept = prepared[key].lock()) return this->Prepared = kept;
  std::shared_ptr<const eclipse::EclipseAtmosphere> made = eclipse::prepareEclipseAtmosphere(
      atm, this->OccluderName, this->SunOccluderDistanceM, options, [&](double f, const std::string&) {
        this->UpdateProgress(from + (to - from) * f);
        return !this->GetAbortExecute();
      });
  prepared[key] = made;
  return this->Prepared = made;
}

std::vector<float> vtkEclipseAtmosphereSource::CachedOrComputed(const char* kind,
                                                                const std::map<std::string, std::string>& parameters,
                                                                int width, int height, double limbDarkening,
                                                                const Compute& compute) {
  using namespace umbra;
  this->LastCacheHit = false;
  this->CacheWarning.clear();
  const tables::TableCache cache(this->CacheDirectory.empty() ? tables::TableCache::defaultDirectory()
                                                              : this->CacheDirectory);
  this->CachePath = cache.pathFor(kind, parameters);
  const std::vector<std::string> rgb = {"R", "G", "B"};
  if (this->UseCache)
    if (auto table = cache.load(kind, parameters))
      if (table->width == width && table->height == height && table->channels == rgb) {
        this->LastCacheHit = true;
        return table->data;
      }
  this->UpdateProgress(0.0);
  eclipse::AtmosphericShadowModel model = this->PrepareAtmosphere(0.0, 0.5)->model;
  model.limbDarkening = limbDarkening;
  tables::Table t;
  t.width = width, t.height = height, t.channels = rgb;
  t.data = compute(model, [this](double f) {
    this->UpdateProgress(0.5 + 0.5 * f);
    return !this->GetAbortExecute();
  });
  if (t.data.empty()) throw std::runtime_error(std::string(kind) + ": computation aborted");
  if (this->UseCache) {
    try {
      cache.store(kind, parameters, t);
    } catch (const std::exception& e) {
      this->CacheWarning = e.what();
    }
  }
  return t.data;
}

void vtkEclipseAtmosphereSource::SetLutInformation(vtkInformationVector* out, int width, int height, int depth,
                                                   const double uRange[2], const double vRange[2],
                                                   double vLowFraction) {
  vtkInformation* info = out->GetInformationObject(0);
  const int extent[6] = {0, width - 1, 0, height - 1, 0, depth - 1};
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double uMin = uRange ? uRange[0] : 0.0, uMax = uRange ? uRange[1] : 1.0;
  const bool split = vLowFraction > 0.0;
  const double vMin = vRange && !split ? vRange[0] : 0.0, vMax = vRange && !split ? vRange[1] : 1.0;
  const double du = (uMax - uMin) / width, dv = (vMax - vMin) / height;
  const double spacing[3] = {du, dv, 1.0};
  const double origin[3] = {uMin + 0.5 * du, vMin + 0.5 * dv, 0.0};
  info->Set(vtkDataObject::SPACING(), spacing, 3);
  info->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 3);
}
