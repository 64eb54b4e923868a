#pragma once
// Eclipse shadows through an atmosphere (eclipse paper, sections 5.2 and 5.3): limb views
// of the atmosphere ring seen from a point of the shadow (Eq. 7, Figures 7 and 10), the
// atmospheric shadow LuT (I = I_indirect + I_direct, stored as I / I_sun) and the
// limb-luminance LuT. Plain C++ (no VTK); reads the atmosphere tables (Precompute.hpp)
// and the deviation / contact table (Refraction.hpp).
//
// Geometry. Seen from a point P at distance d_occ from the occluder's centre, a view ray at
// polar angle theta from the occluder's centre has the impact parameter b = d_occ sin(theta)
// (straight outside the atmosphere). Everything a ray meets inside the atmosphere depends on
// b alone: its total deviation, its contact altitude and its transmittance. So the ray
// optics are tabulated once per atmosphere over b in [r_occ, r_atmo] (LimbRayProfile) and
// every texel of every table shares them; a texel only changes which b its rows see.
// Limb-view rows are gamma = theta - phi_occ in [0, phi_atmo - phi_occ] (v_limb of Eq. 7,
// row 0 at the ground), columns beta in [0, pi] around the occluder (u_limb), beta = 0
// towards the Sun. The other half of the ring is the mirror image (counted twice).
//
// A ray of row theta and column beta leaves the atmosphere towards the direction at polar
// angle theta - Delta-theta(b) on the same azimuth; it sees the Sun where that direction is
// inside the solar disc (exact spherical distance, the limb darkening of Eq. 1), times the
// transmittance T(b) and the terrain factor of its contact altitude. The in-scattered
// radiance comes from the tables (skyRadiance at the ray's entry point), sampled on a
// coarser grid of the view (scatteringColumns x scatteringRows cells).
//
// Units: radiances are per unit solar irradiance [1/sr] (the tables' convention), so the
// illuminance of a surface facing the Sun, divided by the unobstructed Sun's, is
// sum(L dOmega cos) over the view. Per wavelength of the atmosphere tables; RGB channels
// are the ratio at 680, 550 and 440 nm (the tables' rgb() wavelengths; linear interpolation
// in wavelength for other sets), so an airless or grey case has R = G = B.
#include "ShadowLut.hpp"
#include "ShadowMapping.hpp"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace umbra::atmosphere {
struct Atmosphere;
struct AtmosphereTables;
struct RefractionTable;
}

namespace umbra::eclipse {

/// Rough terrain (eclipse paper, 5.2): a ray whose contact altitude is below the mean land
/// elevation is partly blocked, linearly from fully blocked at 0 m to free at twice the
/// mean elevation (Earth: 240 m, so 0-480 m). meanElevationM <= 0: blocked only below 0.
struct TerrainModel {
  double meanElevationM = 0.0;
  double transmission(double contactAltitudeM) const;
};
/// Earth 240 m; other bodies 0 (configurable). The name in any case ("Earth", "earth").
TerrainModel defaultTerrain(const std::string& occluderName);
/// Cells in nu (the view-sun cosine) the occluder's scattering tables need, else
/// `otherwise`: Mars' forward-peaked dust needs 32 (with 8 its multiple scattering at the
/// ~20 degrees that light the umbra at Phobos is interpolated from the forward peak: the
/// umbra's level is 1.9 times too high, and with the earlier Henyey-Greenstein dust it
/// turned blue; docs/eclipse-shadows.md).
int defaultScatteringNu(const std::string& occluderName, int otherwise);

/// Optics of a ray crossing the atmosphere with impact parameter b, at `samples` values of b
/// evenly spaced over [r_occ, r_atmo].
struct LimbRayProfile {
  double occluderRadiusM = 0.0;
  double atmosphereRadiusM = 0.0;
  int channels = 0;                     ///< wavelengths
  std::vector<double> wavelengthsNm;
  std::vector<double> deviationRad;     ///< total deviation, towards the occluder
  std::vector<double> contactAltitudeM; ///< lowest altitude on the path (< 0: ground)
  std::vector<double> transmittance;    ///< whole path, [k * channels + c]

  int samples() const { return static_cast<int>(deviationRad.size()); }
  /// Linear interpolation in b (clamped to the range); `transmittanceOut` gets `channels` values.
  void at(double impactParameterM, double& deviationRad, double& contactAltitudeM,
          double* transmittanceOut) const;
  /// The smallest and largest deviation over impact parameters [bLo, bHi] (the interpolant's).
  /// Reads the runs' extremes below.
  void deviationRange(double bLo, double bHi, double& minRad, double& maxRad) const;

