#pragma once
// A star's light from its catalogue numbers: irradiance from the V magnitude relative to
// the Sun's, its colour temperature from B-V, and its colour.
#include "Photometry.hpp"  // kSunMagnitudeV

#include <glm/vec3.hpp>

#include <cstdint>

namespace umbra::sky {

/// Irradiance of a star of magnitude `vMag` relative to the Sun's at 1 au:
/// 10^(-0.4 (V - V_sun)), V_sun = kSunMagnitudeV.
double irradianceRelativeToSun(double vMag);

/// Effective temperature from B-V (Ballesteros 2012, EPL 97, 34008):
/// T = 4600 K (1 / (0.92 (B-V) + 1.7) + 1 / (0.92 (B-V) + 0.62)), for B-V in [-0.4, 2.0]
/// (clamped there: beyond it the formula leaves the stars it was fitted to; at
/// B-V = -0.6739 it would divide by zero).
double ballesterosTemperatureK(double bMinusV);

/// CIE 1931 XYZ of a blackbody at `temperatureK` (Planck's law through the colour-matching
/// functions in 1 nm steps, 360-830 nm), scaled to Y = 1.
glm::dvec3 blackbodyXyz(double temperatureK);

/// Its colour as umbra shows the Sun's: linear sRGB of blackbodyXyz, with no white balance
/// of its own (the Sun's spectrum takes the same route), at unit luminance.
glm::dvec3 blackbodyLinearSrgb(double temperatureK);

/// blackbodyLinearSrgb(ballesterosTemperatureK(bMinusV)).
glm::dvec3 starLinearSrgb(double bMinusV);

/// A star's illuminance at normal incidence [lx] above any atmosphere: the Sun's at 1 au
/// (atmosphere::solarIlluminanceLux, from its spectrum) times irradianceRelativeToSun(V).
double starIlluminanceLux(double vMag);


/// The Sun's colour in linear sRGB at unit luminance: the top-of-atmosphere solar spectrum
/// (atmosphere::solarXyzLux) through the CIE functions. umbra's frames are white-balanced
/// to it: the bare Sun is drawn (1, 1, 1) times its irradiance.
glm::dvec3 sunLinearSrgb();

/// A star's colour in the frames' white balance: starLinearSrgb(bMinusV) divided channel by
/// channel by sunLinearSrgb(), so that a star with the Sun's spectrum would be (1, 1, 1)
/// and undoing the balance (times sunLinearSrgb) gives back luminance 1. Tabulated in
/// 0.01 steps of B-V (the catalogue's precision: exact there), linear in between.
glm::dvec3 starFrameColour(double bMinusV);

/// A planet's colour in the frames' white balance: sunlight reddened by its reflectance,
/// starFrameColour(bMinusV) / starFrameColour(sunBMinusV) channel by channel, so that a
/// grey planet (the Sun's own B-V) is (1, 1, 1), the Sun's colour.
glm::dvec3 reflectedFrameColour(double bMinusV, double sunBMinusV);

/// A star's irradiance above any atmosphere in the frames' units: linear sRGB in W m^-2,
/// white-balanced to the Sun, for a Sun of `sunIrradianceAt1AuWm2` at 1 au:
/// sunIrradianceAt1AuWm2 * irradianceRelativeToSun(vMag) * starFrameColour(bMinusV).
glm::dvec3 starFrameIrradianceWm2(double vMag, double bMinusV, double sunIrradianceAt1AuWm2);

/// The air mass at a zenith angle (Kasten & Young 1989, Applied Optics 28, 4735):
/// 1 / (cos z + 0.50572 (96.07995 - z[deg])^-1.6364); 1 at the zenith, 38 at the horizon.
/// Throws std::invalid_argument for z outside [0, 90] deg.
double airMass(double zenithAngleRad);

/// Scintillation: a factor exp(s g - s^2 / 2) on a star's irradiance, log-normal with mean 1
/// (g a standard normal draw), s = min(sigmaAtZenith * X^(3/2), 1): the variance of the log
/// grows as the air mass cubed (Young 1967, AJ 72, 747). g comes from (seed, index) by a
/// counter-based hash: the same pair always gives the same factor, whatever else is drawn.
/// Throws std::invalid_argument for a negative or non-finite sigma or an air mass below 1.
double scintillationFactor(double sigmaAtZenith, double airMassX, std::uint64_t seed, std::uint64_t index);

/// The zenith of a dark site's moonless night sky at the ground, V mag per square arcsecond
/// (airglow, zodiacal light and unresolved stars together; Benn & Ellison 1998 measured
/// 21.9 at La Palma at solar minimum, Walker's dark sites 21.6-22.0).
inline constexpr double kDarkSkyZenithVMagPerArcsec2 = 22.0;

/// The radiance of a surface brightness of `vMagPerArcsec2` in the frames' units (W m^-2
/// sr^-1 of white-balanced sunlight): irradianceRelativeToSun(mu) * E_sun per square
/// arcsecond, times the square arcseconds in a steradian.
double radianceOfSurfaceBrightnessWm2Sr(double vMagPerArcsec2, double sunIrradianceAt1AuWm2);

/// The night sky's glow above an atmosphere of zenith optical depth `zenithOpticalDepth`
/// (at 550 nm), in the frames' units: the dark site's kDarkSkyZenithVMagPerArcsec2 at the
/// ground's zenith divided by the zenith transmittance exp(-tau), less `milkyWayMeanWm2Sr`,
/// the mean over the sky of a Milky Way drawn with it (its unresolved stars are then the
/// map's; sky/MilkyWay.hpp), and at least 0.
double nightGlowAboveAirWm2Sr(double zenithOpticalDepth, double sunIrradianceAt1AuWm2,
                              double milkyWayMeanWm2Sr = 0.0);

}  // namespace umbra::sky
