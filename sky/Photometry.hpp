#pragma once
// The photometry of a dusty airless body (the Moon, Phobos, Deimos): the
// Hapke–Lommel–Seeliger reflectance of the day-and-night-sky paper (Eq. 3, Hapke 1966 in
// the form of Jensen et al. 2001) with its opposition surge, its integral over the disc,
// and the apparent magnitude that follows. The GLSL twin is sky/glsl/Photometry.glsl.
//
// The reflectance F is radiance over (irradiance at normal incidence x albedo), in 1/sr:
//
//   F(mu_i, mu_r, alpha) = 2/(3 pi) B(alpha) S(alpha) mu_i / (mu_i + mu_r)
//   B(alpha) = 2 - tan(alpha)/(2 g) (1 - e^{-g/tan alpha}) (3 - e^{-g/tan alpha})   alpha < pi/2
//            = 1                                                                   otherwise
//   S(alpha) = (1 - w) + w [sin alpha + (pi - alpha) cos alpha]/pi + c (1 - cos alpha)^2
//
// mu_i, mu_r: cosines of incidence and emergence; alpha: the phase angle (between the
// directions to the light and to the observer). B is the opposition surge (2 at alpha = 0,
// the surface's shadows hidden; g the surface density), S the phase function of the
// grains: Jensen's is w = 1, c = 0.1 (a Lambert sphere plus a forward term); a share 1 - w
// of isotropic grains flattens it.
//
// Over the disc, mu_i/(mu_i + mu_r) integrates in closed form (the Lommel–Seeliger law):
//   I(alpha) = int_disc F dA / (pi R^2) x pi = B S J / 3,   J(alpha) = 1 - sin(alpha/2) tan(alpha/2) ln cot(alpha/4)
// the flux of the sphere over that of a white Lambert disc of its size at normal incidence,
// so a body of albedo A has geometric albedo p = A I(0) = 2 A / 3 (B(0) = 2, S(0) = J(0) = 1).
#include <glm/vec3.hpp>

#include <string>

namespace umbra::sky {

struct HapkeParameters {
  double oppositionWidth = 0.6;  ///< g (Jensen et al.: 0.6); > 0
  double lambertShare = 1.0;     ///< w in [0, 1]
  double forwardScatter = 0.1;   ///< c >= 0
};

/// How a body reflects light: Lambert's law (radiance = albedo / pi E cos i) or the
/// Hapke–Lommel–Seeliger reflectance (radiance = A E F) with its parameters.
struct Photometry {
  enum class Law { Lambert, Hapke };
  Law law = Law::Lambert;
  HapkeParameters hapke{};
};

/// Jensen et al. 2001's parameters (g 0.6, w 1, c 0.1).
HapkeParameters jensenParameters();
/// The Moon's: fitted to Allen's phase law V(alpha) = -12.73 + 0.026|alpha| + 4e-9 alpha^4
/// (alpha in degrees; within 0.03 mag up to 90 deg, 0.09 up to 120 deg: test_sky's
/// Photometry.PhaseLawOfTheMoon). Phobos and Deimos take them too.
HapkeParameters moonParameters();

/// Throws std::invalid_argument naming the field when a parameter is out of range.
void validate(const HapkeParameters& p);

/// B(alpha): 2 at alpha = 0, 1 from pi/2 on.
double oppositionSurge(double phaseRad, double oppositionWidth);
/// S(alpha): 1 at alpha = 0.
double grainPhase(double phaseRad, const HapkeParameters& p);
/// F in 1/sr; 0 where mu_i <= 0 or mu_r <= 0 (unlit or hidden). phaseRad in [0, pi].
double hapkeReflectance(double cosIncidence, double cosEmergence, double phaseRad, const HapkeParameters& p);

/// J(alpha) = 1 - sin(alpha/2) tan(alpha/2) ln cot(alpha/4): the disc integral of the
/// Lommel–Seeliger law over its value at alpha = 0 (1 at 0, 0 at pi).
double lommelSeeligerPhase(double phaseRad);
/// I(alpha) = B S J / 3 (see the header comment).
double discReflectance(double phaseRad, const HapkeParameters& p);
/// The albedo A (the factor of F) of a body whose geometric albedo is p: A = p / I(0).
double albedoForGeometricAlbedo(double geometricAlbedo, const HapkeParameters& p);

/// The Sun's apparent V magnitude at 1 au (Allen's Astrophysical Quantities).
constexpr double kSunMagnitudeV = -26.74;
/// The apparent V magnitude of a sphere of geometric albedo p (in V) and radius R at
/// distance sunDistanceM from the Sun and observerDistanceM from the observer, seen at
/// phase angle alpha: V_sun - 2.5 log10(p I(alpha)/I(0) (R/Delta)^2 (1 au/r)^2).
double apparentMagnitudeV(double geometricAlbedo, const HapkeParameters& p, double phaseRad, double radiusM,
                          double sunDistanceM, double observerDistanceM);
/// The V magnitude of an irradiance (W m^-2, the Sun's light of 1361 W m^-2 at 1 au being
/// kSunMagnitudeV): what a rendered image's pixels summed over their solid angle give.
double magnitudeOfIrradiance(double irradianceWm2);
/// The Sun's irradiance at 1 au that kSunMagnitudeV stands for (W m^-2).
constexpr double kSolarConstantWm2 = 1361.0;

/// A body's colour from its relative reflectance at 680, 550 and 440 nm (the R, G, B
/// wavelengths of the atmosphere's tables): the sunlight it reflects (the ASTM G173
/// spectrum times the reflectance, interpolated between the three as the atmosphere's
/// colours are: atmosphere/Spectrum.hpp, the solar-ratio rule) in linear sRGB, divided by
/// the Sun's own (the frames' white balance), at unit luminance (its light's Y over the
/// Sun's is the reflectance's luminance-weighted mean: the albedo sets the brightness).
/// Throws std::invalid_argument for a negative, non-finite or all-zero reflectance.
glm::dvec3 reflectanceTint(const glm::dvec3& reflectance680_550_440);

/// "hapke(g=0.72, w=0.72, c=0)" for messages.
std::string describe(const HapkeParameters& p);

}  // namespace umbra::sky