  /// The smallest and largest deviationRad over runs of 2^j nodes from node k, at
  /// [j * samples() + k] (a sparse table: any range of nodes is two runs), made by
  /// indexDeviations(); limbRayProfile and transparentLimbProfile call it, and whoever
  /// changes deviationRad must call it again.
  std::vector<double> deviationRunMin, deviationRunMax;
  void indexDeviations();
};

/// A cloud deck along the limb: the rays whose lowest point lies below `cloudTopM` keep
/// 1 - `cover` of their transmittance (clouds opaque where they are, `cover` of the limb
/// under them). Throws std::invalid_argument for a top < 0 or a cover outside 0..1.
void screenByClouds(LimbRayProfile& rays, double cloudTopM, double cover);

/// T along a refracted ray from (r, mu) to the top (per channel into `out`), given its contact
/// altitude from the deviation / contact table: rising rays (mu >= 0) T(r, mu); descending
/// ones pass their periapsis r_p = r_occ + contact (symmetric about it), so
/// T = T(r_p, horizontal)^2 / T(r, -mu) (at r = r_atmo: T(r_p, horizontal)^2); 0 when the
/// contact is below the ground. The render pass's GLSL twin is
/// umbraRefractedTransmittanceToTop (app/render/glsl/AtmosphereComposite.glsl).
void refractedTransmittanceToTop(const atmosphere::AtmosphereTables& tables, double radiusM, double mu,
                                 double contactAltitudeM, double* out);

/// From the tables: T(b) = T(r_p, horizontal)^2 with r_p the periapsis of the ray (the
/// contact radius of the refraction table, or b without refraction), the deviation and
/// contact from `refraction` (nullptr: straight rays, deviation 0, contact b - r_occ).
LimbRayProfile limbRayProfile(const atmosphere::AtmosphereTables& tables,
                              const atmosphere::RefractionTable* refraction, int samples = 4096);
/// A fully transparent, non-refracting shell: T = 1, deviation 0 (for checks).
LimbRayProfile transparentLimbProfile(double occluderRadiusM, double atmosphereRadiusM,
                                      const std::vector<double>& wavelengthsNm);

/// Everything a limb view needs besides the point.
struct AtmosphericShadowModel {
  SunOccluderSystem system;            ///< Sun radius, occluder radius (the solid body), distance d
  LimbRayProfile rays;                 ///< atmosphereRadiusM comes from here
  /// In-scattered light (both nullptr: none).
  const atmosphere::AtmosphereTables* tables = nullptr;
  const atmosphere::Atmosphere* atmosphere = nullptr;
  TerrainModel terrain;
  double limbDarkening = kDefaultLimbDarkening;
  bool refractedSun = true;  ///< the Sun seen through the atmosphere (refracted, attenuated)
  bool scattering = true;    ///< the light scattered towards the point

