#include "vtkEclipseShadowLutSource.h"

#include "ShadowLutData.h"
#include "umbra/tables/TableCache.h"

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>


vtkStandardNewMacro(vtkEclipseShadowLutSource);

vtkEclipseShadowLutSource::vtkEclipseShadowLutSource() { this->SetNumberOfInputPorts(0); }

void vtkEclipseShadowLutSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n"
     << indent << "LimbDarkening: " << this->LimbDarkening << "\n"
     << indent << "Occluder: " << this->OccluderName << " (" << this->OccluderRadiusM << " m)\n"
     << indent << "UseCache: " << this->UseCache << " " << this->CacheDirectory << "\n";
}

int vtkEclipseShadowLutSource::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                  vtkInformationVector* out) {
  vtkInformation* info = out->GetInformationObject(0);
  const int extent[6] = {0, this->Width - 1, 0, this->Height - 1, 0, 0};
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = {1.0 / this->Width, 1.0 / this->Height, 1.0};
  const double origin[3] = {0.5 / this->Width, 0.5 / this->Height, 0.0};
  info->Set(vtkDataObject::SPACING(), spacing, 3);
  info->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 3);
  return 1;
}

int vtkEclipseShadowLutSource::RequestData(vtkInformation*, vtkInformationVector**,
                                           vtkInformationVector* out) {
  using namespace umbra;
  vtkImageData* output = vtkImageData::GetData(out);
  const eclipse::ShadowLutParams params{this->Width, this->Height, this->LimbDarkening, this->RelativeTolerance};
  const auto parameters = filters::airlessLutParameters(params);
  const tables::TableCache cache(this->CacheDirectory.empty() ? tables::TableCache::defaultDirectory()
                                                              : this->CacheDirectory);
  this->LastCacheHit = false;
  this->CacheWarning.clear();
  this->CachePath = cache.pathFor(filters::kAirlessShadowLutKind, parameters);

  eclipse::ShadowLut lut;
  if (this->UseCache) {
    if (auto table = cache.load(filters::kAirlessShadowLutKind, parameters)) {
      try {
        lut = filters::fromTable(*table, this->CachePath);
        this->LastCacheHit = true;
      } catch (const std::exception&) {
        // not a LuT after all: computed again below and overwritten
      }
    }
  }
  if (!this->LastCacheHit) {
    this->UpdateProgress(0.0);
    lut = eclipse::buildAirlessShadowLut(params, [this](double f) {
      this->UpdateProgress(f);
      return !this->GetAbortExecute();
    });
    if (lut.rgb.empty()) {
      vtkErrorMacro("shadow LuT computation was aborted");
      return 0;
    }
    if (this->UseCache) {
      try {
        cache.store(filters::kAirlessShadowLutKind, parameters, filters::toTable(lut, parameters));
      } catch (const std::exception& e) {
        this->CacheWarning = e.what();
      }
    }
  }

  output->ShallowCopy(filters::toImageData(lut));
  auto fieldParameters = parameters;
  fieldParameters["occluder"] = this->OccluderName;
  fieldParameters["occluderRadiusM"] = filters::formatNumber(this->OccluderRadiusM);
  fieldParameters["sunRadiusM"] = filters::formatNumber(this->SunRadiusM);
  fieldParameters["sunOccluderDistanceM"] = filters::formatNumber(this->SunOccluderDistanceM);
  filters::setFieldParameters(output, fieldParameters);
  this->UpdateProgress(1.0);
  return 1;
}
