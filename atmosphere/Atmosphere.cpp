// Atmosphere: the model's sums (the reading of files: AtmosphereReader.cpp).
#include "Atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace umbra::atmosphere {


// ---- the model --------------------------------------------------------------------------

double Atmosphere::refractivity(double altitudeM, double wavelengthNm) const {
  double rho = 1.0;
  if (!refractivityFollows.empty()) {
    const Component* c = find(refractivityFollows);
    rho = c ? c->density.at(altitudeM) : 0.0;
  }
  return seaLevelRefractivity * dispersionRatio(dispersion, wavelengthNm, refractivityReferenceWavelengthNm) *
         rho;
}

namespace {
// Sum over the components of density(altitude) * coefficient(component, wavelength index).
template <class Coefficient>
std::vector<double> densityWeightedSum(const std::vector<Component>& components, std::size_t wavelengths,
                                       double altitudeM, Coefficient coefficient) {
  std::vector<double> sum(wavelengths, 0.0);
  for (const Component& c : components) {
    const double rho = c.density.at(altitudeM);
    if (rho == 0.0) continue;
    for (std::size_t i = 0; i < wavelengths; ++i) sum[i] += rho * coefficient(c, i);
  }
  return sum;
}
}  // namespace

std::vector<double> Atmosphere::scatteringPerM(double altitudeM) const {
  return densityWeightedSum(components, wavelengthsNm.size(), altitudeM,
                            [](const Component& c, std::size_t i) { return c.scatteringPerM[i]; });
}

std::vector<double> Atmosphere::absorptionPerM(double altitudeM) const {
  return densityWeightedSum(components, wavelengthsNm.size(), altitudeM,
                            [](const Component& c, std::size_t i) { return c.absorptionPerM[i]; });
}

std::vector<double> Atmosphere::extinctionPerM(double altitudeM) const {
  return densityWeightedSum(components, wavelengthsNm.size(), altitudeM,
                            [](const Component& c, std::size_t i) { return c.extinctionPerM(i); });
}

std::vector<double> Atmosphere::verticalOpticalDepth(const Component& c, double fromAltitudeM,
                                                     double toAltitudeM) const {
  const double column = c.density.integral(fromAltitudeM, toAltitudeM);
  std::vector<double> tau(wavelengthsNm.size());
  for (std::size_t i = 0; i < tau.size(); ++i) tau[i] = column * c.extinctionPerM(i);
  return tau;
}

std::vector<double> Atmosphere::verticalOpticalDepth(double fromAltitudeM, double toAltitudeM) const {
  std::vector<double> sum(wavelengthsNm.size(), 0.0);
  for (const Component& c : components) {
    const std::vector<double> tau = verticalOpticalDepth(c, fromAltitudeM, toAltitudeM);
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += tau[i];
  }
  return sum;
}

const Component* Atmosphere::find(const std::string& componentName) const {
  for (const Component& c : components)
    if (c.name == componentName) return &c;
  return nullptr;
}

const Component& Atmosphere::component(const std::string& componentName) const {
  const Component* c = find(componentName);
  if (c == nullptr) throw std::out_of_range(name + ": no component '" + componentName + "'");
  return *c;
}

std::string Atmosphere::validate() const {
  if (!(bottomRadiusM >= kMinRadiusM && bottomRadiusM <= kMaxRadiusM))
    return "bottomRadiusM: expected a radius from 1 m to 1e12 m";
  if (!(topRadiusM >= bottomRadiusM + 1.0 && topRadiusM <= kMaxRadiusM))
    return "topRadiusM: expected a radius at least 1 m above bottomRadiusM, at most 1e12 m";
  if (groundAlbedo.size() != wavelengthsNm.size()) return "groundAlbedo: expected one value per wavelength";
  for (double a : groundAlbedo)
    if (!std::isfinite(a) || a < 0.0 || a > 1.0) return "groundAlbedo: expected values in [0, 1]";
  if (!std::isfinite(seaLevelRefractivity) || seaLevelRefractivity < 0.0)
    return "refraction.seaLevelRefractivity: expected a finite number >= 0";
  for (const Component& c : components) {
    const std::string problem = c.validate(wavelengthsNm.size());
    if (!problem.empty()) return "components." + c.name + "." + problem;
  }
  return ductingProblem();
}

// Rays trapped by refraction (ducting): where n decreases outwards faster than 1/r, a ray
// sent along the ground bends round the body and never leaves; the tables would trace it
// round and round. The refractivity F rho(h) (F with 10 % for the dispersion across the
// visible) must fall more slowly than that at every altitude: Earth's falls at 0.23 of it.
std::string Atmosphere::ductingProblem() const {
  if (!(seaLevelRefractivity > 0.0) || refractivityFollows.empty()) return {};
  const Component* c = find(refractivityFollows);
  if (c == nullptr) return {};
  const double F = 1.1 * seaLevelRefractivity, thickness = topRadiusM - bottomRadiusM;
  constexpr int kSamples = 4000;
  for (int k = 0; k <= kSamples; ++k) {
    const double f = static_cast<double>(k) / kSamples;
    const double h = thickness * f * f;  // denser near the ground
    const double d = std::max(0.01, 1e-4 * h);
    const double slope = F * std::abs(c->density.at(h + d) - c->density.at(std::max(0.0, h - d))) /
                         (h + d - std::max(0.0, h - d));
    if (slope * (bottomRadiusM + h) >= 1.0) {
      std::ostringstream at;
      at.precision(4);
      at << h;
      return "refraction: the refractivity falls faster than 1/r at " + at.str() +
             " m above the ground (along components." + c->name +
             ".density): rays there would circle the body (ducting), which the tables cannot hold";
    }
  }
  return {};
}

}  // namespace umbra::atmosphere
