#include "Photometry.hpp"

#include "Spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace umbra::sky {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kAuM = 1.495978707e11;
}  // namespace

HapkeParameters jensenParameters() { return {0.6, 1.0, 0.1}; }

HapkeParameters moonParameters() { return {0.69, 0.76, 0.0}; }

void validate(const HapkeParameters& p) {
  if (!(std::isfinite(p.oppositionWidth) && p.oppositionWidth > 0.0 && p.oppositionWidth <= 10.0))
    throw std::invalid_argument("photometry: oppositionWidth (g) must be in (0, 10], got " +
                                std::to_string(p.oppositionWidth));
  if (!(std::isfinite(p.lambertShare) && p.lambertShare >= 0.0 && p.lambertShare <= 1.0))
    throw std::invalid_argument("photometry: lambertShare (w) must be in [0, 1], got " + std::to_string(p.lambertShare));
  if (!(std::isfinite(p.forwardScatter) && p.forwardScatter >= 0.0 && p.forwardScatter <= 10.0))
    throw std::invalid_argument("photometry: forwardScatter (c) must be in [0, 10], got " +
                                std::to_string(p.forwardScatter));
}

double oppositionSurge(double phaseRad, double g) {
  const double a = std::abs(phaseRad);
  if (!(a < 0.5 * kPi)) return 1.0;
  const double t = std::tan(a);
  if (t < 1e-300) return 2.0;  // g / tan -> inf: e -> 0, and tan/(2g) * 3 -> 0
  const double e = std::exp(-g / t);
  return 2.0 - t / (2.0 * g) * (1.0 - e) * (3.0 - e);
}

double grainPhase(double phaseRad, const HapkeParameters& p) {
  const double a = std::min(std::abs(phaseRad), kPi);
  const double c = std::cos(a);
  const double lambertSphere = (std::sin(a) + (kPi - a) * c) / kPi;
  return (1.0 - p.lambertShare) + p.lambertShare * lambertSphere + p.forwardScatter * (1.0 - c) * (1.0 - c);
}

double hapkeReflectance(double cosIncidence, double cosEmergence, double phaseRad, const HapkeParameters& p) {
  if (!(cosIncidence > 0.0 && cosEmergence > 0.0)) return 0.0;
  const double ls = cosIncidence / (cosIncidence + cosEmergence);
  return 2.0 / (3.0 * kPi) * oppositionSurge(phaseRad, p.oppositionWidth) * grainPhase(phaseRad, p) * ls;
}

double lommelSeeligerPhase(double phaseRad) {
  const double a = std::min(std::abs(phaseRad), kPi);
  if (a < 1e-12) return 1.0;
  // Near pi, tan(a/2) ln cot(a/4) -> 1 - (pi - a)^2/... : the product below loses digits
  // as both factors go to inf and 0; with x = pi - a, sin(a/2) = cos(x/2),
  // tan(a/2) = cot(x/2) and cot(a/4) = (1 + tan(x/4)) / (1 - tan(x/4)).
  const double x = kPi - a;
  if (x < 1e-12) return 0.0;
  if (x < 1e-3) {
    const double t = std::tan(0.25 * x);
    return 1.0 - std::cos(0.5 * x) / std::tan(0.5 * x) * std::log1p(2.0 * t / (1.0 - t));
  }
  return 1.0 - std::sin(0.5 * a) * std::tan(0.5 * a) * std::log(1.0 / std::tan(0.25 * a));
}

double discReflectance(double phaseRad, const HapkeParameters& p) {
  return oppositionSurge(phaseRad, p.oppositionWidth) * grainPhase(phaseRad, p) * lommelSeeligerPhase(phaseRad) / 3.0;
}

double albedoForGeometricAlbedo(double geometricAlbedo, const HapkeParameters& p) {
  return geometricAlbedo / discReflectance(0.0, p);
}

double apparentMagnitudeV(double geometricAlbedo, const HapkeParameters& p, double phaseRad, double radiusM,
                          double sunDistanceM, double observerDistanceM) {
  const double phase = discReflectance(phaseRad, p) / discReflectance(0.0, p);
  const double a = radiusM / observerDistanceM, b = kAuM / sunDistanceM;
  const double ratio = geometricAlbedo * phase * a * a * b * b;
  if (!(ratio > 0.0)) return std::numeric_limits<double>::infinity();
  return kSunMagnitudeV - 2.5 * std::log10(ratio);
}

double magnitudeOfIrradiance(double irradianceWm2) {
  if (!(irradianceWm2 > 0.0)) return std::numeric_limits<double>::infinity();
  return kSunMagnitudeV - 2.5 * std::log10(irradianceWm2 / kSolarConstantWm2);
}

glm::dvec3 reflectanceTint(const glm::dvec3& reflectance) {
  for (int c = 0; c < 3; ++c)
    if (!(reflectance[c] >= 0.0 && std::isfinite(reflectance[c])))
      throw std::invalid_argument("reflectance must be finite and >= 0");
  if (!(reflectance.x + reflectance.y + reflectance.z > 0.0))
    throw std::invalid_argument("reflectance must not be zero at every wavelength");
  const atmosphere::WavelengthSet set = atmosphere::WavelengthSet::rgb();  // 680, 550, 440 nm
  std::vector<double> sun(3), reflected(3);
  for (int i = 0; i < 3; ++i) {
    sun[i] = atmosphere::solarIrradianceWm2PerNm(set.nm[i]);
    reflected[i] = reflectance[i] * sun[i];
  }
  const glm::dvec3 s = atmosphere::spectralRadianceToLinearSrgb(set, sun);
  const glm::dvec3 r = atmosphere::spectralRadianceToLinearSrgb(set, reflected);
  const double ys = atmosphere::luminanceCdM2(set, sun), yr = atmosphere::luminanceCdM2(set, reflected);
  return r / s * (ys / yr);
}

std::string describe(const HapkeParameters& p) {
  std::ostringstream s;
  s << "hapke(g=" << p.oppositionWidth << ", w=" << p.lambertShare << ", c=" << p.forwardScatter << ")";
  return s.str();
}

}  // namespace umbra::sky
