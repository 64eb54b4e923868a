#include "Describe.hpp"

#include <charconv>

namespace umbra::atmosphere {
namespace {

std::string join(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + formatNumber(v);
  return out;
}

std::string describe(const DensityProfile& p) {
  switch (p.kind) {
    case DensityProfile::Kind::Exponential: return "exponential H=" + formatNumber(p.scaleHeightM);
    case DensityProfile::Kind::DoubleExponential: return "double-exponential H=" + formatNumber(p.scaleHeightM);
    case DensityProfile::Kind::Tent:
      return "tent centre=" + formatNumber(p.centreM) + " halfWidth=" + formatNumber(p.halfWidthM);
    case DensityProfile::Kind::Tabulated: return "tabulated h=" + join(p.altitudesM) + " values=" + join(p.values);
    case DensityProfile::Kind::BoundaryLayer:
      return "boundary-layer top=" + formatNumber(p.boundaryLayerTopM) + " H=" + formatNumber(p.scaleHeightM) +
             " free=" + formatNumber(p.freeTroposphereDensity) + " H=" + formatNumber(p.freeTroposphereScaleHeightM) +
             " top=" + formatNumber(p.freeTroposphereTopM) + " transition=" + formatNumber(p.transitionM);
  }
  return "?";
}

} // namespace

std::string formatNumber(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

ParameterMap refractionParameters(const Atmosphere& a, double wavelengthNm) {
  ParameterMap p{{"bottomRadiusM", formatNumber(a.bottomRadiusM)},
                 {"topRadiusM", formatNumber(a.topRadiusM)},
                 {"wavelengthNm", formatNumber(wavelengthNm)},
                 {"seaLevelRefractivity", formatNumber(a.seaLevelRefractivity)},
                 {"refractivityReferenceWavelengthNm", formatNumber(a.refractivityReferenceWavelengthNm)},
                 {"dispersion", std::to_string(static_cast<int>(a.dispersion))},
                 {"refractivityFollows", a.refractivityFollows}};
  if (const Component* c = a.find(a.refractivityFollows)) p["refractivityProfile"] = describe(c->density);
  return p;
}

ParameterMap atmosphereParameters(const Atmosphere& a) {
  ParameterMap p = refractionParameters(a, a.refractivityReferenceWavelengthNm);
  p.erase("wavelengthNm");
  p["atmosphere"] = a.name;
  p["wavelengthsNm"] = join(a.wavelengthsNm);
  p["groundAlbedo"] = join(a.groundAlbedo);
  for (const Component& c : a.components) {
    const std::string k = "component." + c.name + ".";
    p[k + "density"] = describe(c.density);
    p[k + "scatteringPerM"] = join(c.scatteringPerM);
    p[k + "absorptionPerM"] = join(c.absorptionPerM);
    std::string phases;
    for (const PhaseFunction& f : c.phases) {
      phases += (phases.empty() ? "" : "; ") + f.describe();
      if (f.kind() == PhaseFunction::Kind::Tabulated)
        phases += " mu=" + join(f.cosThetaSamples()) + " p=" + join(f.values());
    }
    p[k + "phases"] = phases;
  }
  return p;
}

} // namespace umbra::atmosphere
