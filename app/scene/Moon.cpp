#include "scene/Moon.hpp"

#include "scene/Bodies.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Units.hpp"

#include "Earthshine.hpp"
#include "MoonGeometry.hpp"
#include "Photometry.hpp"
#include "ShadowLut.hpp"  // occluderSeenBy

#include <erfa.h>
#include <erfam.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace umbra::scene {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

glm::dvec3 rotate(const double r[3][3], const glm::dvec3& v) {
  return {r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z, r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
          r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z};
}

// Longitude in [0, 360) and latitude of a vector, degrees.
void lonLat(const glm::dvec3& v, double& lonDeg, double& latDeg) {
  lonDeg = std::atan2(v.y, v.x) / kDeg;
  if (lonDeg < 0.0) lonDeg += 360.0;
  latDeg = std::atan2(v.z, std::hypot(v.x, v.y)) / kDeg;
}

// The Moon's heliocentric velocity over the speed of light (eraEpv00 + eraMoon98).
glm::dvec3 moonVelocityOverC(double tt1, double tt2) {
  double earth[2][3], barycentric[2][3], moon[2][3];
  eraEpv00(tt1, tt2, earth, barycentric);
  eraMoon98(tt1, tt2, moon);
  constexpr double kCAuPerDay = ERFA_CMPS * 86400.0 / ERFA_DAU;
  return glm::dvec3(earth[1][0] + moon[1][0], earth[1][1] + moon[1][1], earth[1][2] + moon[1][2]) / kCAuPerDay;
}

}  // namespace

