#include "NightVision.hpp"

#include "Sky.hpp"
#include "Spectrum.hpp"
#include "StarLight.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::sky {
namespace {

constexpr double kA = 0.7670, kB = 0.3334;
constexpr double kV0 = 683.0 / 1699.0;

double step(double m, double lp, double ls) {
  const double mes = (m * lp + (1.0 - m) * ls * kV0) / (m + (1.0 - m) * kV0);
  return std::clamp(kA + kB * std::log10(std::max(mes, 1e-30)), 0.0, 1.0);
}

}  // namespace

double scotopicLuminance(const glm::dvec3& xyz) {
  if (!(xyz.x > 0.0)) return 0.0;
  return std::max(xyz.y * (1.33 * (1.0 + (xyz.y + xyz.z) / xyz.x) - 1.68), 0.0);
}

double mesopicConeShareIterated(double lp, double ls, int iterations) {
  double m = 0.5;
  for (int i = 0; i < iterations; ++i) m = step(m, lp, ls);
  return m;
}

double mesopicConeShare(double lp, double ls) {
  if (!(lp >= 0.0 && ls >= 0.0 && std::isfinite(lp) && std::isfinite(ls)))
    throw std::invalid_argument("mesopic adaptation: luminances must be finite and >= 0");
  // The map is a contraction in m wherever 0 < m < 1 (its slope is below 1): iterate to
  // convergence.
  double m = 0.5;
  for (int i = 0; i < 200; ++i) {
    const double next = step(m, lp, ls);
    if (std::abs(next - m) < 1e-14) return next;
    m = next;
  }
  return m;
}

double sunlightEfficacyLmPerW() { return atmosphere::solarIlluminanceLux() / kSolarConstantWm2; }

double sunlightScotopicRatio() {
  const glm::dvec3 xyz = atmosphere::solarXyzLux();
  return scotopicLuminance(xyz / xyz.y);
}

glm::dvec3 nightVisionColour(const glm::dvec3& frameRgb) {
  const double k = sunlightEfficacyLmPerW();
  const glm::dvec3 xyz = atmosphere::linearSrgbToXyz(frameRgb * sunLinearSrgb()) * k;  // cd m^-2
  const double scotopic = scotopicLuminance(xyz);
  const double m = mesopicConeShareIterated(std::max(xyz.y, 0.0), scotopic, 8);
  const glm::dvec3 grey(scotopic / (k * sunlightScotopicRatio()));
  return grey + (frameRgb - grey) * m;
}

}  // namespace umbra::sky
