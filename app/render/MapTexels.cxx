#include "MapTexels.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkTexture.h>
#include <vtkTextureObject.h>

namespace umbra::render {

vtkSmartPointer<vtkTexture> mapTextureOf(const MapTexels& map) {
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetColorModeToDirectScalars();
  texture->InterpolateOn();
  texture->MipmapOn();
  texture->SetMaximumAnisotropicFiltering(1.0f);
  texture->SetWrap(vtkTexture::Repeat);
  texture->UseSRGBColorSpaceOff();
  texture->SetInputData(map.texels);
  return texture;
}

vtkSmartPointer<vtkTextureObject> mapTextureObjectOf(vtkOpenGLRenderWindow* window, const MapTexels& map) {
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  t->SetGenerateMipmap(true);
  t->SetWrapS(vtkTextureObject::Repeat);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  t->SetMinificationFilter(vtkTextureObject::LinearMipmapLinear);
  t->SetMagnificationFilter(vtkTextureObject::Linear);
  vtkDataArray* scalars = map.texels->GetPointData()->GetScalars();
  if (!t->Create2DFromRaw(static_cast<unsigned>(map.width), static_cast<unsigned>(map.height),
                          scalars->GetNumberOfComponents(), scalars->GetDataType(), map.texels->GetScalarPointer()))
    return nullptr;
  return t;
}

}  // namespace umbra::render