MoonNumbers moonNumbers(UtcTime time, const std::optional<Observer>& observer) {
  if (observer && observer->body != "Earth")
    throw std::invalid_argument("the Moon's numbers are for an observer on the Earth, not on '" + observer->body + "'");
  double tt1 = 0.0, tt2 = 0.0;
  toTt(time, tt1, tt2);
  const Body earth = presetBody("Earth", time), moon = presetBody("Moon", time);
  const glm::dvec3 sunM(0.0);
  const glm::dvec3 eyeM = observer ? observerPositionM(earth, *observer, time) : earth.positionM;

  MoonNumbers m;
  m.time = time;
  m.topocentric = observer.has_value();
  const glm::dvec3 toMoon = moon.positionM - eyeM, toSun = sunM - eyeM;
  double npb[3][3];
  eraPnm06a(tt1, tt2, npb);  // GCRS to the true equator and equinox of date
  double sunRa = 0.0, sunDec = 0.0;
  lonLat(rotate(npb, toMoon), m.rightAscensionDeg, m.declinationDeg);
  lonLat(rotate(npb, toSun), sunRa, sunDec);
  m.brightLimbPositionAngleDeg =
      sky::brightLimbPositionAngle(sunRa * kDeg, sunDec * kDeg, m.rightAscensionDeg * kDeg, m.declinationDeg * kDeg) /
      kDeg;
  if (observer) {
    const double lat = observer->latDeg * kDeg, lon = observer->lonDeg * kDeg;
    const glm::dmat3 toInertial = bodyFixedToInertial("Earth", time);
    const glm::dvec3 east = toInertial * glm::dvec3(-std::sin(lon), std::cos(lon), 0.0);
    const glm::dvec3 north =
        toInertial * glm::dvec3(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
    const glm::dvec3 up =
        toInertial * glm::dvec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
    const glm::dvec3 d = glm::normalize(toMoon);
    m.altitudeDeg = std::asin(std::clamp(glm::dot(d, up), -1.0, 1.0)) / kDeg;
    double az = std::atan2(glm::dot(d, east), glm::dot(d, north)) / kDeg;
    m.azimuthDeg = az < 0.0 ? az + 360.0 : az;
  }

  const glm::dvec3 geocentric = moon.positionM - earth.positionM;
  double ecliptic[3][3];
  eraEcm06(tt1, tt2, ecliptic);  // GCRS to the mean ecliptic and equinox of date
  lonLat(rotate(ecliptic, geocentric), m.eclipticLongitudeDeg, m.eclipticLatitudeDeg);

  const double distanceM = glm::length(toMoon);
  m.distanceKm = distanceM / 1000.0;
  m.angularDiameterArcmin = 2.0 * std::asin(std::min(1.0, moon.radiusM / distanceM)) / kDeg * 60.0;
  // The Sun as the Moon sees it: aberrated by the Moon's heliocentric velocity (20", as
  // Meeus's apparent positions count it).
  const glm::dvec3 toSunFromMoon = glm::normalize(sunM - moon.positionM) + moonVelocityOverC(tt1, tt2);
  const double phase = sky::angleBetween(toSunFromMoon, eyeM - moon.positionM);
  m.phaseAngleDeg = phase / kDeg;
  m.illuminatedFraction = sky::illuminatedFraction(phase);
  m.magnitudeV = sky::apparentMagnitudeV(moon.albedo, moon.photometry.hapke, phase, moon.radiusM,
                                         glm::length(moon.positionM - sunM), distanceM);

  const double t = ((tt1 - 2451545.0) + tt2) / 36525.0;  // TT for TDB: < 2 ms apart
  const sky::Libration l =
      sky::opticalLibration(m.eclipticLongitudeDeg * kDeg, m.eclipticLatitudeDeg * kDeg, eraFaom03(t), eraFaf03(t));
  m.librationLongitudeDeg = l.longitudeRad / kDeg;
  m.librationLatitudeDeg = l.latitudeRad / kDeg;

  const double auOverR = kAuM / glm::length(earth.positionM - sunM);
  m.earthshineWm2 = sky::earthshineIrradiance(sky::kSolarConstantWm2 * auOverR * auOverR, earth.albedo, earth.radiusM,
                                              glm::length(geocentric),
                                              sky::angleBetween(sunM - earth.positionM, geocentric));
  return m;
}

std::string describeMoon(const MoonNumbers& m) {
  char text[200];
  std::string where;
  if (m.altitudeDeg) {
    std::snprintf(text, sizeof text, "alt %.1f deg, az %.1f deg, ", *m.altitudeDeg, *m.azimuthDeg);
    where = text;
  }
  std::snprintf(text, sizeof text, "Moon: %s%.1f', phase %.1f deg (%.0f %% lit), V %.1f, libration %+.1f/%+.1f deg",
                where.c_str(), m.angularDiameterArcmin, m.phaseAngleDeg, 100.0 * m.illuminatedFraction, m.magnitudeV,
                m.librationLongitudeDeg, m.librationLatitudeDeg);
  return text;
}

glm::dvec3 moonSeenFromM(UtcTime time, const glm::dvec3& observerM) {
  const Body moon = presetBody("Moon", time);
  const eclipse::Occluder o{moon.positionM, moon.radiusM, {}, moon.velocityMps};
  return eclipse::occluderSeenBy(o, observerM, 0.0, 0.0).centreM;
}

SunAndMoonInHorizon sunAndMoonInHorizon(UtcTime time, const Observer& observer) {
  if (observer.body != "Earth")
    throw std::invalid_argument("the Sun and the Moon in the horizon are for an observer on the Earth, not on '" +
                                observer.body + "'");
  const Body earth = presetBody("Earth", time), sun = presetBody("Sun", time);
  const glm::dvec3 eyeM = observerPositionM(earth, observer, time);
  Body moon = presetBody("Moon", time);
  moon.positionM = moonSeenFromM(time, eyeM);
  const glm::dvec3 east = horizontalDirection(earth, observer, {90.0, 0.0}, time);
  const glm::dvec3 north = horizontalDirection(earth, observer, {0.0, 0.0}, time);
  const glm::dvec3 up = horizontalDirection(earth, observer, {0.0, 90.0}, time);
  const auto local = [&](const glm::dvec3& v) { return glm::dvec3(glm::dot(v, east), glm::dot(v, north), glm::dot(v, up)); };
  SunAndMoonInHorizon out;
  out.sunM = local(sun.positionM - eyeM);
  out.moonM = local(moon.positionM - eyeM);
  out.sunRadiusM = sun.radiusM;
  out.moonRadiusM = moon.radiusM;
  return out;
}

std::optional<std::string> describeMoonOf(const Scene& scene) {
  if (!scene.hasTime) return std::nullopt;
  bool hasMoon = false;
  for (const Body& b : scene.bodies) hasMoon = hasMoon || b.preset == "Moon";
  if (!hasMoon) return std::nullopt;
  std::optional<Observer> observer;
  if (scene.camera.observer) {
    const Body* on = scene.find(scene.camera.observer->body);
    if (on && on->preset == "Earth") {
      observer = *scene.camera.observer;
      observer->body = "Earth";
    }
  }
  try {
    return describeMoon(moonNumbers(scene.time, observer));
  } catch (const std::exception&) {
    return std::nullopt;  // a time outside the ephemeris' range: no line rather than an error
  }
}

}  // namespace umbra::scene
