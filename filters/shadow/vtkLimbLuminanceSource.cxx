#include "vtkLimbLuminanceSource.h"

#include "EclipseAtmosphere.hpp"
#include "ShadowLutData.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

vtkStandardNewMacro(vtkLimbLuminanceSource);

void vtkLimbLuminanceSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << " x (" << this->Columns << " x " << this->Layers
     << ")\n";
}

int vtkLimbLuminanceSource::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) {
  SetLutInformation(out, this->Width, this->Height, this->Columns * this->Layers, this->URange, this->VRange,
                    this->VLowFraction);
  return 1;
}

int vtkLimbLuminanceSource::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) {
  using namespace umbra;
  vtkImageData* output = vtkImageData::GetData(out);
  this->LastAborted = false;
  this->LastError.clear();
  try {
    if (!this->HasAtmosphere()) throw std::invalid_argument("the limb-luminance LuT needs an atmosphere");
    if (this->Layers > this->LimbRows) throw std::invalid_argument("more layers than limb-view rows");
    eclipse::LimbLuminanceLutParams params;
    params.width = this->Width, params.height = this->Height, params.columns = this->Columns;
    params.layers = this->Layers;
    params.limb = {this->Columns, this->LimbRows, this->ScatteringCells, this->ScatteringCells};
    params.range = this->GetLutRange();
    eclipse::checkLutRange(params.range.uMin, params.range.uMax, params.range.vMin, params.range.vMax,
                           params.range.vLowFraction);
    auto parameters = this->AtmosphereParameters();
    parameters["kind"] = filters::kLimbLuminanceLutKind;
    parameters["model"] = "limb views averaged to layers (eclipse paper 5.3), rows integrated by sub-rows; v2";
    parameters["size"] = std::to_string(this->Width) + "x" + std::to_string(this->Height) + "x" +
                         std::to_string(this->Columns) + "x" + std::to_string(this->Layers);
    parameters["limbView"] = std::to_string(this->LimbRows) + " rows, scattering " +
                             std::to_string(this->ScatteringCells) + "x" + std::to_string(this->ScatteringCells);
    parameters["limbDarkening"] = filters::formatNumber(this->LimbDarkening);
    parameters["occluder"] = this->OccluderName;
    parameters["layout"] = "x = u index, y = v index + height * (layer * columns + column): the slices stacked";
    parameters["values"] = "radiance per unit solar irradiance [1/sr], R, G, B = 680, 550, 440 nm";
    filters::addLutRange(parameters, params.range);
    const int depth = this->Columns * this->Layers;
    const std::vector<float> rgb = this->CachedOrComputed(
        filters::kLimbLuminanceLutKind, parameters, this->Width, this->Height * depth, depth, this->LimbDarkening,
        [&](const eclipse::AtmosphericShadowModel& model, const eclipse::Progress& progress,
            const eclipse::TexelShare& share) { return eclipse::buildLimbLuminanceLut(model, params, progress, share).rgb; });
    output->SetDimensions(this->Width, this->Height, depth);
    double spacing[3], origin[3];
    LutSpacingOrigin(this->Width, this->Height, this->URange, this->VRange, this->VLowFraction, spacing, origin);
    output->SetSpacing(spacing);
    output->SetOrigin(origin);
    auto values = vtkSmartPointer<vtkFloatArray>::New();
    values->SetName("L_over_Esun");
    values->SetNumberOfComponents(3);
    values->SetNumberOfTuples(static_cast<vtkIdType>(rgb.size() / 3));
    std::copy(rgb.begin(), rgb.end(), values->GetPointer(0));
    output->GetPointData()->SetScalars(values);
    filters::setFieldParameters(output, parameters);
  } catch (const std::exception& e) {
    return this->RequestFailed(e, output);
  }
  this->UpdateProgress(1.0);
  return 1;
}
