#pragma once
// A body's relief as a normal map: an equirectangular RGB image laid like an albedo map
// (sky/AlbedoMap.hpp: columns from east longitude -180 to +180 deg, rows from latitude -90
// at the bottom to +90 at the top, in the body-fixed frame), each texel a unit normal in
// the local tangent frame: red = east, green = south (the image's down), blue = up, each
// component c in [-1, 1] stored as (c + 1) / 2. stellarium-data's Moon
// (textures/moon_normals.png, 1024 x 512) is laid so: a crater's western inner wall is red,
// its northern one green.
//
// The shading takes the tilted normal for the light's and the eye's angles and keeps the
// sphere's for the large-scale terminator (no light where the sphere's own cosine of
// incidence is <= 0), so relief brightens the slopes facing the Sun along the terminator
// and darkens the others, and the disc seen whole stays as bright (docs/moon.md).
//
// A texel holds the slopes averaged over it (stellarium-data's Moon: 10.7 km at the
// equator) and casts no shadow: magnified far beyond a pixel it would only tilt whole
// landscapes, brightening them under a grazing Sun where the real relief shadows itself.
// So the relief is drawn where the map resolves it on screen: at full strength while a
// texel spans at most 4 pixels, fading (linearly in the log of the magnification) to none
// at 16 pixels and more (reliefFade). A surface view near the body, whose relief is a
// terrain patch's (docs/scene-format.md, "Terrain"), is left smooth.
#include <glm/vec3.hpp>

namespace umbra::sky {

/// The relief's unit normal at a point whose sphere normal is nb (unit, body-fixed), for a
/// texel t (RGB in [0, 1]): the texel's tangential components times `strength` (0: the
/// sphere; 1: as the map has them) in the local east-north-up frame, then normalised. The
/// up component is held at >= 0.05 (a texel cannot turn a facet over). At the poles east is
/// taken along the body-fixed y axis. The GLSL twin is umbraReliefNormal
/// (sky/glsl/Photometry.glsl).
glm::dvec3 reliefNormal(const glm::dvec3& nb, const glm::dvec3& texel, double strength);

/// The share of the relief drawn where a map texel spans `pixelsPerTexel` pixels on
/// screen: 1 up to 4, 0 from 16, linear in log2 between. The GLSL twin is in
/// app/render/glsl/ReceiverFragment.glsl (umbraReliefAt).
double reliefFade(double pixelsPerTexel);

}  // namespace umbra::sky
