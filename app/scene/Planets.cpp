#include "scene/Planets.hpp"

#include "scene/Ephemeris.hpp"

#include "PlanetMagnitudes.hpp"
#include "ShadowLut.hpp"  // kLightSpeedMps

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kAuM = 149597870700.0;

/// A longitude in [0, 360) degrees.
double wrapDeg(double deg) {
  deg = std::fmod(deg, 360.0);
  return deg < 0.0 ? deg + 360.0 : deg;
}

/// Saturn's north pole (IAU WGCCRE 2015, Archinal et al. 2018: alpha0 = 40.589 - 0.036 T,
/// delta0 = 83.537 - 0.004 T degrees, T in Julian centuries from J2000), ICRS axes: the
/// body frame's z axis (its rotation about the pole does not matter here).
glm::dvec3 saturnPoleIcrs(UtcTime time) {
  double t1 = 0.0, t2 = 0.0;
  toTt(time, t1, t2);
  const double t = ((t1 - 2451545.0) + t2) / 36525.0;
  return iauBodyFixedToInertial(40.589 - 0.036 * t, 83.537 - 0.004 * t, 0.0)[2];
}

/// The saturnicentric latitude of `direction` (a unit vector from Saturn's centre) [deg].
double latitudeOverPoleDeg(const glm::dvec3& pole, const glm::dvec3& direction) {
  return std::asin(std::clamp(glm::dot(pole, direction), -1.0, 1.0)) / kDeg;
}

/// The longitude (west, degrees, as the Astronomical Almanac gives Mars') of the point of
/// Mars under `direction` (ICRS axes, from Mars' centre).
double westLongitudeDeg(const glm::dmat3& bodyToIcrs, const glm::dvec3& direction) {
  const glm::dvec3 b = glm::transpose(bodyToIcrs) * direction;
  return wrapDeg(-std::atan2(b.y, b.x) / kDeg);
}

}  // namespace

const std::vector<std::string>& planetsWithMagnitudes() {
  static const std::vector<std::string> names{"Mercury", "Venus", "Mars", "Jupiter", "Saturn"};
  return names;
}

std::vector<PlanetSeen> planetsSeenFrom(const glm::dvec3& observerM, UtcTime time) {
  if (!(std::isfinite(observerM.x) && std::isfinite(observerM.y) && std::isfinite(observerM.z)))
    throw std::invalid_argument("planets: the observer's position is not finite");
  std::vector<PlanetSeen> out;
  for (const std::string& name : planetsWithMagnitudes()) {
    // The planet where the light left it: one light time back, found twice.
    glm::dvec3 planet = planetHeliocentricPositionM(name, time);
    UtcTime departure = time;
    for (int k = 0; k < 2; ++k) {
      departure = addSeconds(time, -glm::length(planet - observerM) / eclipse::kLightSpeedMps);
      planet = planetHeliocentricPositionM(name, departure);
    }
    const glm::dvec3 toObserver = observerM - planet;
    const double delta = glm::length(toObserver), r = glm::length(planet);
    if (delta < kNearPlanetM) continue;
    PlanetSeen p;
    p.name = name;
    p.directionIcrs = -toObserver / delta;
    p.distanceAu = delta / kAuM;
    p.sunDistanceAu = r / kAuM;
    p.phaseAngleDeg = std::acos(std::clamp(glm::dot(-planet / r, toObserver / delta), -1.0, 1.0)) / kDeg;
    if (name == "Mercury") {
      p.magnitudeV = sky::mercuryMagnitudeV(p.sunDistanceAu, p.distanceAu, p.phaseAngleDeg);
    } else if (name == "Venus") {
      p.magnitudeV = sky::venusMagnitudeV(p.sunDistanceAu, p.distanceAu, p.phaseAngleDeg);
    } else if (name == "Jupiter") {
      p.magnitudeV = sky::jupiterMagnitudeV(p.sunDistanceAu, p.distanceAu, p.phaseAngleDeg);
    } else if (name == "Saturn") {  // its rings, by the Sun's and the observer's latitudes over them
      const glm::dvec3 pole = saturnPoleIcrs(departure);
      const double sunLat = latitudeOverPoleDeg(pole, -planet / r);
      p.ringTiltDeg = latitudeOverPoleDeg(pole, toObserver / delta);
      p.magnitudeV = sky::saturnMagnitudeV(p.sunDistanceAu, p.distanceAu, p.phaseAngleDeg, sunLat, p.ringTiltDeg);
    } else {  // Mars: its face towards the observer and the Sun, and its season
      const glm::dmat3 bodyToIcrs = bodyFixedToInertial("Mars", departure);
      sky::MarsAspect aspect;
      aspect.subObserverLonDeg = westLongitudeDeg(bodyToIcrs, toObserver / delta);
      aspect.subSolarLonDeg = westLongitudeDeg(bodyToIcrs, -planet / r);
      const double yEcliptic = std::cos(kObliquityJ2000Rad) * planet.y + std::sin(kObliquityJ2000Rad) * planet.z;
      aspect.heliocentricEclipticLonDeg = wrapDeg(std::atan2(yEcliptic, planet.x) / kDeg);
      p.magnitudeV = sky::marsMagnitudeV(p.sunDistanceAu, p.distanceAu, p.phaseAngleDeg, aspect);
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace umbra::scene
