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

/// Angle between two directions, accurate for tiny angles (no acos of a dot product).
double angleBetweenRad(const glm::dvec3& a, const glm::dvec3& b);

/// Angles seen from `pointM`. Positions in metres, any common origin.
ShadowAngles shadowAngles(const glm::dvec3& pointM, const glm::dvec3& sunM, double sunRadiusM,
                          const glm::dvec3& occluderM, double occluderRadiusM);

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

} // namespace umbra::eclipse
