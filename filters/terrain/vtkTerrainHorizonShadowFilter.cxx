#include "vtkTerrainHorizonShadowFilter.h"

#include "SoftShadow.hpp"
#include "TerrainImageData.h"

#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

#include <cmath>

vtkStandardNewMacro(vtkTerrainHorizonShadowFilter);

void vtkTerrainHorizonShadowFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SunDirection: " << this->SunDirection[0] << " " << this->SunDirection[1] << " "
     << this->SunDirection[2] << "\n"
     << indent << "Method: " << this->Method << " Levels: " << this->Levels << "\n";
}

void vtkTerrainHorizonShadowFilter::SetSunElevationAzimuthDeg(double e, double a) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  const glm::dvec3 d = umbra::terrain::sunDirectionFromElevationAzimuth(e * deg, a * deg);
  this->SetSunDirection(d.x, d.y, d.z);
}

void vtkTerrainHorizonShadowFilter::SetNoDataValue(double value) {
  if (this->HasNoDataValue && this->NoDataValue == value) return;
  this->HasNoDataValue = true;
  this->NoDataValue = value;
  this->Modified();
}

void vtkTerrainHorizonShadowFilter::ClearNoDataValue() {
  if (!this->HasNoDataValue) return;
  this->HasNoDataValue = false;
  this->Modified();
}

int vtkTerrainHorizonShadowFilter::RequestData(vtkInformation*, vtkInformationVector** in, vtkInformationVector* out) {
  using namespace umbra;
  vtkImageData* input = vtkImageData::GetData(in[0]);
  vtkImageData* output = vtkImageData::GetData(out);
  try {
    const terrain::HeightField field = filters::heightFieldFromImage(
        input, this->HeightArrayName, this->BodyRadiusM,
        this->HasNoDataValue ? std::optional<double>(this->NoDataValue) : std::nullopt);
    const terrain::MaximumMipmap mip(field);
    terrain::SunDisc sun;
    sun.direction = {this->SunDirection[0], this->SunDirection[1], this->SunDirection[2]};
    sun.angularRadiusRad = this->SunAngularRadiusRad;
    sun.limbDarkening = this->LimbDarkening;
    terrain::ShadowOptions options;
    options.method = static_cast<terrain::ShadowMethod>(this->Method);
    options.levels = this->Levels;
    options.uniformSteps = this->UniformSteps;
    options.referenceStrips = this->ReferenceStrips;
    options.referenceStepTexels = this->ReferenceStepTexels;
    this->UpdateProgress(0.0);
    terrain::ShadowMapStats stats;
    const std::vector<double> fraction =
        terrain::visibleFractionMap(field, mip, sun, options, [this](double f) { this->UpdateProgress(f); }, &stats);
    this->SamplesLookedAt = stats.samples;

    output->ShallowCopy(input);
    auto array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName("visible_solar_fraction");
    array->SetNumberOfTuples(static_cast<vtkIdType>(fraction.size()));
    for (std::size_t k = 0; k < fraction.size(); ++k) array->SetValue(static_cast<vtkIdType>(k), fraction[k]);
    output->GetPointData()->AddArray(array);
    this->UpdateProgress(1.0);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
