#pragma once
// The maps and the star catalogue a scene names, read from their files once per process for
// each file and kind (an animation's frames, the GUI's updates and every view share them):
// a body's albedo, reflectance or normal map as the renderer's texels (render::MapTexels),
// and the Milky Way panorama with the catalogue's stars taken out.
#include "MapTexels.h"

#include <memory>
#include <string>

namespace umbra::pipeline {

using render::MapTexels;

enum class MapKind {
  RelativeAlbedo,  ///< grey (the luminance of a colour image), scaled to the geometric albedo; marks filled
  Reflectance,     ///< sRGB colour decoded, the surface's reflectance as it is (an Earth colour map)
  Normals,         ///< RGB tangent-space normals, as they are
};

/// The texels of the map at `path` of that kind: 8-bit grey (RelativeAlbedo: its grey values,
/// small dark marks filled, sky/AlbedoMap.hpp, with discMean), 8-bit RGB (Normals:
/// sky/NormalMap.hpp), or the sRGB colour decoded to 16-bit linear RGB (Reflectance:
/// atmosphere::srgbToLinear). Throws std::invalid_argument naming the file (missing, not an
/// image VTK reads, not 8- or 16-bit, a normal or reflectance map without RGB, an albedo map
/// that is black where it is seen).
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

}  // namespace umbra::pipeline
