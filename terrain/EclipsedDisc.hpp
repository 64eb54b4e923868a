#pragma once
// The Sun's disc cut by the horizon and covered by an occluding body at once: what a
// receiver on terrain sees of the Sun during an eclipse (the Earth in front of it, seen
// from the Moon; Phobos, seen from Mars). Neither the horizon's fraction (Eq. 7) nor the
// eclipse's (eclipse/SolarDisc.hpp) alone, nor their product: the part of the disc above
// the horizon *and* outside the occluder's disc, limb-darkened.
//
// Disc coordinates: the Sun's centre at the origin, its radius 1; x along the receiver's
// horizon, y up; the horizon is the line y = -d (d: the Sun's centre above the horizon in
// solar radii, as SoftShadow's discFractionForOffset takes it). Flat discs in the sky, as
// eclipse/SolarDisc.hpp.
#include <glm/glm.hpp>

namespace umbra::terrain {

/// An occluder's disc on the Sun's: its centre (x, y) and radius, in solar radii.
struct OccluderOnDisc {
  double x = 0.0, y = 0.0, radius = 0.0;
};

/// The occluder seen from a receiver whose vertical is `up`: the Sun and the occluder
/// towards unit vectors sunDir and occluderDir with angular radii [rad]. Directions in
/// any one frame.
OccluderOnDisc occluderOnDisc(const glm::dvec3& sunDir, double sunRadiusRad, const glm::dvec3& occluderDir,
                              double occluderRadiusRad, const glm::dvec3& up);

/// Whether the occluder's disc touches the Sun's at all.
inline bool overlaps(const OccluderOnDisc& o) { return o.radius > 0.0 && glm::length(glm::dvec2(o.x, o.y)) < 1.0 + o.radius; }

/// The visible fraction of the disc (linear limb darkening u in [0, 1]) above the horizon
/// y = -d and outside the occluder: over the disc's heights y, Gauss-Legendre on pieces
/// between the horizon, the disc's and the occluder's top and bottom (each piece through
/// y = mid + half sin(phi), which takes away the square roots at its ends), the chord's
/// visible stretches at each y in closed form. Accurate to about 1e-7.
double visibleFractionAboveHorizonOutside(double d, const OccluderOnDisc& occluder, double limbDarkening);

/// The same by brute force, the reference: the disc's n x n cell centres, each weighed by
/// its luminance, counted where above the horizon and outside the occluder.
double visibleFractionAboveHorizonOutsideSampled(double d, const OccluderOnDisc& occluder, double limbDarkening, int n);

} // namespace umbra::terrain
