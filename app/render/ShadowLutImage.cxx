#include "ShadowLutImage.h"

#include <vtkFloatArray.h>
#include <vtkPointData.h>

#include <stdexcept>
#include <string>

namespace umbra::render {

vtkSmartPointer<vtkImageData> shadowLutToImageData(const eclipse::ShadowLut& lut) {
  const std::size_t texels = static_cast<std::size_t>(lut.width) * static_cast<std::size_t>(lut.height);
  if (lut.width < 2 || lut.height < 2 || lut.rgb.size() != 3 * texels) {
    throw std::invalid_argument("shadow LuT is empty or inconsistent (" + std::to_string(lut.width) + "x" +
                                std::to_string(lut.height) + ", " + std::to_string(lut.rgb.size()) +
                                " floats)");
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(lut.width, lut.height, 1);
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName("shadow");
  values->SetNumberOfComponents(3);
  values->SetNumberOfTuples(static_cast<vtkIdType>(texels));
  std::copy(lut.rgb.begin(), lut.rgb.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);
  return image;
}

} // namespace umbra::render
