#pragma once
// How the eye sees dim light: the rods' (scotopic) luminance of a colour and the CIE's
// mesopic adaptation between rods and cones. The render pass's display transform
// (app/render/glsl/ToneMap.glsl, umbraNightVision) is the GLSL twin; EXR output keeps the
// physical radiance.
//
// Scotopic luminance from CIE XYZ (Larson, Rushmeier & Piatko 1997, IEEE TVCG 3(4)):
//     V = Y (1.33 (1 + (Y + Z) / X) - 1.68)
// in scotopic cd m^-2 for Y in cd m^-2 (D65 white: V / Y = 2.58).
// Mesopic adaptation (CIE 191:2010, the MES2 system): the cones' share m in [0, 1] is the
// fixed point of
//     m = a + b log10(L_mes),   L_mes = (m L_p + (1 - m) L_s V'0) / (m + (1 - m) V'0)
// with a = 0.7670, b = 0.3334, V'0 = 683 / 1699; m = 1 (photopic) from L_mes = 5 cd m^-2 up,
// m = 0 (scotopic) from 0.005 cd m^-2 down.
#include <glm/vec3.hpp>

namespace umbra::sky {

/// Scotopic luminance [scotopic cd m^-2] of CIE XYZ [cd m^-2] (Larson et al.); 0 where X or
/// the result is not positive.
double scotopicLuminance(const glm::dvec3& xyz);

/// The CIE 191 cones' share m for a photopic luminance Lp [cd m^-2] and a scotopic one Ls
/// [scotopic cd m^-2]: 1 photopic, 0 scotopic. Throws std::invalid_argument for negative or
/// non-finite luminances.
double mesopicConeShare(double photopicCdM2, double scotopicCdM2);

/// Its fixed-point iteration, as the GLSL runs it: `iterations` steps of the equation from
/// m = 0.5, clamped to [0, 1] at each.
double mesopicConeShareIterated(double photopicCdM2, double scotopicCdM2, int iterations);

/// Sunlight's luminous efficacy [lm W^-1]: the illuminance of the top-of-atmosphere Sun over
/// its irradiance (about 98): a frame radiance of 1 W m^-2 sr^-1 of white-balanced
/// sunlight is that many cd m^-2.
double sunlightEfficacyLmPerW();

/// The scotopic-to-photopic ratio of sunlight (the frames' white).
double sunlightScotopicRatio();

/// What the eye sees of a frame colour (linear sRGB, white-balanced to the Sun, W m^-2
/// sr^-1): at the pixel's own adaptation (its photopic and scotopic luminance), the cones'
/// share m of its colour and 1 - m of a grey of its scotopic luminance, scaled so that
/// sunlight's white keeps its value: mix(V / (ratio of sunlight), colour, m).
glm::dvec3 nightVisionColour(const glm::dvec3& frameRgb);

}  // namespace umbra::sky
