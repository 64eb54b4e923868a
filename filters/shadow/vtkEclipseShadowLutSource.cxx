#include "vtkEclipseShadowLutSource.h"

#include "SpreadTable.h"

#include "EclipseAtmosphere.hpp"
#include "Precompute.hpp"
#include "ShadowLutData.h"
#include "umbra/tables/CachedTables.h"

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>


vtkStandardNewMacro(vtkEclipseShadowLutSource);

vtkEclipseShadowLutSource::vtkEclipseShadowLutSource() = default;

void vtkEclipseShadowLutSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n"
     << indent << "LimbDarkening: " << this->LimbDarkening << "\n"
     << indent << "LimbSize: " << this->LimbSize << " ScatteringCells: " << this->ScatteringCells << "\n";
}

int vtkEclipseShadowLutSource::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                  vtkInformationVector* out) {
  SetLutInformation(out, this->Width, this->Height, 1, this->URange, this->VRange, this->VLowFraction);
  return 1;
}

int vtkEclipseShadowLutSource::RequestData(vtkInformation*, vtkInformationVector**,
                                           vtkInformationVector* out) {
  using namespace umbra;
  vtkImageData* output = vtkImageData::GetData(out);
  this->LastAborted = false;
  this->LastError.clear();
  if (this->HasAtmosphere()) return this->RequestAtmospheric(out->GetInformationObject(0), output);
  eclipse::ShadowLutParams params{this->Width, this->Height, this->LimbDarkening, this->RelativeTolerance};
  params.uMin = this->URange[0], params.uMax = this->URange[1];
  params.vMin = this->VRange[0], params.vMax = this->VRange[1], params.vLowFraction = this->VLowFraction;
  try {
    eclipse::checkLutRange(params.uMin, params.uMax, params.vMin, params.vMax, params.vLowFraction);
  } catch (const std::exception& e) {
    return this->RequestFailed(e, output);
  }
  const auto parameters = filters::airlessLutParameters(params);
  const tables::TableCache cache(this->CacheDirectory.empty() ? tables::TableCache::defaultDirectory()
                                                              : this->CacheDirectory);
  this->CachePath = cache.pathFor(filters::kAirlessShadowLutKind, parameters);
  this->LastCacheHit = false;
  this->CacheWarning.clear();
  eclipse::ShadowLut lut;
  try {
    tables::CacheOutcome outcome;
    const tables::Table made = filters::spreadOrCached(
        cache, this->UseCache != 0,
        {filters::kAirlessShadowLutKind, parameters, params.width, params.height, {"R", "G", "B"}},
        params.width * params.height, 1, this->SpreadOverRanks,
        [&](int index, int count) {
          this->UpdateProgress(0.0);
          const eclipse::ShadowLut built = eclipse::buildAirlessShadowLut(params, [this](double f) {
            this->UpdateProgress(f);
            return !this->GetAbortExecute();
          }, eclipse::TexelShare{index, count});
          if (built.rgb.empty()) throw atmosphere::PrecomputeCancelled();
          return filters::toTable(built, parameters);
        },
        outcome);
    this->LastCacheHit = outcome.hits > 0;
    this->CacheWarning = outcome.warning;
    lut = filters::fromTable(made, this->CachePath);
  } catch (const std::exception& e) {
    return this->RequestFailed(e, output);
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

int vtkEclipseShadowLutSource::RequestAtmospheric(vtkInformation* outInfo, vtkImageData* output) {
  using namespace umbra;
  try {
    int ext[6] = {0, this->Width - 1, 0, this->Height - 1, 0, 0};
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
    const eclipse::LutExtent extent{std::max(ext[0], 0), std::min(ext[1], this->Width - 1) + 1, std::max(ext[2], 0),
                                    std::min(ext[3], this->Height - 1) + 1};
    if (extent.empty()) throw std::invalid_argument("empty update extent");
    const bool whole = extent.uBegin == 0 && extent.vBegin == 0 && extent.uEnd == this->Width && extent.vEnd == this->Height;

    eclipse::AtmosphericShadowLutParams params;
    params.width = this->Width;
    params.height = this->Height;
    params.limb = {this->LimbSize, this->LimbSize, this->ScatteringCells, this->ScatteringCells};
    params.uMin = this->URange[0], params.uMax = this->URange[1];
    params.vMin = this->VRange[0], params.vMax = this->VRange[1], params.vLowFraction = this->VLowFraction;
    eclipse::checkLutRange(params.uMin, params.uMax, params.vMin, params.vMax, params.vLowFraction);
    auto parameters = this->AtmosphereParameters();
    parameters["kind"] = filters::kAtmosphereShadowLutKind;
    parameters["model"] = "limb views of the refracted Sun and in-scattered light + direct light past r_atmo (eclipse paper 5.2), rows integrated by sub-rows; v2";
    parameters["width"] = std::to_string(this->Width);
    parameters["height"] = std::to_string(this->Height);
    parameters["limbView"] = std::to_string(this->LimbSize) + "x" + std::to_string(this->LimbSize) + " scattering " +
                             std::to_string(this->ScatteringCells) + "x" + std::to_string(this->ScatteringCells);
    parameters["limbDarkening"] = filters::formatNumber(this->LimbDarkening);
    parameters["occluder"] = this->OccluderName;
    parameters["values"] = "I/I_sun (R, G, B: 680, 550, 440 nm) at texel centres u=(i+0.5)/width, v=(j+0.5)/height (Eq. 4)";
    filters::addLutRange(parameters, {params.uMin, params.uMax, params.vMin, params.vMax, params.vLowFraction});
    if (!whole)
      parameters["extent"] = std::to_string(extent.uBegin) + " " + std::to_string(extent.uEnd) + " " +
                             std::to_string(extent.vBegin) + " " + std::to_string(extent.vEnd);
    eclipse::ShadowLut lut;
    lut.width = extent.uEnd - extent.uBegin;
    lut.height = extent.vEnd - extent.vBegin;
    lut.rgb = this->CachedOrComputed(
        filters::kAtmosphereShadowLutKind, parameters, lut.width, lut.height, 1, this->LimbDarkening,
        [&](const eclipse::AtmosphericShadowModel& model, const eclipse::Progress& progress,
            const eclipse::TexelShare& share) {
          return eclipse::buildAtmosphericShadowLut(model, params, extent, progress, share).rgb;
        });
    vtkSmartPointer<vtkImageData> image = filters::toImageData(lut);
    output->ShallowCopy(image);
    output->SetExtent(extent.uBegin, extent.uEnd - 1, extent.vBegin, extent.vEnd - 1, 0, 0);
    double spacing[3], origin[3];
    LutSpacingOrigin(this->Width, this->Height, this->URange, this->VRange, this->VLowFraction, spacing, origin);
    output->SetSpacing(spacing);
    output->SetOrigin(origin);
    parameters["sunRadiusM"] = filters::formatNumber(this->SunRadiusM);
    filters::setFieldParameters(output, parameters);
  } catch (const std::exception& e) {
    return this->RequestFailed(e, output);
  }
  this->UpdateProgress(1.0);
  return 1;
}
