#pragma once
// Body positions and orientations from ERFA and the IAU WGCCRE rotation models.
//
// Frame: heliocentric (origin at the centre of the Sun), axes aligned with ICRS/GCRS
// (equatorial J2000), metres.
#include "scene/Time.hpp"

#include <glm/glm.hpp>

#include <string>

namespace umbra::scene {

/// The mean obliquity of the ecliptic at J2000 (IAU 2006: 84381.406 arcseconds), radians.
inline constexpr double kObliquityJ2000Rad = 84381.406 / 3600.0 * 3.14159265358979323846 / 180.0;

/// True for the bodies heliocentricPositionM knows: Sun, Earth, Moon, Mars.
bool hasEphemeris(const std::string& body);

/// Heliocentric position in metres: Sun (zero), Earth (eraEpv00), Moon (Earth +
/// moonGeocentricElpM), Mars (eraPlan94). Throws std::invalid_argument for other bodies.
glm::dvec3 heliocentricPositionM(const std::string& body, UtcTime time);

/// Heliocentric velocity in m/s of the same bodies: the Sun zero (its 13 m/s about the
/// barycentre left out), the Earth's and Mars' from their theories, the Moon's the
/// Earth's plus eraMoon98's (ELP's truncated series: its velocity within 0.1 %, all that
/// the light-time corrections it serves need). Throws std::invalid_argument as above.
glm::dvec3 heliocentricVelocityMps(const std::string& body, UtcTime time);

/// The Moon's geocentric position in metres (ICRS axes) at a Terrestrial Time Julian date,
/// from the lunar theory ELP 2000-82B with every term (libnova; Chapront-Touze & Chapront):
/// well under an arcsecond over 1900-2100, against eraMoon98's ~10 arcseconds, at 2 ms a
/// call against 3 us. Its mean ecliptic and equinox of J2000 are turned to ICRS axes by the
/// IAU 2006 obliquity (the 0.05 arcsecond frame bias between them is left out). The
/// eclipse predictions and the scenes' Moon (heliocentricPositionM) take it.
glm::dvec3 moonGeocentricElpM(double ttJd);

/// eraMoon98 (Meeus' truncated ELP series: ~10 arcseconds) at a TT Julian date:
/// the Moon's geocentric position in metres, ICRS axes.
glm::dvec3 moonGeocentricMeeusM(double ttJd);

/// The Earth's heliocentric position in metres (ICRS axes; eraEpv00, fitted to JPL's DE405
/// to a few km over 1900-2100) at a TT Julian date.
glm::dvec3 earthHeliocentricM(double ttJd);

/// The planets' heliocentric positions in metres (ICRS axes) from ERFA's eraPlan94 (Simon
/// et al. 1994: a few arcseconds over 1800-2050 for the inner planets, some tens for the
/// outer ones): "Mercury", "Venus", "Mars", "Jupiter", "Saturn", "Uranus", "Neptune".
/// Throws std::invalid_argument for other names.
glm::dvec3 planetHeliocentricPositionM(const std::string& planet, UtcTime time);

/// "" at times the ephemerides are made for, else a note that positions degrade there:
/// ERFA's Earth ephemeris (eraEpv00, which the Moon's and every heliocentric place go
/// through) is fitted to 1900-2100; outside, it still gives positions, less exact.
std::string ephemerisRangeNote(UtcTime time);

/// True for the bodies bodyFixedToInertial knows: Sun, Earth, Moon, Mars.
bool hasRotationModel(const std::string& body);

/// Rotation from the body-fixed frame (z = north pole, x = prime meridian) to the
/// ICRS-aligned frame. Throws std::invalid_argument for bodies without a model.
glm::dmat3 bodyFixedToInertial(const std::string& body, UtcTime time);

/// The Sun seen from the centre of a body (heliocentricPositionM, bodyFixedToInertial).
struct SunFromBody {
  glm::dvec3 directionBodyFixed{0.0, 0.0, 1.0};  ///< unit vector towards the Sun, body-fixed frame
  double distanceM = 0.0;
  double angularRadiusRad = 0.0;                 ///< of the Sun's disc
};

/// The Sun from `body` at `time`: what a terrain on it is lit by (terrain::bodyFixedToTangent
/// turns the direction into a grid's tangent frame; over a 100 km patch it changes by
/// < 1e-6 rad). Throws std::invalid_argument for the Sun and for a body without an
/// ephemeris or a rotation model.
SunFromBody sunFromBody(const std::string& body, UtcTime time);

/// Rotation from the body-fixed frame to ICRS for an IAU pole (alpha0, delta0) and
/// prime meridian angle W, all in degrees.
glm::dmat3 iauBodyFixedToInertial(double alpha0Deg, double delta0Deg, double wDeg);

} // namespace umbra::scene
