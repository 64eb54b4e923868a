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

struct ShadowLutParams {
  int width = 256;                 ///< texels along u
  int height = 256;                ///< texels along v
  double limbDarkening = kDefaultLimbDarkening;
  double relativeTolerance = 1e-10;  ///< of the per-texel quadrature
  /// u and v ranges mapped onto the texture's width and height (default [0, 1]: the whole
  /// of Eq. 4); narrower ones (lutRangeForDistances) give full resolution where a scene's
  /// receivers are.
  double uMin = 0.0, uMax = 1.0, vMin = 0.0, vMax = 1.0;
  /// Fraction of the rows given to v in [0, vMin] (0: none, below vMin row 0 is read).
  double vLowFraction = 0.0;
};

/// The u and v ranges of a LuT (ShadowLutParams) and its texel layout: texel (i, j) of a
/// width x height LuT stands for (texelU(i, width), texelV(j, height)); a lookup at (u, v)
/// reads texture coordinate (textureU(u), textureV(v)) (before clamping; ShadowLut).
struct LutRange {
  double uMin = 0.0, uMax = 1.0, vMin = 0.0, vMax = 1.0, vLowFraction = 0.0;
  double texelU(int i, int width) const { return uMin + (uMax - uMin) * (i + 0.5) / width; }
  double texelV(int j, int height) const;
  double textureU(double u) const { return (u - uMin) / (uMax - uMin); }
  double textureV(double v) const;
  /// textureU and textureV in the form a shader evaluates without division or branch:
  /// (u - uOrigin) uScale, and (v - vOrigin) vScale for v >= vSplit, (v - vLowOrigin)
  /// vLowScale below (a split v axis; without one the two pairs are the same).
  struct TextureMap {
    double uOrigin = 0.0, uScale = 1.0, vOrigin = 0.0, vScale = 1.0;
    double vSplit = 0.0, vLowOrigin = 0.0, vLowScale = 1.0;
  };
  TextureMap textureMap() const;
  bool operator==(const LutRange& o) const {
    return uMin == o.uMin && uMax == o.uMax && vMin == o.vMin && vMax == o.vMax && vLowFraction == o.vLowFraction;
  }
  bool operator!=(const LutRange& o) const { return !(*this == o); }
};

/// I / I_sun per texel, RGB (equal channels for an airless occluder). Texel (i, j) holds
/// the value at its centre u = uMin + (uMax - uMin) (i + 0.5) / width, v = vMin + (vMax -
/// vMin) (j + 0.5) / height, so that the GPU's linear filtering with clamp-to-edge of the
/// texture coordinate ((u - uMin) / (uMax - uMin), (v - vMin) / (vMax - vMin)) samples it
/// exactly as `sample` does. Outside the ranges the edge texels are used (a range-limited
/// LuT is valid inside its ranges only). With vLowFraction f > 0 the v axis is split: the
/// texture coordinate is t = f v / vMin below vMin, f + (1 - f)(v - vMin) / (vMax - vMin)
/// above (the first f of the rows for [0, vMin], e.g. the umbra's inside, the rest for
/// [vMin, vMax], e.g. a penumbra that is a few per cent of v wide).
struct ShadowLut {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< row-major, row j = v index, 3 floats per texel
  double uMin = 0.0, uMax = 1.0;  ///< the u range over the width (ShadowLutParams)
  double vMin = 0.0, vMax = 1.0;  ///< the v range over the height
  double vLowFraction = 0.0;      ///< of the rows, for v in [0, vMin]
  glm::dvec3 texel(int i, int j) const;
  glm::dvec3 sample(const LutCoords& c) const;
  LutRange range() const { return {uMin, uMax, vMin, vMax, vLowFraction}; }
  /// u of column i's centre, v of row j's.
  double texelU(int i) const { return range().texelU(i, width); }
  double texelV(int j) const { return range().texelV(j, height); }
  /// The texture coordinate along the height of v (before clamping).
  double textureV(double v) const { return range().textureV(v); }
};

/// Checks a LuT's ranges: 0 <= min < max <= 1, 0 <= vLowFraction < 1 and vMin > 0 with a
/// split (throws std::invalid_argument).
void checkLutRange(double uMin, double uMax, double vMin, double vMax, double vLowFraction = 0.0);

/// Value of the airless shadow function at (u, v): the visible fraction of the
/// limb-darkened Sun (v >= 1: 1, no eclipse).
double airlessShadow(const LutCoords& c, double limbDarkening = kDefaultLimbDarkening,
                     double relativeTolerance = 1e-10);

/// Progress callback: fraction done in [0, 1]; return false to cancel.
using Progress = std::function<bool(double)>;

