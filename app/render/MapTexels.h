#pragma once
// A body's maps as the render pass samples them: the texels of an albedo map (grey, relative
// to the geometric albedo: sky/AlbedoMap.hpp), of a reflectance map (sRGB colour taken as
// the surface's reflectance, decoded on the CPU: atmosphere::srgbToLinear, kept as 16-bit
// linear values), or of a normal map (sky/NormalMap.hpp), read once per process
// for each file and kind (an animation's frames, the GUI's updates and every view share
// them). Each user makes its own GPU texture of them, as a texture belongs to one window:
// a receiver a vtkTexture (mapTextureOf), the atmosphere's composite a vtkTextureObject
// (mapTextureObjectOf). Both repeat in longitude (the seam at 180 deg) and filter
// trilinearly with mipmaps.
#include <vtkSmartPointer.h>

#include <memory>
#include <string>

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTexture;
class vtkTextureObject;

namespace umbra::render {

enum class MapKind {
  RelativeAlbedo,  ///< grey (the luminance of a colour image), scaled to the geometric albedo; marks filled
  Reflectance,     ///< sRGB colour decoded, the surface's reflectance as it is (an Earth colour map)
  Normals,         ///< RGB tangent-space normals, as they are
};

struct MapTexels {
  /// 8-bit grey (RelativeAlbedo) or RGB (Normals); 16-bit linear RGB (Reflectance)
  vtkSmartPointer<vtkImageData> texels;
  double discMean = 1.0;  ///< RelativeAlbedo: sky::nearSideDiscMean of the texels (0..1); 1 otherwise
  int width = 2, height = 2;
};

/// The texels of the map at `path` of that kind. Throws std::invalid_argument naming the file
/// (missing, not an image VTK reads, not 8- or 16-bit, a normal or reflectance map without
/// RGB, an albedo map that is black where it is seen).
std::shared_ptr<const MapTexels> mapTexels(const std::string& path, MapKind kind);

/// The Milky Way panorama as the stars' stage draws it (sky/MilkyWay.hpp): its sRGB decoded
/// to linear values, the catalogue's stars that it shows and the scene draws taken out
/// (sky::removeStars), kept as 16-bit linear RGB; with the factors that turn its texels into
/// frame radiance and give its mean over the sphere, both per W m^-2 of the Sun at 1 au.
struct MilkyWayTexels {
  std::shared_ptr<const MapTexels> map;
  double radiancePerSunIrradiance = 0.0;            ///< sky::milkyWayRadianceScale / E_sun
  double sphereMeanRadiancePerSunIrradiance = 0.0;  ///< the same times sky::sphereMeanLuminance
};

/// The Milky Way map at `path` with the stars of the catalogue at `cataloguePath` ("" for
/// none) to V `removedToV` taken out, read once per process for each of those. Throws
/// std::invalid_argument naming the file (as mapTexels; a black map).
std::shared_ptr<const MilkyWayTexels> milkyWayTexels(const std::string& path, const std::string& cataloguePath,
                                                     double removedToV);

/// A receiver's texture of the texels (no anisotropic filtering: Mesa's llvmpipe blurs
/// magnified texels with VTK's default of 4).
vtkSmartPointer<vtkTexture> mapTextureOf(const MapTexels& map);

/// A texture object of the texels in `window`, for a full-screen program; nullptr when it
/// cannot be made.
vtkSmartPointer<vtkTextureObject> mapTextureObjectOf(vtkOpenGLRenderWindow* window, const MapTexels& map);

}  // namespace umbra::render
