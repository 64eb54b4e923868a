#pragma once
// Apparent V magnitudes of the planets after Mallama & Hilton 2018, "Computing apparent
// planetary magnitudes for The Astronomical Almanac" (Astronomy and Computing 25, 10-24):
// V = V(1, alpha) + 5 log10(r delta), r the planet's distance from the Sun and delta from
// the observer in au, alpha the phase angle (Sun-planet-observer) in degrees, and V(1, alpha)
// their fitted phase curves:
//   Mercury  eq. 2: -0.613 + 6.3280e-2 a - 1.6336e-3 a^2 + 3.3644e-5 a^3 - 3.4265e-7 a^4
//                   + 1.6893e-9 a^5 - 3.0334e-12 a^6
//   Venus    eq. 3 (a < 163.7): -4.384 - 1.044e-3 a + 3.687e-4 a^2 - 2.814e-6 a^3 + 8.938e-9 a^4;
//            eq. 4 (a >= 163.7): 236.05828 - 2.81914 a + 8.39034e-3 a^2
//   Mars     eq. 6 (a <= 50): -1.601 + 2.267e-2 a - 1.302e-4 a^2;
//            eq. 7 (a > 50): -0.367 - 0.02573 a + 3.445e-4 a^2;
//            plus the corrections for the longitude facing the observer and the season of
//            Mallama 2007 (Icarus 192, 404, tables 6 and 8: every 10 degrees of the effective
//            central meridian and of L_s), interpolated by Stirling's central differences
//   Jupiter  eq. 8 (a <= 12): -9.395 - 3.7e-4 a + 6.16e-4 a^2;
//            eq. 9 (a > 12): -9.428 - 2.5 log10(1 - 1.507 x - 0.363 x^2 - 0.062 x^3
//                   + 2.809 x^4 - 1.876 x^5), x = a / 180
//   Saturn   eq. 10, globe and rings (a <= 6.5 and b <= 27): -8.914 - 1.825 sin b + 0.026 a
//                   - 0.378 sin b exp(-2.25 a), b = sqrt(b_sun b_obs) from the saturnicentric
//                   latitudes of the Sun and the observer over the ring plane (0 when they are
//                   on opposite sides: the observer sees the rings' unlit face);
//            the globe alone (the rings have no fit beyond those limits, as seen from beyond
//            the Earth): eq. 11 (a <= 6.5) -8.95 - 3.7e-4 a + 6.16e-4 a^2; eq. 12 (a > 6.5)
//                   -8.94 + 2.446e-4 a + 2.672e-4 a^2 - 1.506e-6 a^3 + 4.767e-9 a^4
#include <string>

namespace umbra::sky {

/// The planets' B-V colour indices, whole disc near full phase: Mercury 0.97, Venus 0.81,
/// Mars 1.43, Jupiter 0.87, Saturn (with its rings) 1.09 (NASA report NTRS 19710009758's
/// table, which also gives the Moon's 0.92). Throws std::invalid_argument for another name.
double planetBMinusV(const std::string& planet);

double mercuryMagnitudeV(double rAu, double deltaAu, double phaseAngleDeg);
double venusMagnitudeV(double rAu, double deltaAu, double phaseAngleDeg);
double jupiterMagnitudeV(double rAu, double deltaAu, double phaseAngleDeg);
/// Saturn with its rings (eq. 10) where the fit holds, else its globe alone (eqs. 11-12:
/// at 6.5 deg the value steps by the rings' share, 0.2-1.1 mag, as the published fits do).
/// The latitudes are saturnicentric, over the ring plane (its equator), in degrees.
double saturnMagnitudeV(double rAu, double deltaAu, double phaseAngleDeg, double sunLatitudeDeg,
                        double observerLatitudeDeg);
/// Saturn's globe alone (eqs. 11-12).
double saturnGlobeMagnitudeV(double rAu, double deltaAu, double phaseAngleDeg);
/// The rings' effective tilt of eq. 10: sqrt(b_sun b_obs), 0 for opposite signs [deg].
double saturnRingTiltDeg(double sunLatitudeDeg, double observerLatitudeDeg);

/// The Sun's B-V (Ramirez et al. 2012, ApJ 752, 5: 0.653).
inline constexpr double kSunBMinusV = 0.653;

/// How Mars is turned and where it is in its year, for its corrections (degrees): the
/// longitudes of the sub-observer and sub-solar points (west, as the Astronomical Almanac
/// and Horizons give them) and its heliocentric ecliptic longitude (L_s = that - 85).
struct MarsAspect {
  double subObserverLonDeg = 0.0;
  double subSolarLonDeg = 0.0;
  double heliocentricEclipticLonDeg = 0.0;
};
/// Mars with its rotation and orbit corrections (each within +-0.09 mag).
double marsMagnitudeV(double rAu, double deltaAu, double phaseAngleDeg, const MarsAspect& aspect);
/// The corrections alone: for the effective central meridian (the sub-observer and
/// sub-solar longitudes' mean, across 0 where they straddle it) and for L_s.
double marsRotationCorrection(double effectiveCentralMeridianDeg);
double marsOrbitCorrection(double solarLongitudeDeg);

}  // namespace umbra::sky
