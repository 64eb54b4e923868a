#pragma once
// The sky seen by an observer: luminance [cd m^-2] and linear sRGB over a grid of view
// directions, from the precomputed tables (Precompute.hpp, skyRadiance: single + multiple
// scattering) lit by the top-of-atmosphere solar spectrum at 1 au
// (solarIrradianceWm2PerNm); and the CIE standard general sky (ISO 15469:2004 /
// CIE S 011/E:2003) to compare its relative luminance with (Costa et al., section 6.3,
// Fig. 7: the Earth model against type 12, the CIE standard clear sky, low luminance
// turbidity). docs/sky-validation.md has the measured comparison.
//
// Directions: view zenith angle Z in [0, pi/2] (0: the zenith, pi/2: the horizon) and the
// azimuth A measured from the Sun's azimuth (0: towards the Sun). The sky of a spherically
// symmetric atmosphere is symmetric about the Sun's vertical, so A in [0, pi] is enough.
// The cosine of the angle between the view and the Sun is
//     cos chi = nu = cos Z cos Z_s + sin Z sin Z_s cos A.
// Radiance is the sky's only (the Sun's disc and the ground are not added).
#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Spectrum.hpp"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace umbra::atmosphere {

/// 683 lm/W * integral E_sun(lambda) ybar(lambda) dlambda over 360-830 nm: the illuminance
/// [lx] of the top-of-atmosphere Sun at 1 au at normal incidence (1 nm trapezoid over
/// solarIrradianceWm2PerNm and the CIE 1931 ybar). About 1.33e5 lx (docs/sky-validation.md).
double solarIlluminanceLux();

/// X, Y, Z [lx] of that Sun (the same integral with xbar, ybar, zbar): Y is
/// solarIlluminanceLux(). Its chromaticity is the white every render is balanced to.
glm::dvec3 solarXyzLux();

struct SkySample {
  double viewZenithRad = 0.0;
  double azimuthRad = 0.0;      ///< from the Sun's azimuth
  double luminanceCdM2 = 0.0;
  glm::dvec3 linearSrgb{0.0};   ///< cd m^-2 scale: (1, 1, 1) is D65 white of luminance 1
};

/// Samples zenith-major: index iz * azimuthCount + ia, Z = iz * zenithStep (the last row
/// the horizon when the step divides 90 degrees), A = ia * azimuthStep up to 180 degrees.
struct SkyGrid {
  double sunZenithRad = 0.0;
  double observerAltitudeM = 0.0;
  double solarIlluminanceLux = 0.0;  ///< of the light the sky was computed for
  double zenithStepRad = 0.0, azimuthStepRad = 0.0;
  int zenithCount = 0, azimuthCount = 0;
  std::vector<SkySample> samples;

  const SkySample& at(int iz, int ia) const {
    return samples[static_cast<std::size_t>(iz) * azimuthCount + ia];
  }
};

/// The tables `umbra atmosphere sky` makes for a Sun at sunZenithRad
/// (docs/sky-validation.md): transmittance 128 x 32, scattering (NU 8 * MU_S 128) x MU 64 x
/// R 8, irradiance 32 x 8, 40 samples per view ray, the Sun down to
/// skyLowestSunZenithRad(sunZenithRad); 12 x 24 density directions for a Sun above the
/// horizon, 24 x 48 below it, or more where a forward-peaked phase function of
/// `atmosphere` asks for them (densityDirectionsFor above kMinDensityDirections: Mars' dust,
/// 48 x 96; its dome's mean is 17 % too dark with 12 x 24). About 2 s (day) and 4 s
/// (twilight) for Earth at 15 wavelengths and 4 orders on 2 cores; Mars 88 s. The twilight sky varies by orders of magnitude over a few degrees
/// of Sun and of view, and coarse tables miss it (docs/accuracy-vs-speed/atmosphere-tables.md, "Twilight"):
/// linear interpolation across 16 mu_s cells made the zenith x4.7 too bright at a Sun
/// 100 deg from the zenith; 12 density directions make it +27 % (+75 % at 106 deg), 24
/// within 3 % of 48.
PrecomputeOptions skyPrecomputeOptions(const Atmosphere& atmosphere, int orders = 4, double sunZenithRad = 0.0);

/// The lowest Sun the sky's tables need for a Sun at sunZenithRad: 102 deg (the tables'
/// usual lowest), or 20 deg below a lower Sun (at most 170 deg). Air with the Sun below
/// the tables' lowest is taken to be dark (skyRadiance), so a night sky needs the tables to
/// reach below its Sun: the shadowed air overhead is lit by the sunlit air's scattering
/// (second-order twilight, the zenith's only light from a Sun about 12 deg down on), and
/// so are the views away from the Sun, whose air has the Sun lower still.
double skyLowestSunZenithRad(double sunZenithRad);