  double atmosphereRadiusM() const { return rays.atmosphereRadiusM; }
  /// Empty when usable, else what is wrong.
  std::string validate() const;
};

struct LimbViewParams {
  int columns = 256;           ///< beta over [0, pi]
  int rows = 256;              ///< gamma over [0, phi_atmo - phi_occ]
  int scatteringColumns = 16;  ///< cells the in-scattered radiance is sampled on (docs/accuracy-vs-speed/eclipse-luts.md)
  int scatteringRows = 16;
  /// The refracted Sun is integrated over each row's extent: sub-rows across which the exit
  /// direction moves by at most 1 / subRowsPerSunDiameter of the Sun's diameter; 0: one point
  /// sample at each row's centre (docs/accuracy-vs-speed/eclipse-luts.md, "Single columns of the limb ring").
  double subRowsPerSunDiameter = 128.0;
};

/// Where a texel stands: the angles of Eq. 3 and the distance to the occluder's centre.
/// Points inside the atmosphere (u -> 0) are moved out to its top.
struct LimbPosition {
  double sunAngularRadiusRad = 0.0, occluderAngularRadiusRad = 0.0, atmosphereAngularRadiusRad = 0.0;
  double separationRad = 0.0;
  double occluderDistanceM = 0.0;
};
LimbPosition limbPosition(const AtmosphericShadowModel& model, const LutCoords& coords);
/// The point `distanceBehindM` behind the occluder's centre (on the axis away from the Sun)
/// and `offsetM` off the axis.
LimbPosition limbPositionBehind(const AtmosphericShadowModel& model, double distanceBehindM, double offsetM);
/// Eq. 4 for a position (the shadow LuT's coordinates).
LutCoords lutCoordsOf(const LimbPosition& position);

/// A limb view: radiance per pixel and channel, row-major (row = gamma index).
struct LimbView {
  int columns = 0, rows = 0, channels = 0;
  std::vector<double> radiance;     ///< [(row * columns + column) * channels + c], 1/sr
  std::vector<double> solidAngleSr; ///< per row: one pixel's solid angle
  double& at(int row, int column, int c) {
    return radiance[(static_cast<std::size_t>(row) * columns + column) * channels + c];
  }
  double at(int row, int column, int c) const {
    return radiance[(static_cast<std::size_t>(row) * columns + column) * channels + c];
  }
};
/// The view from `position` (pixels are exact averages over their beta range of the
/// refracted Sun, integrated over their gamma range by sub-rows; in-scattering from the
/// coarse cells).
LimbView renderLimbView(const AtmosphericShadowModel& model, const LimbPosition& position,
                        const LimbViewParams& params);
/// The view averaged over the rows of each of `layers` bands by solid angle (what the
/// limb-luminance LuT stores): [(layer * columns + column) * channels + c].
std::vector<double> layerAverages(const LimbView& view, int layers);

/// I / I_sun per channel at `position`: the limb view summed by solid angle (twice: both
/// halves) plus the direct light past an opaque sphere of radius r_atmo.
struct Illuminance {
  std::vector<double> indirect;  ///< per channel
  double direct = 0.0;           ///< the same for all channels
  std::vector<double> total() const;
};
/// Sum over the rows of the refracted Sun integrated exactly in beta (the column count
/// does not matter) plus the in-scattered cells. Equal to summing renderLimbView.
Illuminance illuminanceAt(const AtmosphericShadowModel& model, const LimbPosition& position,
                          const LimbViewParams& params);

/// The light (I / I_sun) at `offsetM` from the shadow's axis `distanceBehindM` behind the
/// occluder, computed directly (illuminanceAt with `limb`).
ProfileSample atmosphericShadowAt(const AtmosphericShadowModel& model, double distanceBehindM, double offsetM,
                                  const LimbViewParams& limb);

/// Cross-section of the shadow `distanceBehindM` behind the occluder, offsets 0 to
/// `maxOffsetM` in `samples` samples (>= 2): sampled from `lut` (bilinear, as the renderer;
/// 1 past v = 1) or, without it, computed directly at each point (illuminanceAt with
/// `limb`; past v = 1 too, where the ring of the atmosphere still covers part of the Sun).
std::vector<ProfileSample> atmosphericShadowProfile(const AtmosphericShadowModel& model, double distanceBehindM,
                                                    double maxOffsetM, int samples, const ShadowLut* lut,
                                                    const LimbViewParams& limb = {});

/// The RGB of a per-wavelength ratio: its values at 680, 550, 440 nm (see the header).
glm::dvec3 rgbOfSpectralRatio(const std::vector<double>& wavelengthsNm, const double* ratio);

/// Texels [uBegin, uEnd) x [vBegin, vEnd) of a width x height LuT; empty: all.
struct LutExtent {
  int uBegin = 0, uEnd = 0, vBegin = 0, vEnd = 0;
  bool empty() const { return uEnd <= uBegin || vEnd <= vBegin; }
};

struct AtmosphericShadowLutParams {
  int width = 256, height = 256;
  LimbViewParams limb;
  double uMin = 0.0, uMax = 1.0, vMin = 0.0, vMax = 1.0;  ///< ranges over the width and height, as ShadowLutParams'
  double vLowFraction = 0.0;  ///< (a split v axis needs the whole v extent)
};

/// The shadow LuT (texel centres as the airless LuT's); only `extent` is computed: the
/// result is extent-sized (texel (i, j) is the LuT's (uBegin + i, vBegin + j); its ranges
/// those of the extent's columns and rows). OpenMP over
/// texels; `progress` from the calling thread; empty when cancelled. Throws
/// std::invalid_argument for a bad model, sizes or extent.
ShadowLut buildAtmosphericShadowLut(const AtmosphericShadowModel& model,
                                    const AtmosphericShadowLutParams& params,
                                    const LutExtent& extent = {}, const Progress& progress = {},
                                    const TexelShare& share = {});

struct LimbLuminanceLutParams {
  int width = 64, height = 64;  ///< u, v
  int columns = 64;             ///< beta samples of each limb view
  int layers = 1;               ///< rows kept of each view (subsampled from limb.rows)
  LimbViewParams limb{64, 256, 32, 32};
  LutRange range;  ///< u and v ranges over the width and height, as the shadow LuT's
};

/// For each (u, v) texel (at its centre in params.range) the limb view averaged down to `layers` rows: RGB radiance per
/// unit solar irradiance [1/sr]. Stored as a 3D texture width x height x (columns * layers),
/// the rows one after the other: value (i, j, layer * columns + column).
struct LimbLuminanceLut {
  int width = 0, height = 0, columns = 0, layers = 0;
  LutRange range;  ///< texel (i, j) at (range.texelU(i, width), range.texelV(j, height))
  std::vector<float> rgb;  ///< [((k * height + j) * width + i) * 3 + c], k = layer * columns + column
  int depth() const { return columns * layers; }
  glm::dvec3 texel(int i, int j, int k) const;
};
LimbLuminanceLut buildLimbLuminanceLut(const AtmosphericShadowModel& model,
                                       const LimbLuminanceLutParams& params,
                                       const Progress& progress = {}, const TexelShare& share = {});

} // namespace umbra::eclipse
