#pragma once
// The eclipse-shadow lookup table of an airless occluder and everything that reads it:
// the texel layout, GL-equivalent bilinear sampling, the shadow factor at a point, and
// cross-sections (profiles) of the shadow. The GLSL twin of `eclipseFactor` lives in
// glsl/EclipseShadow.glsl; tests/render checks that the two agree.
#include "ShadowMapping.hpp"
#include "SolarDisc.hpp"

#include <glm/vec3.hpp>

#include <functional>
#include <vector>

namespace umbra::eclipse {

/// Relative luminance of a linear RGB triple (Rec. 709 / sRGB primaries).
double luminance(const glm::dvec3& rgb);

struct ShadowLutParams {
  int width = 256;                 ///< texels along u
  int height = 256;                ///< texels along v
  double limbDarkening = kDefaultLimbDarkening;
  double relativeTolerance = 1e-10;  ///< of the per-texel quadrature
};

/// I / I_sun per texel, RGB (equal channels for an airless occluder). Texel (i, j) holds
/// the value at its centre u = (i + 0.5) / width, v = (j + 0.5) / height, so that the
/// GPU's linear filtering with clamp-to-edge samples it exactly as `sample` does.
struct ShadowLut {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< row-major, row j = v index, 3 floats per texel
  glm::dvec3 texel(int i, int j) const;
  glm::dvec3 sample(const LutCoords& c) const;
};

/// Value of the airless shadow function at (u, v): the visible fraction of the
/// limb-darkened Sun (v >= 1: 1, no eclipse).
double airlessShadow(const LutCoords& c, double limbDarkening = kDefaultLimbDarkening,
                     double relativeTolerance = 1e-10);

/// Progress callback: fraction done in [0, 1]; return false to cancel.
using Progress = std::function<bool(double)>;

/// Build the airless LuT (parallel over rows). Returns an empty LuT when cancelled.
/// An airless LuT depends only on its size and the limb darkening: Eq. 4 makes the
/// visible fraction a function of (u, v) alone, for every Sun and occluder.
ShadowLut buildAirlessShadowLut(const ShadowLutParams& params, const Progress& progress = {});

/// One occluder as the shadow sees it.
struct Occluder {
  glm::dvec3 centreM{0.0};
  double radiusM = 0.0;
};

/// Fraction of sunlight (per channel) reaching `pointM` past `occluder`: 1 where the
/// occluder is behind the Sun or the point outside the penumbra. With `lut` the value is
/// sampled from the table (as the renderer does), without it computed exactly.
glm::dvec3 eclipseFactor(const glm::dvec3& pointM, const glm::dvec3& sunM, double sunRadiusM,
                         const Occluder& occluder, const ShadowLut* lut,
                         double limbDarkening = kDefaultLimbDarkening);

struct ProfileSample {
  double offsetM = 0.0;  ///< from the shadow axis
  glm::dvec3 rgb{1.0};   ///< I / I_sun
  double luminance = 1.0;
};

/// Cross-section of the shadow `distanceBehindM` behind the occluder's centre (along the
/// axis pointing away from the Sun), from offset 0 to `maxOffsetM` in `samples` samples.
std::vector<ProfileSample> shadowProfile(const SunOccluderSystem& system, double distanceBehindM,
                                         double maxOffsetM, int samples, const ShadowLut* lut,
                                         double limbDarkening = kDefaultLimbDarkening);

} // namespace umbra::eclipse