/// Luminance and linear sRGB of the sky in one direction (sunlight: E_sun(lambda_i) at the
/// tables' wavelengths, which must be `wavelengths.nm`).
SkySample skyLuminanceAt(const AtmosphereTables& tables, const Atmosphere& atmosphere,
                         const WavelengthSet& wavelengths, double sunZenithRad, double observerAltitudeM,
                         double viewZenithRad, double azimuthRad);

/// The most directions a sky grid may have (the steps' product): 1 000 000.
inline constexpr int kMaxSkyDirections = 1000000;

/// The grid: Z = 0, step, ... <= 90 degrees; A = 0, step, ... <= 180 degrees. Throws
/// std::invalid_argument for steps outside (0, 90] degrees, a Sun zenith outside
/// [0, 180] degrees, a negative altitude or one above the atmosphere, or tables whose
/// wavelengths differ from `wavelengths`.
SkyGrid skyLuminance(const AtmosphereTables& tables, const Atmosphere& atmosphere,
                     const WavelengthSet& wavelengths, double sunZenithRad, double observerAltitudeM,
                     double zenithStepRad, double azimuthStepRad);

// ---- the CIE standard general sky (ISO 15469:2004, CIE S 011/E:2003) --------------------

/// Gradation (a, b) and indicatrix (c, d, e) parameters of one of the 15 standard skies.
struct CieSkyParameters {
  double a, b, c, d, e;
};
/// Type 12, "CIE standard clear sky, low luminance turbidity": gradation group V
/// (a = -1, b = -0.32), indicatrix group 4 (c = 10, d = -3, e = 0.45).
inline constexpr CieSkyParameters kCieClearSkyType12{-1.0, -0.32, 10.0, -3.0, 0.45};
/// Type 11, "white-blue sky with distinct solar corona": gradation group V with b = -0.55
/// (a = -1), indicatrix group 4 (c = 10, d = -3, e = 0.45).
inline constexpr CieSkyParameters kCieSkyType11{-1.0, -0.55, 10.0, -3.0, 0.45};
/// Type 13, "CIE standard clear sky, polluted atmosphere": gradation group V (a = -1,
/// b = -0.32), indicatrix group 5 (c = 16, d = -3, e = 0.30).
inline constexpr CieSkyParameters kCieSkyType13{-1.0, -0.32, 16.0, -3.0, 0.30};

/// phi(Z) = 1 + a exp(b / cos Z); phi(pi/2) = 1 (the limit, taken for Z >= pi/2).
double cieGradation(const CieSkyParameters& p, double zenithRad);
/// f(chi) = 1 + c (exp(d chi) - exp(d pi / 2)) + e cos^2 chi.
double cieIndicatrix(const CieSkyParameters& p, double chiRad);
/// L / L_z = f(chi) phi(Z) / (f(Z_s) phi(0)), chi the angle between the view and the Sun.
double cieRelativeLuminance(const CieSkyParameters& p, double viewZenithRad, double azimuthFromSunRad,
                            double sunZenithRad);

enum class SkyNormalisation {
  Zenith,  ///< both skies divided by their zenith luminance (Costa et al., Fig. 7)
  Mean,    ///< the model scaled so that its solid-angle-weighted mean over the compared
           ///< samples equals the CIE sky's (insensitive to the zenith alone)
};

struct SkyComparisonOptions {
  SkyNormalisation normalisation = SkyNormalisation::Zenith;
  double excludeAroundSunRad = 0.08726646259971647;  ///< 5 degrees: the aureole
  double maxViewZenithRad = 1.4835298641951802;      ///< 85 degrees: the horizon band left out
};

struct SkyComparison {
  int samples = 0;                 ///< grid samples compared
  double rmsRelativeError = 0.0;   ///< sqrt(sum w (m/c - 1)^2 / sum w), w = solid angle (sin Z)
  double maxRelativeError = 0.0;   ///< max |m/c - 1|
  double meanRelativeError = 0.0;  ///< sum w (m/c - 1) / sum w (the bias)
  double maxErrorZenithRad = 0.0, maxErrorAzimuthRad = 0.0;  ///< where the max is
};

/// The model's relative luminance m against the CIE sky's c over the grid's samples with
/// Z <= maxViewZenithRad and at least excludeAroundSunRad from the Sun. The grid must
/// include the zenith (its first row).
SkyComparison compareWithCie(const SkyGrid& grid, const CieSkyParameters& p = kCieClearSkyType12,
                             const SkyComparisonOptions& options = {});

}  // namespace umbra::atmosphere
