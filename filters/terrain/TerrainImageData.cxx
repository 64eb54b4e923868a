#include "TerrainImageData.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace umbra::filters {

terrain::HeightField heightFieldFromImage(vtkImageData* image, const std::string& arrayName, double bodyRadiusM,
                                          std::optional<double> noDataValue) {
  if (!image) throw std::invalid_argument("DEM: no image");
  int dims[3];
  image->GetDimensions(dims);
  if (dims[2] != 1 || dims[0] < 2 || dims[1] < 2)
    throw std::invalid_argument("DEM: expected a 2D image of at least 2 x 2 samples, got " + std::to_string(dims[0]) +
                                " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]));
  double spacing[3];
  image->GetSpacing(spacing);
  if (!(spacing[0] > 0.0) || std::abs(spacing[0] - spacing[1]) > 1e-9 * spacing[0])
    throw std::invalid_argument("DEM: x and y spacing must be equal and positive (got " + std::to_string(spacing[0]) +
                                " and " + std::to_string(spacing[1]) + " m)");
  vtkDataArray* heights = arrayName.empty() ? image->GetPointData()->GetScalars()
                                            : image->GetPointData()->GetArray(arrayName.c_str());
  if (!heights)
    throw std::invalid_argument(arrayName.empty() ? "DEM: no point scalars (heights)"
                                                  : "DEM: no point array '" + arrayName + "'");
  if (heights->GetNumberOfComponents() != 1) throw std::invalid_argument("DEM: the height array must have one component");
  terrain::HeightField f;
  f.width = dims[0];
  f.height = dims[1];
  f.spacingM = spacing[0];
  f.bodyRadiusM = bodyRadiusM;
  f.heightsM.resize(static_cast<std::size_t>(dims[0]) * dims[1]);
  for (vtkIdType k = 0; k < static_cast<vtkIdType>(f.heightsM.size()); ++k) {
    double h = heights->GetTuple1(k);
    if (noDataValue && h == *noDataValue) h = std::numeric_limits<double>::quiet_NaN();
    f.heightsM[k] = h;
  }
  f.validate();
  return f;
}

vtkSmartPointer<vtkImageData> imageFromHeightField(const terrain::HeightField& f) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(f.width, f.height, 1);
  image->SetSpacing(f.spacingM, f.spacingM, 1.0);
  auto heights = vtkSmartPointer<vtkDoubleArray>::New();
  heights->SetName("height_m");
  heights->SetNumberOfTuples(static_cast<vtkIdType>(f.heightsM.size()));
  for (std::size_t k = 0; k < f.heightsM.size(); ++k) heights->SetValue(static_cast<vtkIdType>(k), f.heightsM[k]);
  image->GetPointData()->SetScalars(heights);
  return image;
}

} // namespace umbra::filters
