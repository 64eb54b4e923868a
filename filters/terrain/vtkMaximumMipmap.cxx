#include "vtkMaximumMipmap.h"

#include "MaximumMipmap.hpp"
#include "TerrainImageData.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMaximumMipmap);

void vtkMaximumMipmap::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Level: " << this->Level << "\n";
}

int vtkMaximumMipmap::RequestInformation(vtkInformation*, vtkInformationVector** in, vtkInformationVector* out) {
  // The level's extent and spacing follow from the input's dimensions alone.
  vtkInformation* inInfo = in[0]->GetInformationObject(0);
  vtkInformation* outInfo = out->GetInformationObject(0);
  int extent[6];
  double spacing[3], origin[3];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  inInfo->Get(vtkDataObject::SPACING(), spacing);
  inInfo->Get(vtkDataObject::ORIGIN(), origin);
  int w = std::max(1, extent[1] - extent[0]), h = std::max(1, extent[3] - extent[2]);  // cells
  int level = 0;
  for (; level < this->Level && (w > 1 || h > 1); ++level) w = (w + 1) / 2, h = (h + 1) / 2;
  const double block = std::ldexp(1.0, level);
  const int outExtent[6] = {0, w - 1, 0, h - 1, 0, 0};
  const double outSpacing[3] = {spacing[0] * block, spacing[1] * block, 1.0};
  const double outOrigin[3] = {origin[0] + extent[0] * spacing[0] + 0.5 * outSpacing[0],
                               origin[1] + extent[2] * spacing[1] + 0.5 * outSpacing[1], origin[2]};
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), outExtent, 6);
  outInfo->Set(vtkDataObject::SPACING(), outSpacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), outOrigin, 3);
  return 1;
}

int vtkMaximumMipmap::RequestData(vtkInformation*, vtkInformationVector** in, vtkInformationVector* out) {
  using namespace umbra;
  vtkImageData* input = vtkImageData::GetData(in[0]);
  vtkImageData* output = vtkImageData::GetData(out);
  try {
    // The spacing does not matter to the maxima; any radius makes a valid field.
    terrain::HeightField field = filters::heightFieldFromImage(input, this->HeightArrayName, 1e12);
    const terrain::MaximumMipmap mip(field);
    const int level = std::min(this->Level, mip.levels() - 1);
    double spacing[3], origin[3];
    input->GetSpacing(spacing);
    input->GetOrigin(origin);
    const double block = std::ldexp(1.0, level);
    output->SetDimensions(mip.width(level), mip.height(level), 1);
    output->SetSpacing(spacing[0] * block, spacing[1] * block, 1.0);
    output->SetOrigin(origin[0] + 0.5 * spacing[0] * block, origin[1] + 0.5 * spacing[1] * block, origin[2]);
    auto maxima = vtkSmartPointer<vtkDoubleArray>::New();
    maxima->SetName("max_height_m");
    const std::vector<double>& values = mip.level(level);
    maxima->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    for (std::size_t k = 0; k < values.size(); ++k) maxima->SetValue(static_cast<vtkIdType>(k), values[k]);
    output->GetPointData()->SetScalars(maxima);
    auto levels = vtkSmartPointer<vtkIntArray>::New();
    levels->SetName("levels");
    levels->InsertNextValue(mip.levels());
    output->GetFieldData()->AddArray(levels);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
