#include "scene/Ephemeris.hpp"

#include "SolarDisc.hpp"  // kSunRadiusM

#include "scene/Units.hpp"

#include <erfa.h>
#include <erfam.h>
#include <libnova/lunar.h>

#include <cmath>
#include <mutex>
#include <stdexcept>

namespace umbra::scene {

namespace {

constexpr double kJ2000 = 2451545.0;
constexpr double kDaysPerCentury = 36525.0;
constexpr double kDayS = 86400.0;

glm::dvec3 auToM(const double p[3]) { return glm::dvec3(p[0], p[1], p[2]) * kAuM; }

/// ERFA's row-major r[row][col] as a glm matrix (glm is column-major: m[col][row]).
glm::dmat3 fromErfa(const double r[3][3]) {
  glm::dmat3 m;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) m[col][row] = r[row][col];
  return m;
}

/// Rotation of the frame about z by angle (ERFA's eraRz convention), as a glm matrix.
glm::dmat3 frameRotationZ(double angleRad) {
  double r[3][3];
  eraIr(r);
  eraRz(angleRad, r);
  return fromErfa(r);
}

glm::dmat3 frameRotationX(double angleRad) {
  double r[3][3];
  eraIr(r);
  eraRx(angleRad, r);
  return fromErfa(r);
}

/// Days and Julian centuries since J2000, TT standing in for TDB (< 2 ms apart).
void daysSinceJ2000(UtcTime time, double& days, double& centuries) {
  double tt1 = 0.0, tt2 = 0.0;
  toTt(time, tt1, tt2);
  days = (tt1 - kJ2000) + tt2;
  centuries = days / kDaysPerCentury;
}

glm::dvec3 earthHeliocentricM(double tt1, double tt2) {
  double pvh[2][3], pvb[2][3];
  eraEpv00(tt1, tt2, pvh, pvb); // status +1: outside 1900-2100, still usable
  return auToM(pvh[0]);
}

[[noreturn]] void throwNoEphemeris(const std::string& body) {
  throw std::invalid_argument("no ephemeris for '" + body +
                              "': give its position explicitly in metres");
}

} // namespace

bool hasEphemeris(const std::string& body) {
  return body == "Sun" || body == "Earth" || body == "Moon" || body == "Mars";
}

glm::dvec3 heliocentricPositionM(const std::string& body, UtcTime time) {
  if (!hasEphemeris(body)) throwNoEphemeris(body);
  if (body == "Sun") return glm::dvec3(0.0);
  double tt1 = 0.0, tt2 = 0.0; // ERFA wants TDB; TT is within 2 ms of it
  toTt(time, tt1, tt2);
  if (body == "Earth") return earthHeliocentricM(tt1, tt2);
  if (body == "Moon") return earthHeliocentricM(tt1, tt2) + moonGeocentricElpM(tt1 + tt2);
  return planetHeliocentricPositionM("Mars", time);
}

glm::dvec3 heliocentricVelocityMps(const std::string& body, UtcTime time) {
  if (!hasEphemeris(body)) throwNoEphemeris(body);
  if (body == "Sun") return glm::dvec3(0.0);
  double tt1 = 0.0, tt2 = 0.0;
  toTt(time, tt1, tt2);
  double pv[2][3];
  if (body == "Mars") {
    if (eraPlan94(tt1, tt2, 4, pv) < 0) throw std::invalid_argument("Mars ephemeris failed at this date");
    return auToM(pv[1]) / kDayS;
  }
  double pvb[2][3];
  eraEpv00(tt1, tt2, pv, pvb);
  glm::dvec3 v = auToM(pv[1]);
  if (body == "Moon") {
    double moon[2][3];
    eraMoon98(tt1, tt2, moon);
    v += auToM(moon[1]);
  }
  return v / kDayS;  // au/day -> m/s
}

glm::dvec3 moonGeocentricElpM(double ttJd) {
  // libnova's lunar theory keeps its last result in static variables: one caller at a time.
  static std::mutex libnovaLunar;
  ln_rect_posn p{};
  {
    const std::lock_guard<std::mutex> lock(libnovaLunar);
    ln_get_lunar_geo_posn(ttJd, &p, 0.0);
  }  // km, mean ecliptic and equinox of J2000; 0: every term
  const double c = std::cos(kObliquityJ2000Rad), s = std::sin(kObliquityJ2000Rad);
  return glm::dvec3(p.X, c * p.Y - s * p.Z, s * p.Y + c * p.Z) * 1000.0;
}

glm::dvec3 moonGeocentricMeeusM(double ttJd) {
  double pv[2][3];
  eraMoon98(ttJd, 0.0, pv);
  return auToM(pv[0]);
}

glm::dvec3 earthHeliocentricM(double ttJd) { return earthHeliocentricM(ttJd, 0.0); }

glm::dvec3 planetHeliocentricPositionM(const std::string& planet, UtcTime time) {
  // eraPlan94's numbering; 3 is the Earth-Moon barycentre, not offered.
  const char* const names[] = {"Mercury", "Venus", "", "Mars", "Jupiter", "Saturn", "Uranus", "Neptune"};
  int number = 0;
  for (int k = 0; k < 8; ++k)
    if (planet == names[k] && k != 2) number = k + 1;
  if (number == 0) throw std::invalid_argument("no planetary theory for '" + planet + "'");
  double tt1 = 0.0, tt2 = 0.0;  // ERFA wants TDB; TT is within 2 ms of it
  toTt(time, tt1, tt2);
  double pv[2][3];
  if (eraPlan94(tt1, tt2, number, pv) < 0)  // heliocentric, J2000 equatorial
    throw std::invalid_argument(planet + " ephemeris failed at this date");
  return auToM(pv[0]);
}

