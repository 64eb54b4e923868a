#include "SightLines.hpp"

#include <cmath>

namespace umbra::atmosphere {

RefractiveMedium refractiveMedium(const Atmosphere& atm, double wavelengthNm) {
  RefractiveMedium m;
  m.bottomRadiusM = atm.bottomRadiusM;
  m.topRadiusM = atm.topRadiusM;
  // Atmosphere::refractivity's n - 1, its numbers copied in (the medium may outlive atm).
  const double F = atm.seaLevelRefractivity *
                   dispersionRatio(atm.dispersion, wavelengthNm, atm.refractivityReferenceWavelengthNm);
  if (atm.refractivityFollows.empty()) {
    m.refractivity = [F](double) { return F; };
    m.refractivityDerivativePerM = [](double) { return 0.0; };
    return m;
  }
  const Component* c = atm.find(atm.refractivityFollows);
  if (c == nullptr) {
    m.refractivity = [](double) { return 0.0; };
    m.refractivityDerivativePerM = [](double) { return 0.0; };
    return m;
  }
  const DensityProfile prof = c->density;
  m.refractivity = [F, prof](double h) { return F * prof.at(h); };
  if (prof.kind == DensityProfile::Kind::Exponential) {
    const double H = prof.scaleHeightM;
    m.refractivityDerivativePerM = [F, H](double h) { return -F / H * std::exp(-h / H); };
  } else if (prof.kind == DensityProfile::Kind::DoubleExponential) {
    const double H = prof.scaleHeightM;
    m.refractivityDerivativePerM = [F, H](double h) {
      const double e = std::exp(h / H);
      return -F / H * e * std::exp(1.0 - e);
    };
  }
  return m;
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
