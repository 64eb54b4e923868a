#include "MoonGeometry.hpp"

#include <glm/geometric.hpp>

#include <cmath>

namespace umbra::sky {

namespace {
constexpr double kPi = 3.14159265358979323846;

double wrapPi(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}
}  // namespace

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

double illuminatedFraction(double phaseRad) { return 0.5 * (1.0 + std::cos(phaseRad)); }

double brightLimbPositionAngle(double sunRaRad, double sunDecRad, double moonRaRad, double moonDecRad) {
  const double dRa = sunRaRad - moonRaRad;
  const double chi = std::atan2(std::cos(sunDecRad) * std::sin(dRa),
                                std::sin(sunDecRad) * std::cos(moonDecRad) -
                                    std::cos(sunDecRad) * std::sin(moonDecRad) * std::cos(dRa));
  return chi < 0.0 ? chi + 2.0 * kPi : chi;
}

Libration opticalLibration(double meanLongitudeRad, double latitudeRad, double ascendingNodeRad,
                           double argumentOfLatitudeRad) {
  const double i = kMoonEquatorInclinationRad;
  const double w = meanLongitudeRad - ascendingNodeRad;
  const double cb = std::cos(latitudeRad), sb = std::sin(latitudeRad);
  const double a = std::atan2(std::sin(w) * cb * std::cos(i) - sb * std::sin(i), std::cos(w) * cb);
  Libration l;
  l.longitudeRad = wrapPi(a - argumentOfLatitudeRad);
  l.latitudeRad = std::asin(-std::sin(w) * cb * std::sin(i) - sb * std::cos(i));
  return l;
}

}  // namespace umbra::sky
