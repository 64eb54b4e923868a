#pragma once
// The eclipsed Moon's light: the Earth's shadow (a cross-section I/I_sun against the offset
// from the axis, shadowProfile or atmosphericShadowProfile) averaged over the Moon's disc,
// with the Earth's outline an ellipse (its oblateness as the Moon sees it).
#include "ShadowLut.hpp"  // ProfileSample
#include "ShadowMapping.hpp"  // SunOccluderSystem

#include <glm/glm.hpp>

#include <vector>

namespace umbra::eclipse {

/// The Earth's limb seen along the shadow's axis: an ellipse with the equatorial radius
/// across the projected pole and equatorialRadiusM sqrt(1 - e^2 cos^2 delta) along it
/// (delta the axis' declination); the profile was computed for a sphere of profileRadiusM.
struct EarthOutline {
  double equatorialRadiusM = 6378137.0;
  double projectedPolarRadiusM = 6378137.0;
  double profileRadiusM = 6378137.0;
  /// The outline's radius in the direction at angle `fromEquatorRad` from the projected equator.
  double radiusM(double fromEquatorRad) const;
};

/// The outline for an Earth of equatorial radius `a` and flattening `f` seen along an axis
/// of declination `declinationRad`, the profile computed for radius `profileRadiusM`.
EarthOutline earthOutline(double a, double f, double declinationRad, double profileRadiusM);

/// I / I_sun (luminance) on the Moon's disc: its mean over the disc (a uniform disc, as the
/// full Moon nearly is), and at its centre and its two limbs on the line through the axis.
struct EclipsedMoonLight {
  double mean = 1.0, centre = 1.0, nearLimb = 1.0, farLimb = 1.0;
};

/// The profile (offsets from 0 up, increasing) at offset r: linear between samples, its
/// last value beyond them.
double profileLuminanceAt(const std::vector<ProfileSample>& profile, double offsetM);

/// The Moon's disc of radius `moonRadiusM` centred at `moonCentreM` on the shadow's
/// cross-section (x along the projected equator, y along the projected north pole, from the
/// axis). A point at offset r in direction theta sees the profile at r minus the outline's
/// excess over the profile's sphere there (the shadow's edges move with the limb). The
/// disc is summed over `rings` rings of equal width, each in 4 x rings sectors.
/// Throws std::invalid_argument for an empty or non-increasing profile or a radius <= 0.
EclipsedMoonLight eclipsedMoonLight(const std::vector<ProfileSample>& profile, glm::dvec2 moonCentreM,
                                    double moonRadiusM, const EarthOutline& outline, int rings = 96);

/// The eclipsed Moon's integrated V for a Danjon L, by Vital's correlation of the two over
/// the eclipses of 2004-2019: V = 4.2 - 3 L + (L / 2)^2.
double danjonMagnitude(double danjonL);
/// Its inverse on 0..4 (the scale's range; a V brighter than L 4's or fainter than L 0's
/// gives 4 or 0).
double danjonLFromMagnitude(double magnitudeV);

/// A disc's mean surface brightness (mag/arcsec^2) for its integrated magnitude and
/// angular radius.
double meanSurfaceBrightness(double magnitude, double angularRadiusRad);

/// The eclipsed Moon's magnitudes: its integrated V and Danjon L, and the surface
/// brightness (mag/arcsec^2) of the uneclipsed Moon and at the centre and the limbs.
struct EclipsedMoonMagnitudes {
  double v = 0.0, danjonL = 0.0;
  double fullSurface = 0.0, centreSurface = 0.0, nearLimbSurface = 0.0, farLimbSurface = 0.0;
};
/// From the Moon's V outside the shadow (`uneclipsedV`, lit as the shadow's light comes),
/// its angular radius and the shadow's light on it: each I / I_sun as -2.5 log10 of it
/// added (a factor below 1e-30 taken as 1e-30).
EclipsedMoonMagnitudes eclipsedMoonMagnitudes(double uneclipsedV, double moonAngularRadiusRad,
                                              const EclipsedMoonLight& light);

/// The umbra's edge as an atmosphere draws it: the offset where the profile's logarithm
/// rises steepest (between the samples where it does). Throws std::invalid_argument for a
/// profile of fewer than 2 samples or with a value <= 0.
double steepestLogRiseOffsetM(const std::vector<ProfileSample>& profile);

/// How much that edge enlarges the occluder: the radius to add to `system`'s occluder for its
/// geometric umbra, `distanceBehindM` behind it, to reach the profile's edge (the umbra's
/// radius grows by 1 + distance / sun distance per metre of radius). The "physical" rule
/// of the lunar shadow, against Danjon's 1/85 and Chauvenet's 1/50.
double umbraEdgeEnlargementM(const std::vector<ProfileSample>& profile, const SunOccluderSystem& system,
                             double distanceBehindM);

}  // namespace umbra::eclipse
