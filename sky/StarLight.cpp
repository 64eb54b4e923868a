#include "StarLight.hpp"

#include "Sky.hpp"
#include "Spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace umbra::sky {

double irradianceRelativeToSun(double vMag) { return std::pow(10.0, -0.4 * (vMag - kSunMagnitudeV)); }

double ballesterosTemperatureK(double bMinusV) {
  const double bv = std::clamp(bMinusV, -0.4, 2.0);
  return 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
}

glm::dvec3 blackbodyXyz(double temperatureK) {
  if (!(temperatureK > 0.0) || !std::isfinite(temperatureK))
    throw std::invalid_argument("blackbody: temperature must be positive and finite");
  // Planck's law up to a constant factor (the result is scaled to Y = 1): h c / k = 0.014388 m K.
  constexpr double kSecondRadiationConstantMK = 1.438776877e-2;
  glm::dvec3 xyz(0.0);
  for (int nm = static_cast<int>(atmosphere::kCmfMinNm); nm <= static_cast<int>(atmosphere::kCmfMaxNm); ++nm) {
    const double lambdaM = nm * 1e-9;
    const double planck = 1.0 / (std::pow(lambdaM * 1e6, 5) * std::expm1(kSecondRadiationConstantMK / (lambdaM * temperatureK)));
    xyz += planck * atmosphere::cie1931(nm);
  }
  return xyz / xyz.y;
}

glm::dvec3 blackbodyLinearSrgb(double temperatureK) { return atmosphere::xyzToLinearSrgb(blackbodyXyz(temperatureK)); }

glm::dvec3 starLinearSrgb(double bMinusV) { return blackbodyLinearSrgb(ballesterosTemperatureK(bMinusV)); }

double starIlluminanceLux(double vMag) {
  static const double sunLux = atmosphere::solarIlluminanceLux();
  return sunLux * irradianceRelativeToSun(vMag);
}


glm::dvec3 sunLinearSrgb() {
  static const glm::dvec3 rgb = [] {
    const glm::dvec3 xyz = atmosphere::solarXyzLux();
    return atmosphere::xyzToLinearSrgb(xyz / xyz.y);
  }();
  return rgb;
}

glm::dvec3 starFrameColour(double bMinusV) {
  constexpr double kLo = -0.4, kHi = 2.0, kStep = 0.01;
  constexpr int kCount = 241;  // (kHi - kLo) / kStep + 1
  static const std::vector<glm::dvec3> table = [] {
    std::vector<glm::dvec3> t(kCount);
    const glm::dvec3 sun = sunLinearSrgb();
    for (int i = 0; i < kCount; ++i) t[i] = starLinearSrgb(kLo + i * kStep) / sun;
    return t;
  }();
  if (!std::isfinite(bMinusV)) throw std::invalid_argument("star colour: B-V must be finite");
  const double x = (std::clamp(bMinusV, kLo, kHi) - kLo) / kStep;
  const int i = std::min(static_cast<int>(std::floor(x)), kCount - 2);
  const double f = x - i;
  return f < 1e-9 ? table[i] : table[i] * (1.0 - f) + table[i + 1] * f;
}

glm::dvec3 reflectedFrameColour(double bMinusV, double sunBMinusV) {
  return starFrameColour(bMinusV) / starFrameColour(sunBMinusV);
}

glm::dvec3 starFrameIrradianceWm2(double vMag, double bMinusV, double sunIrradianceAt1AuWm2) {
  return sunIrradianceAt1AuWm2 * irradianceRelativeToSun(vMag) * starFrameColour(bMinusV);
}

double airMass(double zenithAngleRad) {
  const double deg = zenithAngleRad * 180.0 / 3.14159265358979323846;
  if (!(deg >= 0.0 && deg <= 90.0)) throw std::invalid_argument("air mass: the zenith angle must be in [0, 90] deg");
  return 1.0 / (std::cos(zenithAngleRad) + 0.50572 * std::pow(96.07995 - deg, -1.6364));
}

namespace {
// SplitMix64 (Steele, Lea & Flood 2014): a well-mixed 64-bit value from a counter.
std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
// A uniform draw in (0, 1) from 53 bits.
double unitOpen(std::uint64_t bits) { return ((bits >> 11) + 0.5) * 0x1.0p-53; }
}  // namespace

double scintillationFactor(double sigmaAtZenith, double airMassX, std::uint64_t seed, std::uint64_t index) {
  if (!(sigmaAtZenith >= 0.0 && std::isfinite(sigmaAtZenith)))
    throw std::invalid_argument("scintillation: sigma must be finite and >= 0");
  if (!(airMassX >= 1.0 && std::isfinite(airMassX)))
    throw std::invalid_argument("scintillation: the air mass must be finite and >= 1");
  if (sigmaAtZenith == 0.0) return 1.0;
  const double s = std::min(sigmaAtZenith * std::pow(airMassX, 1.5), 1.0);
  // Box-Muller on two draws keyed by (seed, index).
  const std::uint64_t key = splitMix64(seed ^ splitMix64(index));
  const double u1 = unitOpen(splitMix64(key)), u2 = unitOpen(splitMix64(key + 1));
  const double g = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
  return std::exp(s * g - 0.5 * s * s);
}

double radianceOfSurfaceBrightnessWm2Sr(double vMagPerArcsec2, double sunIrradianceAt1AuWm2) {
  constexpr double kArcsecPerRad = 180.0 / 3.14159265358979323846 * 3600.0;
  return sunIrradianceAt1AuWm2 * irradianceRelativeToSun(vMagPerArcsec2) * kArcsecPerRad * kArcsecPerRad;
}

double nightGlowAboveAirWm2Sr(double zenithOpticalDepth, double sunIrradianceAt1AuWm2, double milkyWayMeanWm2Sr) {
  return std::max(0.0, radianceOfSurfaceBrightnessWm2Sr(kDarkSkyZenithVMagPerArcsec2, sunIrradianceAt1AuWm2) *
                               std::exp(zenithOpticalDepth) -
                           milkyWayMeanWm2Sr);
}

}  // namespace umbra::sky
