#pragma once
// A body's map as the render pass samples it: its texels (8-bit grey: an albedo map relative
// to the geometric albedo, sky/AlbedoMap.hpp; 16-bit linear RGB: a reflectance map or the
// Milky Way; 8-bit RGB: a normal map, sky/NormalMap.hpp), as the caller read them
// (pipeline::mapTexels reads them from files). Each user makes its own GPU texture of them,
// as a texture belongs to one window: a receiver a vtkTexture (mapTextureOf), the
// atmosphere's composite a vtkTextureObject (mapTextureObjectOf). Both repeat in longitude
// (the seam at 180 deg) and filter trilinearly with mipmaps.
#include <vtkSmartPointer.h>

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTexture;
class vtkTextureObject;

namespace umbra::render {

struct MapTexels {
  /// 8-bit grey (an albedo map) or RGB (normals); 16-bit linear RGB (reflectance, the Milky Way)
  vtkSmartPointer<vtkImageData> texels;
  double discMean = 1.0;  ///< an albedo map: sky::nearSideDiscMean of the texels (0..1); 1 otherwise
  int width = 2, height = 2;
};

/// A receiver's texture of the texels (no anisotropic filtering: Mesa's llvmpipe blurs
/// magnified texels with VTK's default of 4).
vtkSmartPointer<vtkTexture> mapTextureOf(const MapTexels& map);

/// A texture object of the texels in `window`, for a full-screen program; nullptr when it
/// cannot be made.
vtkSmartPointer<vtkTextureObject> mapTextureObjectOf(vtkOpenGLRenderWindow* window, const MapTexels& map);

}  // namespace umbra::render
