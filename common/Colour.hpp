#pragma once
// Colour of linear RGB (Rec. 709 / sRGB primaries, D65): the relative luminance that the
// shadow profiles, the maps, the sky and the XYZ conversion (atmosphere/Spectrum.hpp) weigh
// R, G and B with. Header-only.
#include <glm/vec3.hpp>

namespace umbra::colour {

/// Relative luminance Y of a linear RGB triple: the Y row of IEC 61966-2-1's linear sRGB to
/// XYZ (D65).
inline double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

}  // namespace umbra::colour
