#include "precompute/Batch.hpp"

#include "SightLines.hpp"  // refractiveMedium

#include <map>

namespace umbra::atmosphere::stages {

Batch::Batch(const Atmosphere& atmIn, const PrecomputeOptions& oIn, Runner& runIn,
             std::vector<FloatTable3D>& singleIn, FloatTable3D& multipleIn, int l0In)
    : atm(atmIn), o(oIn), run(runIn), m(atmIn, oIn), nl(m.nl), nc(m.nc), ns(static_cast<int>(m.scatterers.size())),
      shell{atmIn.bottomRadiusM, atmIn.topRadiusM}, b(m.b), t(m.t), alpha(oIn.sunAngularRadiusRad),
      g(shell, {oIn.scatteringR, oIn.scatteringMu, oIn.scatteringMuS, oIn.scatteringNu}, oIn.muSMin), points(g),
      W(oIn.scatteringNu * oIn.scatteringMuS), MU(oIn.scatteringMu), R(oIn.scatteringR), MUS(oIn.scatteringMuS),
      TW(oIn.transmittanceWidth), TH(oIn.transmittanceHeight), IW(oIn.irradianceWidth), IH(oIn.irradianceHeight),
      texels(static_cast<std::size_t>(W) * MU * R), single(singleIn), multiple(multipleIn), l0(l0In) {
  if (!o.refraction) return;
  std::map<double, int> seen;
  for (int l = 0; l < nl; ++l) {
    const double key = dispersionRatio(atm.dispersion, atm.wavelengthsNm[l], atm.refractivityReferenceWavelengthNm);
    auto it = seen.find(key);
    if (it == seen.end()) {
      seen[key] = static_cast<int>(media.size());
      media.push_back(refractiveMedium(atm, atm.wavelengthsNm[l]));
      mediumUsers.push_back({l});
    } else {
      mediumUsers[it->second].push_back(l);
    }
  }
  referenceMedium = refractiveMedium(atm, atm.refractivityReferenceWavelengthNm);
}

}  // namespace umbra::atmosphere::stages
