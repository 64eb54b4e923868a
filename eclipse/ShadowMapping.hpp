#pragma once
// Where a point lies in an occluder's shadow: the apparent angles of Sun and occluder,
// the shadow-LuT coordinates of Eq. 3-4 (eclipse paper, section 5.1), their iterative
// inverse (Eq. 5-6), and the classical umbra / penumbra / antumbra cone geometry.
#include <glm/vec3.hpp>

namespace umbra::eclipse {

/// The three angles that fix the eclipse seen from a point (Eq. 3 and Figure 8).
struct ShadowAngles {
  double sunAngularRadiusRad = 0.0;       ///< phi_sun
  double occluderAngularRadiusRad = 0.0;  ///< phi_occ
  double separationRad = 0.0;             ///< delta, between the centres of Sun and occluder
};

struct LutCoords {
  double u = 0.0;  ///< 1 / (phi_occ / phi_sun + 1): 0 at the occluder, 1 infinitely far
  double v = 0.0;  ///< delta / (phi_occ + phi_sun): 0 on the axis, 1 at the penumbra's edge
};

/// Angular radius of a sphere of radius r seen from distance d (Eq. 3); pi/2 inside it.
double angularRadiusRad(double radiusM, double distanceM);

/// Eq. 3 for distances near d0 (the points of a receiver around its centre): a quadratic
/// in e = d0 / d - 1, phi(d) = phi0 + e (c1 + e c2), the Taylor expansion of asin(r w) in
/// the inverse distance w = 1 / d, in which it is nearly linear (the cubic term is
/// (r / d0)^3 (1 + 2 (r / d0)^2) / (6 (1 - (r / d0)^2)^(5/2)) e^3). A shader evaluates it
/// with two multiply-adds instead of an arctangent.
struct AngularRadiusExpansion {
  double distanceM = 0.0;  ///< d0
  double phi0Rad = 0.0, c1Rad = 0.0, c2Rad = 0.0;
  /// max |angularRadiusRad - at| over [d0 - h, d0 + h] (65 points, both ends included;
  /// the error grows as |e|^3, so it is largest at an end); +infinity when the range
  /// reaches the sphere (d0 - h <= r: no expansion there).
  double maxErrorRad = 0.0;
  double maxPhiRad = 0.0;  ///< Eq. 3 at d0 - h (pi/2 where that is inside the sphere)
  double at(double distanceM) const;
  /// True when the expansion is exact to float precision: maxErrorRad at most 2^-26 (an
  /// eighth of float's epsilon) of phi0. A renderer uses it only then (else Eq. 3 itself).
  bool exactToFloat() const { return maxErrorRad <= 0x1p-26 * phi0Rad; }
};
AngularRadiusExpansion angularRadiusExpansion(double radiusM, double distanceM, double halfWidthM);

/// The largest angle up to which a shader takes the angle between two unit vectors as
/// asin |a x b| by its series to the 7th power (no arctangent): the first term left out,
/// 35/1152 s^9, is below 2^-26 of the angle there.
constexpr double kSmallAngleSeriesMaxRad = 0.15;

/// True when a receiver's shader may compute Eq. 3-4 for one occluder from the
/// expansions of the Sun's and the occluder's angular radius over the receiver and the
/// series angle (both expansions exact to float, and the penumbra, phi_sun + phi_occ,
/// narrower than kSmallAngleSeriesMaxRad everywhere on it). Else Eq. 3-4 exactly.
bool receiverShadowExpands(const AngularRadiusExpansion& sun, const AngularRadiusExpansion& occluder);

/// Angle between two directions, accurate for tiny angles (no acos of a dot product).
double angleBetweenRad(const glm::dvec3& a, const glm::dvec3& b);

/// Angles seen from `pointM`. Positions in metres, any common origin.
ShadowAngles shadowAngles(const glm::dvec3& pointM, const glm::dvec3& sunM, double sunRadiusM,
                          const glm::dvec3& occluderM, double occluderRadiusM);

/// An occluder's figure: a sphere (flattening 0), or an oblate spheroid of flattening f
/// about the unit axis `pole`, of the same volume as the sphere of the body's mean radius
/// (equatorial radius R (1 - f)^(-1/3), polar R (1 - f)^(2/3)). The Earth's f is 1/298.257.
struct Oblateness {
  glm::dvec3 pole{0.0, 0.0, 1.0};
  double flattening = 0.0;
};

/// The equatorial radius of that spheroid: meanRadiusM (1 - f)^(-1/3).
double equatorialRadiusM(double meanRadiusM, const Oblateness& figure);

/// A spheroid of flattening f seen along a direction whose cosine to its pole is
/// `cosViewToPole` shows an ellipse: its semi-axis along the projected pole over the one
/// across it, q = sqrt(1 - e^2 (1 - cos^2)), e^2 = f (2 - f).
double outlinePolarRatio(double cosViewToPole, double flattening);
/// An ellipse of semi-axes 1 and q: its radius in a direction whose squared cosine to the
/// q axis is `cosToMinorSq`, q / sqrt(q^2 + (1 - q^2) cos^2).
double ellipseRadius(double q, double cosToMinorSq);

/// A spheroid seen along `viewDir` (unit) shows an ellipse, of semi-axes a across the
/// projected pole and a q along it, q^2 = 1 - e^2 (1 - (view . pole)^2), e^2 = f (2 - f).
/// Its radius towards `towards` (the part of it across the view) over a: ellipseRadius with
/// outlinePolarRatio's q. 1 across the pole, q along it; for `towards` along the view (no
/// direction across it) or a view along the pole, 1.
double outlineRadiusFactor(const glm::dvec3& viewDir, const glm::dvec3& towards, const Oblateness& figure);

/// The radius of an occluder's outline, seen from `pointM`, in the direction of the Sun
/// from its centre: `meanRadiusM` for a sphere; for a spheroid, its equatorial radius times
/// outlineRadiusFactor. The shadow of the ellipse is taken, at each point, as that of the
/// circle of this radius: the circle that meets the ellipse where the line of centres
/// does (docs/eclipse-shadows.md, "Oblate occluders", gives its error against the
/// spheroid sampled ray by ray).
double outlineRadiusTowardsSunM(const glm::dvec3& pointM, const glm::dvec3& sunM, const glm::dvec3& occluderM,
                                double meanRadiusM, const Oblateness& figure);

/// shadowAngles with an oblate occluder: its angular radius that of outlineRadiusTowardsSunM.
ShadowAngles shadowAngles(const glm::dvec3& pointM, const glm::dvec3& sunM, double sunRadiusM,
                          const glm::dvec3& occluderM, double meanRadiusM, const Oblateness& figure);

/// The fraction of the limb-darkened Sun (coefficient `limbDarkening`, Eq. 1) seen from
/// `pointM` past a spheroid occluder, by brute force: the solar disc sampled on `n` x `n`
/// cells of its bounding square (cell centres inside it), each ray tested against the
/// spheroid itself. The reference for the oblate shadow; its error is about the disc's
/// edge cells, a few 1 / n^1.5.
double visibleFractionPastSpheroid(const glm::dvec3& pointM, const glm::dvec3& sunM, double sunRadiusM,
                                   const glm::dvec3& occluderM, double meanRadiusM, const Oblateness& figure,
                                   double limbDarkening, int n);

/// True when the occluder is nearer than the Sun, i.e. can cast a shadow on the point.
bool occluderInFront(const glm::dvec3& pointM, const glm::dvec3& sunM,
                     const glm::dvec3& occluderM);

/// Eq. 4.
LutCoords lutCoords(const ShadowAngles& angles);

/// The sky as the shadow function sees it, in units of the solar angular radius: the
/// occluder's radius and the separation of the centres (see SolarDisc.hpp).
struct NormalisedDiscs {
  double occluderRadius = 0.0;
  double separation = 0.0;
};
NormalisedDiscs normalisedDiscs(const ShadowAngles& angles);
NormalisedDiscs normalisedDiscs(const LutCoords& coords);  ///< from Eq. 4 solved for the ratios

/// A system of Sun and occluder: what Eq. 5-6 needs besides (u, v).
struct SunOccluderSystem {
  double sunRadiusM = 0.0;
  double occluderRadiusM = 0.0;
  double sunOccluderDistanceM = 0.0;  ///< d in the paper
};

struct InverseMapping {
  ShadowAngles angles;
  double occluderDistanceM = 0.0;  ///< d_occ
  double sunDistanceM = 0.0;       ///< d_sun
  glm::dvec3 pointM{0.0};          ///< the point, with the occluder at the origin and the Sun at (-d, 0, 0)
  LutCoords reached;               ///< (u, v) measured back from pointM (== the input unless clamped)
  int iterations = 0;              ///< Eq. 5-6 steps taken
  bool converged = false;          ///< relative change below the tolerance
  /// u outside what any point behind the occluder can see: closer than the occluder's
  /// surface (u too small) or farther than `maxDistanceFactor` times d (u too close to the
  /// limit r_sun / (r_sun + r_occ)). The nearest reachable u is used instead.
  bool clamped = false;
};

/// Inverse of Eq. 4 (paper, Eq. 5-6): the point behind the occluder whose (u, v) are the
/// given ones. Fixed-point iteration of Eq. 5-6 from d_occ = 0, d_sun = d, accelerated
/// with Steffensen's method where it converges slowly (u near its upper limit), until the
/// relative change of d_occ and d_sun is below `relativeTolerance`. Never returns NaN.
InverseMapping inverseLutCoords(const LutCoords& coords, const SunOccluderSystem& system,
                                double relativeTolerance = 1e-12, int maxIterations = 200,
                                double maxDistanceFactor = 1e3);

/// Radii of the shadow cones at distance `distanceBehindM` behind the occluder's centre,
/// along the axis pointing away from the Sun, from the tangent cones of the two spheres.
struct ShadowConeRadii {
  double umbraRadiusM = 0.0;     ///< 0 beyond the umbra's tip
  double antumbraRadiusM = 0.0;  ///< 0 before the umbra's tip
  double penumbraRadiusM = 0.0;
  double umbraLengthM = 0.0;     ///< from the occluder's centre to the umbra's tip
};
ShadowConeRadii shadowConeRadii(const SunOccluderSystem& system, double distanceBehindM);

/// How far in front of a point, towards a Sun `sunDistanceM` away, an occluder's centre must
/// stand on the line to the Sun for the umbra's cross-section through the point
/// (perpendicular to the axis) to have radius `umbraRadiusM` (< occluderRadiusM; 0: the
/// umbra's tip at the point). From the umbra's radius x behind the occluder,
/// R_occ - x (R_sun - R_occ) / (D - x), solved for x:
///   x = D (R_occ - r) / (R_sun - r).
double occluderDistanceForUmbraM(double sunDistanceM, double sunRadiusM, double occluderRadiusM, double umbraRadiusM);

} // namespace umbra::eclipse
