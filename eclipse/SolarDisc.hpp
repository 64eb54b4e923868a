#pragma once
// The Sun as a limb-darkened disc and the fraction of it left visible when a spherical
// occluder covers part of it (eclipse paper, section 2.2, Eq. 1).
//
// Everything here works in *normalised* angles: the solar disc has radius 1 and is centred
// at the origin; the occluder disc has radius `occluderRadius` (= phi_occ / phi_sun) and
// its centre is `separation` (= delta / phi_sun) away. Both discs are treated as flat
// circles in the sky, which is exact to the order of phi_sun^2 (< 2e-5 at 1 au).
#include <algorithm>
#include <cmath>

namespace umbra::eclipse {

/// Solar radius used by the eclipse papers [m].
inline constexpr double kSunRadiusM = 696342e3;
/// Linear limb-darkening coefficient of Eq. 1.
inline constexpr double kDefaultLimbDarkening = 0.6;

/// Luminance of the limb-darkened disc at normalised radius rho in [0, 1] (Eq. 1),
/// normalised so that its mean over the disc is 1 (the uniform disc's flux).
double limbDarkenedLuminance(double rho, double limbDarkening);
/// The same at rho^2 = rho2 (inline: the limb views' inner loop).
inline double limbDarkenedLuminanceAtSquare(double rho2, double limbDarkening) {
  const double mu = std::sqrt(std::max(0.0, 1.0 - rho2));
  // times the reciprocal: in a loop at one limbDarkening it is computed once
  return (1.0 - limbDarkening * (1.0 - mu)) * (1.0 / (1.0 - limbDarkening / 3.0));
}

/// Flux of the limb-darkened disc inside radius rho, as a fraction of the whole disc's.
double limbDarkenedFluxInside(double rho, double limbDarkening);

/// Area of the lens where the unit solar disc and the occluder disc overlap.
/// Exact closed form, written to stay accurate when one disc is 1e7 times the other.
double discOverlapArea(double occluderRadius, double separation);

/// Fraction of a uniform solar disc left visible (1 - overlap / pi), accurate also
/// when the visible part is tiny.
double visibleFractionUniform(double occluderRadius, double separation);

struct QuadratureResult {
  double value = 0.0;       ///< the visible fraction
  double errorEstimate = 0.0;
  int levels = 0;            ///< tanh-sinh refinement levels used (0: closed form)
};

/// Fraction of the limb-darkened solar disc (Eq. 1) left visible. The occluded part is
/// integrated over rings of the solar disc (tanh-sinh quadrature, which is exact at the
/// square-root end points); the smaller of the visible and the hidden flux is integrated,
/// so both a grazing contact and a nearly total eclipse keep their relative accuracy.
QuadratureResult visibleFractionLimbDarkened(double occluderRadius, double separation,
    double limbDarkening = kDefaultLimbDarkening, double relativeTolerance = 1e-10);

/// Fraction of a uniform solar disc above a straight horizon whose chord lies `d` disc
/// radii below the disc's centre (d = 1: the whole disc is up, d = -1: none, d = 0: half).
/// The circular segment of the terrain paper's Eq. 7, (pi - acos d + d sqrt(1 - d^2)) / pi,
/// formed from the smaller cap so that a thin sliver keeps its relative accuracy.
double visibleFractionAboveHorizon(double d);

/// The same for the limb-darkened disc of Eq. 1 (linear law, coefficient u), in closed
/// form: a chord at height y of the disc carries 2(1-u) sqrt(1-y^2) + u (pi/2)(1-y^2).
double visibleFractionAboveHorizonLimbDarkened(double d, double limbDarkening = kDefaultLimbDarkening);

} // namespace umbra::eclipse
