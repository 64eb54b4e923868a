#pragma once
// How the Moon is seen: phase, illuminated fraction, the position angle of its bright limb
// and its optical libration (Meeus, Astronomical Algorithms, 2nd ed., ch. 48 and 53), as
// plain formulas of angles and vectors. app/scene/Moon.cpp feeds them from the ephemeris.
#include <glm/vec3.hpp>

namespace umbra::sky {

/// The angle between two non-zero vectors, rad in [0, pi] (atan2 of |a x b| and a . b:
/// exact near 0 and pi, where acos of the dot product loses half the digits).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b);

/// The illuminated fraction of the disc, k = (1 + cos i) / 2 (Meeus 48.1).
double illuminatedFraction(double phaseRad);

/// The position angle of the Moon's bright limb, measured from the north point of the
/// disc towards the east, rad in [0, 2 pi) (Meeus 48.5), from the apparent right
/// ascensions and declinations of the Sun (alpha0, delta0) and the Moon.
double brightLimbPositionAngle(double sunRaRad, double sunDecRad, double moonRaRad, double moonDecRad);

/// The inclination of the Moon's mean equator to the ecliptic, I = 1.54242 deg (Meeus ch. 53).
constexpr double kMoonEquatorInclinationRad = 1.54242 * 3.14159265358979323846 / 180.0;

struct Libration {
  double longitudeRad = 0.0;  ///< l': the selenographic longitude of the centre of the disc
  double latitudeRad = 0.0;   ///< b': its latitude
};
/// The optical libration (Meeus 53.1): from the Moon's geocentric ecliptic longitude and
/// latitude referred to the mean equinox of date (lambda without nutation), the longitude
/// of its mean ascending node Omega and its argument of latitude F. l' is wrapped to
/// (-pi, pi].
Libration opticalLibration(double meanLongitudeRad, double latitudeRad, double ascendingNodeRad,
                           double argumentOfLatitudeRad);

}  // namespace umbra::sky
