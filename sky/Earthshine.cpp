#include "Earthshine.hpp"

#include "Colour.hpp"
#include "Photometry.hpp"

#include <algorithm>
#include <cmath>

namespace umbra::sky {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double earthshinePaper(double moonPhaseRad) {
  const double p = std::clamp(moonPhaseRad, 0.0, kPi);
  return std::max(0.0, -0.0061 * p * p * p + 0.0289 * p * p - 0.0105 * std::sin(p));
}

double earthshineJensen(double moonPhaseRad) {
  return 0.19 * 0.5 * lommelSeeligerPhase(kPi - std::clamp(moonPhaseRad, 0.0, kPi));
}

double earthshineIrradiance(double sunIrradianceAtEarthWm2, double earthGeometricAlbedo, double earthRadiusM,
                            double earthMoonDistanceM, double earthPhaseRad) {
  if (!(earthMoonDistanceM > earthRadiusM && earthRadiusM > 0.0)) return 0.0;
  const double s = earthRadiusM / earthMoonDistanceM;
  const double phase = earthshinePaper(kPi - std::clamp(earthPhaseRad, 0.0, kPi)) / earthshinePaper(kPi);
  return sunIrradianceAtEarthWm2 * earthGeometricAlbedo * s * s * phase;
}

glm::dvec3 earthshineColour() {
  const glm::dvec3 beta(0.88, 0.96, 1.00);
  return beta / colour::luminance(beta);
}

}  // namespace umbra::sky