/// The texels of a LuT one process computes when several share it (the ranks of an MPI
/// run): texel k (row-major over u and v) when k % count == index. Interleaved, so that
/// costly and cheap parts of the table are shared alike. The others are left 0.
struct TexelShare {
  int index = 0, count = 1;
  bool owns(long long k) const { return k % count == index; }
  /// How many of `total` texels are this share's, and the n-th of them.
  int texels(int total) const { return total / count + (index < total % count ? 1 : 0); }
  int texel(int n) const { return index + n * count; }
};

/// Build the airless LuT (parallel over rows; only `share`'s texels). Returns an empty LuT
/// when cancelled. An airless LuT depends only on its size and the limb darkening: Eq. 4
/// makes the visible fraction a function of (u, v) alone, for every Sun and occluder.
ShadowLut buildAirlessShadowLut(const ShadowLutParams& params, const Progress& progress = {},
                                const TexelShare& share = {});

/// The ranges of a scene-limited LuT. u: that (Eq. 4) of every point at distance
/// [minDistanceM, maxDistanceM] from the occluder's centre, for `system` (conservative: the
/// Sun's distance taken from d - distance to d + distance). v: near the occluder the
/// penumbra is v in [1 - 2u, 1], 2u of the height, so v is split at the umbra's edge
/// 1 - 2 uMax (when > 0). With `darkUmbra` (an airless occluder: I = 0 wherever the occluder
/// covers the whole Sun) all rows go to the penumbra, from where row 0's centre of a
/// `height`-row LuT is in the umbra for every u of the range (clamping below it reads 0);
/// without (an atmosphere lights the umbra's inside) a quarter of the rows go to [0, vMin].
/// Throws std::invalid_argument when the distances are not 0 < min <= max < d - r_sun.
LutRange lutRangeForDistances(const SunOccluderSystem& system, double minDistanceM, double maxDistanceM,
                              bool darkUmbra = false, int height = 256);
/// The v part of lutRangeForDistances for the u range [uMin, uMax] (0 <= uMin < uMax <= 1).
LutRange lutRangeForU(double uMin, double uMax, bool darkUmbra = false, int height = 256);
/// Whether a LuT over `range` pays against a whole one of `height` rows: near the occluder
/// the penumbra is 2 uMax of the whole LuT's height; below 16 rows it is too coarse there
/// (docs/eclipse-shadows.md). `umbra profile shadow` and the scenes' LuTs use it.
bool rangedLutPays(const LutRange& range, int height);

/// One occluder as the shadow sees it.
struct Occluder {
  glm::dvec3 centreM{0.0};
  double radiusM = 0.0;  ///< the mean radius
  Oblateness figure{};   ///< a sphere unless its flattening is set
  /// Its velocity in the Sun's rest frame, and how long before the scene's time centreM
  /// has it (its light time to the camera, lightTimeToSurfaceS): what occluderSeenBy needs
  /// to move it to where the light that reaches a receiver passed it. Zero: at rest.
  glm::dvec3 velocityMps{0.0};
  double lightDelayS = 0.0;
};

/// The speed of light in vacuum, m/s (exact, SI).
inline constexpr double kLightSpeedMps = 299792458.0;

/// Seconds light takes from a body's near surface to `pointM`: (|centre - point| -
/// radius) / c, at least 0. A body is drawn where it was this long before the scene's time
/// (the camera at `pointM`), and a receiver's occluders are taken this long before the
/// receiver's own time (a receiver's surface stands for all its points: the 640 m the
/// Moon moves in the Earth's radius' light time is the error left).
double lightTimeToSurfaceS(const glm::dvec3& pointM, const glm::dvec3& centreM, double radiusM);

/// `body` as a camera at `cameraM` sees it: where it was lightTimeToSurfaceS(camera, its
/// centre, its radius) before the scene's time, its lightDelayS that (from the delay 0).
Occluder seenFromCamera(const Occluder& body, const glm::dvec3& cameraM);

/// `o` where the light that reaches a receiver (of centre and radius as drawn, drawn
/// `receiverDelayS` before the scene's time) passed it: moved by -velocity x (receiverDelayS
/// + lightTimeToSurfaceS(receiver from the occluder) - o.lightDelayS), to first order in
/// v/c in the Sun's rest frame (the Sun's own motion about the barycentre, 13 m/s, left
/// out). The Moon's shadow on the Earth moves 38 km by it (its 1.28 s at 30 km/s); the
/// Earth's on the Moon seen from the Earth as much. The receiver's own motion is not a
/// shadow's: the Sun, at rest, sends light along straight lines.
Occluder occluderSeenBy(const Occluder& o, const glm::dvec3& receiverCentreM, double receiverRadiusM,
                        double receiverDelayS);

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