std::string ephemerisRangeNote(UtcTime time) {
  double tt1 = 0.0, tt2 = 0.0;
  toTt(time, tt1, tt2);
  double pvh[2][3], pvb[2][3];
  if (eraEpv00(tt1, tt2, pvh, pvb) == 0) return "";
  return "note: " + formatUtc(time) +
         " is outside 1900-2100, the years ERFA's Earth ephemeris (epv00) is fitted to: the positions of the Earth, "
         "the Moon and the planets are less exact there";
}

bool hasRotationModel(const std::string& body) { return hasEphemeris(body); }

glm::dmat3 iauBodyFixedToInertial(double alpha0Deg, double delta0Deg, double wDeg) {
  // ICRS -> body-fixed is Rz(W) Rx(90 deg - delta0) Rz(90 deg + alpha0) (frame
  // rotations); its transpose takes body-fixed vectors to ICRS.
  const double deg = ERFA_DD2R;
  const glm::dmat3 inertialToBody = frameRotationZ(wDeg * deg) *
                                    frameRotationX((90.0 - delta0Deg) * deg) *
                                    frameRotationZ((90.0 + alpha0Deg) * deg);
  return glm::transpose(inertialToBody);
}

glm::dmat3 bodyFixedToInertial(const std::string& body, UtcTime time) {
  if (body == "Earth") {
    // IAU 2006/2000A; polar motion set to zero and UT1 = UTC (errors <= 0.9 s of
    // rotation, i.e. <= 0.004 deg).
    double tt1 = 0.0, tt2 = 0.0;
    toTt(time, tt1, tt2);
    double rc2t[3][3];
    eraC2t06a(tt1, tt2, time.jd1, time.jd2, 0.0, 0.0, rc2t);
    return glm::transpose(fromErfa(rc2t)); // rc2t is celestial-to-terrestrial
  }
  // IAU WGCCRE 2015 models (Archinal et al. 2018). For the Moon with its periodic terms
  // (the E1..E13 series: the 18.6-year E1 terms move the pole by 1.5 deg, which decides
  // where the Sun stands at the lunar poles); for Mars only the constant and linear terms
  // (its nutation-precession series costs well under 0.01 deg).
  double d = 0.0, t = 0.0;
  daysSinceJ2000(time, d, t);
  if (body == "Sun") return iauBodyFixedToInertial(286.13, 63.87, 84.176 + 14.1844000 * d);
  if (body == "Moon") {
    // E_k = e0 + e1 d [deg]; then the coefficients of sin E_k in alpha0, cos E_k in
    // delta0 and sin E_k in W [deg].
    struct Term {
      double e0, e1, alpha, delta, w;
    };
    static constexpr Term kTerms[13] = {
        {125.045, -0.0529921, -3.8787, 1.5419, 3.5610},  {250.089, -0.1059842, -0.1204, 0.0239, 0.1208},
        {260.008, 13.0120009, 0.0700, -0.0278, -0.0642}, {176.625, 13.3407154, -0.0172, 0.0068, 0.0158},
        {357.529, 0.9856003, 0.0, 0.0, 0.0252},          {311.589, 26.4057084, 0.0072, -0.0029, -0.0066},
        {134.963, 13.0649930, 0.0, 0.0009, -0.0047},     {276.617, 0.3287146, 0.0, 0.0, -0.0046},
        {34.226, 1.7484877, 0.0, 0.0, 0.0028},           {15.134, -0.1589763, -0.0052, 0.0008, 0.0052},
        {119.743, 0.0036096, 0.0, 0.0, 0.0040},          {239.961, 0.1643573, 0.0, 0.0, 0.0019},
        {25.053, 12.9590088, 0.0043, -0.0009, -0.0044}};
    constexpr double deg = 3.14159265358979323846 / 180.0;
    double alpha0 = 269.9949 + 0.0031 * t, delta0 = 66.5392 + 0.0130 * t;
    double w = 38.3213 + 13.17635815 * d - 1.4e-12 * d * d;
    for (const Term& k : kTerms) {
      const double e = std::fmod(k.e0 + k.e1 * d, 360.0) * deg;
      alpha0 += k.alpha * std::sin(e), delta0 += k.delta * std::cos(e), w += k.w * std::sin(e);
    }
    return iauBodyFixedToInertial(alpha0, delta0, w);
  }
  if (body == "Mars")
    return iauBodyFixedToInertial(317.68143 - 0.1061 * t, 52.88650 - 0.0609 * t,
                                  176.630 + 350.89198226 * d);
  throw std::invalid_argument("no rotation model for '" + body +
                              "': body-fixed coordinates are not available");
}

SunFromBody sunFromBody(const std::string& body, UtcTime time) {
  if (body == "Sun") throw std::invalid_argument("the Sun seen from itself has no direction");
  if (!hasEphemeris(body) || !hasRotationModel(body))
    throw std::invalid_argument("no ephemeris or rotation model for '" + body + "' (Earth, Moon, Mars have them)");
  const glm::dvec3 toSunM = heliocentricPositionM("Sun", time) - heliocentricPositionM(body, time);
  SunFromBody sun;
  sun.distanceM = glm::length(toSunM);
  sun.directionBodyFixed = glm::transpose(bodyFixedToInertial(body, time)) * (toSunM / sun.distanceM);
  sun.angularRadiusRad = std::asin(eclipse::kSunRadiusM / sun.distanceM);
  return sun;
}

} // namespace umbra::scene
