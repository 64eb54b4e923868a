#pragma once
// The Moon's numbers at an instant, for an observer on the Earth or the Earth's centre:
// where it stands, how far, how large, its phase, brightness and libration, and the
// earthshine on it (umbra moon, the GUI's status line). Positions from ERFA
// (eraMoon98: Meeus's series; eraEpv00), the formulas from sky/ (MoonGeometry,
// Photometry, Earthshine).
#include "scene/Scene.hpp"
#include "scene/Time.hpp"

#include <optional>
#include <string>

namespace umbra::scene {

struct MoonNumbers {
  UtcTime time;
  bool topocentric = false;           ///< seen from an observer (else from the Earth's centre)
  // Where: the direction from the observer, geometric (no light time, aberration or
  // refraction), on the true equator and equinox of date.
  double rightAscensionDeg = 0.0;     ///< [0, 360)
  double declinationDeg = 0.0;
  std::optional<double> altitudeDeg;  ///< above the observer's geodetic horizon (observer only)
  std::optional<double> azimuthDeg;   ///< from north through east (observer only)
  // The geocentric ecliptic longitude and latitude on the mean ecliptic and equinox of
  // date (Meeus ch. 47's lambda and beta, without nutation).
  double eclipticLongitudeDeg = 0.0;
  double eclipticLatitudeDeg = 0.0;
  double distanceKm = 0.0;            ///< centre to centre, from the observer
  double angularDiameterArcmin = 0.0;
  double phaseAngleDeg = 0.0;         ///< at the Moon, between the Sun (aberrated) and the observer
  double illuminatedFraction = 0.0;
  double brightLimbPositionAngleDeg = 0.0;  ///< from the disc's north point through east
  double magnitudeV = 0.0;            ///< outside eclipses (sky::apparentMagnitudeV, the Moon preset)
  double librationLongitudeDeg = 0.0; ///< optical (Meeus ch. 53), geocentric
  double librationLatitudeDeg = 0.0;
  double earthshineWm2 = 0.0;         ///< on the Moon (sky::earthshineIrradiance)
};

/// The numbers at `time`, seen from `observer` on the Earth (its body must be "Earth";
/// std::invalid_argument otherwise) or from the Earth's centre.
MoonNumbers moonNumbers(UtcTime time, const std::optional<Observer>& observer);

/// Where the Moon was (heliocentric, metres, ICRS axes) when the light that reaches
/// `observerM` (heliocentric) at `time` passed it: its place one light time from its near
/// surface earlier, as scenes take it (eclipse::occluderSeenBy; about 1.3 s from the Earth:
/// some 40 km along the Earth's orbit, the 20 arcseconds of the aberration of the Sun's
/// light). With the Sun at rest at the origin, the Moon's shadow at `observerM` is cast by
/// the Moon there.
glm::dvec3 moonSeenFromM(UtcTime time, const glm::dvec3& observerM);

/// The Sun and the Moon seen from an observer on the Earth at an instant, in the
/// observer's horizon frame: x east, y north, z up (the geodetic horizon), metres from the
/// observer. The Moon as moonSeenFromM places it, the Sun at rest at its centre. What the
/// Moon's shadow on and over the observer is made from.
struct SunAndMoonInHorizon {
  glm::dvec3 sunM{0.0}, moonM{0.0};
  double sunRadiusM = 0.0, moonRadiusM = 0.0;
};
SunAndMoonInHorizon sunAndMoonInHorizon(UtcTime time, const Observer& observer);

/// describeMoon for a scene with the Moon (its preset) and a time, seen from the camera's
/// observer when it stands on the Earth, else from the Earth's centre; nothing otherwise.
std::optional<std::string> describeMoonOf(const Scene& scene);

/// One line for a status bar: "Moon: alt 34.2 deg, az 140.3 deg, 31.2', phase 64.1 deg
/// (72 % lit), V -11.1, libration +3.4/-5.1 deg".
std::string describeMoon(const MoonNumbers& m);

}  // namespace umbra::scene
