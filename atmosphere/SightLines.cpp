#include "SightLines.hpp"

#include <cmath>

namespace umbra::atmosphere {

RefractiveMedium refractiveMedium(const Atmosphere& atmosphere, double wavelengthNm) {
  RefractiveMedium medium;
  medium.bottomRadiusM = atmosphere.bottomRadiusM;
  medium.topRadiusM = atmosphere.topRadiusM;
  medium.refractivity = [&atmosphere, wavelengthNm](double altitudeM) {
    return atmosphere.refractivity(altitudeM, wavelengthNm);
  };
  return medium;
}

SightLine traceSightLine(const Atmosphere& atmosphere, double altitudeM, double zenithRad,
                         double referenceWavelengthNm, double stepM, int piecesPerStep) {
  const std::size_t n = atmosphere.wavelengthsNm.size();
  std::vector<double> opticalDepth(n, 0.0);
  TraceOptions options;
  options.stepM = stepM;
  options.segmentsPerStep = piecesPerStep;
  options.segment = [&](double segmentAltitudeM, double lengthM) {
    const std::vector<double> extinction = atmosphere.extinctionPerM(segmentAltitudeM);
    for (std::size_t i = 0; i < n; ++i) opticalDepth[i] += extinction[i] * lengthM;
  };
  const RayPath path = traceRay(refractiveMedium(atmosphere, referenceWavelengthNm),
                                atmosphere.bottomRadiusM + altitudeM, std::cos(zenithRad), options);
  SightLine line;
  line.deviationRad = path.deviationRad;
  line.contactAltitudeM = path.contactAltitudeM;
  line.hitGround = path.hitGround;
  line.transmittance.resize(n);
  for (std::size_t i = 0; i < n; ++i) line.transmittance[i] = path.hitGround ? 0.0 : std::exp(-opticalDepth[i]);
  return line;
}

} // namespace umbra::atmosphere
