#pragma once
// The eclipse shadow LuT (eclipse/ShadowLut.hpp) as the vtkImageData that EclipseShading
// binds: W x H x 1, point scalars float RGB, texel (i, j) = value at u = (i + .5) / W,
// v = (j + .5) / H. A copy of the table, no computation.
#include "ShadowLut.hpp"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

namespace umbra::render {

vtkSmartPointer<vtkImageData> shadowLutToImageData(const eclipse::ShadowLut& lut);

} // namespace umbra::render
