#pragma once
// A DEM as vtkImageData and as umbra::terrain::HeightField: the 2D image's point scalars
// are heights [m] above the body's sphere, its spacing is the grid spacing [m] (equal
// along x and y), column i = x, row j = y. NaN (or the no-data value, if one is given)
// marks no data.
#include "HeightField.hpp"

#include <vtkSmartPointer.h>

#include <optional>

class vtkImageData;

namespace umbra::filters {

/// Throws std::invalid_argument (one line) if the image is not a 2D grid of at least
/// 2 x 2 samples with equal x / y spacing and a one-component height array.
/// `arrayName` empty: the active point scalars.
terrain::HeightField heightFieldFromImage(vtkImageData* image, const std::string& arrayName, double bodyRadiusM,
                                          std::optional<double> noDataValue = std::nullopt);

/// The heights as a 2D image (point scalars "height_m", NaN for no data), origin 0.
vtkSmartPointer<vtkImageData> imageFromHeightField(const terrain::HeightField& field);

} // namespace umbra::filters
