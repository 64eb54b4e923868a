#include "Sky.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::atmosphere {
namespace {

constexpr double kPi = 3.14159265358979323846;

int stepCount(double rangeRad, double stepRad) {
  return static_cast<int>(std::floor(rangeRad / stepRad + 1e-9)) + 1;
}

} // namespace

PrecomputeOptions skyPrecomputeOptions(const Atmosphere& atmosphere, int orders, double sunZenithRad) {
  PrecomputeOptions o;
  o.transmittanceWidth = 128;
  o.transmittanceHeight = 32;
  o.scatteringR = 8;
  o.scatteringMu = 64;
  o.scatteringMuS = 128;
  o.scatteringNu = 8;
  o.irradianceWidth = 32;
  o.irradianceHeight = 8;
  o.sphereSamples = sunZenithRad > kPi / 2 ? 24 : 12;
  const int asked = densityDirectionsFor(atmosphere);
  if (asked > kMinDensityDirections) o.sphereSamples = std::max(o.sphereSamples, asked);  // a forward peak
  o.irradianceSamples = 16;
  o.singleScatteringSamples = 40;
  o.multipleScatteringSamples = 40;
  o.orders = orders;
  o.muSMin = std::cos(skyLowestSunZenithRad(sunZenithRad));
  return o;
}

double skyLowestSunZenithRad(double sunZenithRad) {
  const double deg = kPi / 180.0;
  return std::clamp(sunZenithRad + 20.0 * deg, 102.0 * deg, 170.0 * deg);
}

glm::dvec3 solarXyzLux() {
  // 1 nm trapezoid; both functions are piecewise linear on (at most) 1 nm pieces or
  // smoother, so this is accurate to far better than 0.1 %.
  glm::dvec3 sum(0.0);
  for (int nm = static_cast<int>(kCmfMinNm); nm <= static_cast<int>(kCmfMaxNm); ++nm) {
    const double w = (nm == static_cast<int>(kCmfMinNm) || nm == static_cast<int>(kCmfMaxNm)) ? 0.5 : 1.0;
    sum += w * solarIrradianceWm2PerNm(nm) * cie1931(nm);
  }
  return kMaxLuminousEfficacyLmPerW * sum;
}

double solarIlluminanceLux() { return solarXyzLux().y; }

SkySample skyLuminanceAt(const AtmosphereTables& tables, const Atmosphere& atmosphere,
                         const WavelengthSet& wavelengths, double sunZenithRad, double observerAltitudeM,
                         double viewZenithRad, double azimuthRad) {
  const double r = tables.bottomRadiusM + observerAltitudeM;
  const double mu = std::cos(viewZenithRad);
  const double muS = std::cos(sunZenithRad);
  const double nu = std::clamp(
      mu * muS + std::sin(viewZenithRad) * std::sin(sunZenithRad) * std::cos(azimuthRad), -1.0, 1.0);
  std::vector<double> sun(wavelengths.size());
  for (std::size_t l = 0; l < sun.size(); ++l) sun[l] = solarIrradianceWm2PerNm(wavelengths.nm[l]);
  const std::vector<double> L = skyRadiance(tables, atmosphere, r, mu, muS, nu, sun);
  const glm::dvec3 xyz = spectralRadianceToXyz(wavelengths, L);
  SkySample s;
  s.viewZenithRad = viewZenithRad;
  s.azimuthRad = azimuthRad;
  s.luminanceCdM2 = xyz.y;
  s.linearSrgb = xyzToLinearSrgb(xyz);
  return s;
}

SkyGrid skyLuminance(const AtmosphereTables& tables, const Atmosphere& atmosphere,
                     const WavelengthSet& wavelengths, double sunZenithRad, double observerAltitudeM,
                     double zenithStepRad, double azimuthStepRad) {
  if (!(zenithStepRad > 0.0 && zenithStepRad <= kPi / 2 + 1e-12))
    throw std::invalid_argument("sky: the zenith step must be in (0, 90] degrees");
  if (!(azimuthStepRad > 0.0 && azimuthStepRad <= kPi / 2 + 1e-12))
    throw std::invalid_argument("sky: the azimuth step must be in (0, 90] degrees");
  if (!(sunZenithRad >= 0.0 && sunZenithRad <= kPi))
    throw std::invalid_argument("sky: the Sun zenith angle must be in [0, 180] degrees");
  if (!(observerAltitudeM >= 0.0 && tables.bottomRadiusM + observerAltitudeM < tables.topRadiusM))
    throw std::invalid_argument("sky: the observer altitude must be >= 0 and inside the atmosphere");
  if (wavelengths.nm != tables.wavelengthsNm)
    throw std::invalid_argument("sky: the tables were computed at other wavelengths");

  if ((0.5 * kPi / zenithStepRad + 1.0) * (kPi / azimuthStepRad + 1.0) > kMaxSkyDirections)  // before int counts
    throw std::invalid_argument("sky: more than " + std::to_string(kMaxSkyDirections) + " directions");
  SkyGrid g;
  g.sunZenithRad = sunZenithRad;
  g.observerAltitudeM = observerAltitudeM;
  g.solarIlluminanceLux = solarIlluminanceLux();
  g.zenithStepRad = zenithStepRad;
  g.azimuthStepRad = azimuthStepRad;
  g.zenithCount = stepCount(kPi / 2, zenithStepRad);
  g.azimuthCount = stepCount(kPi, azimuthStepRad);
  g.samples.reserve(static_cast<std::size_t>(g.zenithCount) * g.azimuthCount);
  for (int iz = 0; iz < g.zenithCount; ++iz)
    for (int ia = 0; ia < g.azimuthCount; ++ia)
      g.samples.push_back(skyLuminanceAt(tables, atmosphere, wavelengths, sunZenithRad, observerAltitudeM,
                                         std::min(iz * zenithStepRad, kPi / 2), std::min(ia * azimuthStepRad, kPi)));
  return g;
}

double cieGradation(const CieSkyParameters& p, double zenithRad) {
  const double c = std::cos(zenithRad);
  if (c <= 0.0) return 1.0;  // exp(b / cos Z) -> 0 for b < 0 (all 15 standard skies)
  return 1.0 + p.a * std::exp(p.b / c);
}

double cieIndicatrix(const CieSkyParameters& p, double chiRad) {
  const double c = std::cos(chiRad);
  return 1.0 + p.c * (std::exp(p.d * chiRad) - std::exp(p.d * kPi / 2)) + p.e * c * c;
}

double cieRelativeLuminance(const CieSkyParameters& p, double viewZenithRad, double azimuthFromSunRad,
                            double sunZenithRad) {
  const double cosChi = std::clamp(std::cos(viewZenithRad) * std::cos(sunZenithRad) +
                                       std::sin(viewZenithRad) * std::sin(sunZenithRad) * std::cos(azimuthFromSunRad),
                                   -1.0, 1.0);
  const double chi = std::acos(cosChi);
  return cieIndicatrix(p, chi) * cieGradation(p, viewZenithRad) /
         (cieIndicatrix(p, sunZenithRad) * cieGradation(p, 0.0));
}

SkyComparison compareWithCie(const SkyGrid& grid, const CieSkyParameters& p, const SkyComparisonOptions& options) {
  if (grid.samples.empty() || grid.at(0, 0).viewZenithRad != 0.0)
    throw std::invalid_argument("sky comparison: the grid must start at the zenith");
  const double zenith = grid.at(0, 0).luminanceCdM2;
  if (!(zenith > 0.0)) throw std::invalid_argument("sky comparison: the zenith luminance is not positive");

  struct Pair {
    double model, cie, weight, z, a;
  };
  std::vector<Pair> pairs;
  for (const SkySample& s : grid.samples) {
    if (s.viewZenithRad > options.maxViewZenithRad + 1e-12) continue;
    const double cosChi = std::cos(s.viewZenithRad) * std::cos(grid.sunZenithRad) +
                          std::sin(s.viewZenithRad) * std::sin(grid.sunZenithRad) * std::cos(s.azimuthRad);
    if (std::acos(std::clamp(cosChi, -1.0, 1.0)) < options.excludeAroundSunRad) continue;
    // Solid angle of the sample: sin Z (the zenith itself gets the cap's share, so that it
    // counts once and not zero times).
    const double w = std::max(std::sin(s.viewZenithRad), 0.25 * grid.zenithStepRad);
    pairs.push_back({s.luminanceCdM2 / zenith,
                     cieRelativeLuminance(p, s.viewZenithRad, s.azimuthRad, grid.sunZenithRad), w,
                     s.viewZenithRad, s.azimuthRad});
  }
  SkyComparison out;
  if (pairs.empty()) return out;
  double scale = 1.0;
  if (options.normalisation == SkyNormalisation::Mean) {
    double sm = 0.0, sc = 0.0;
    for (const Pair& q : pairs) sm += q.weight * q.model, sc += q.weight * q.cie;
    scale = sc / sm;
  }
  double sw = 0.0, se = 0.0, se2 = 0.0;
  for (const Pair& q : pairs) {
    const double e = scale * q.model / q.cie - 1.0;
    sw += q.weight;
    se += q.weight * e;
    se2 += q.weight * e * e;
    if (std::abs(e) > out.maxRelativeError) {
      out.maxRelativeError = std::abs(e);
      out.maxErrorZenithRad = q.z;
      out.maxErrorAzimuthRad = q.a;
    }
  }
  out.samples = static_cast<int>(pairs.size());
  out.rmsRelativeError = std::sqrt(se2 / sw);
  out.meanRelativeError = se / sw;
  return out;
}

}  // namespace umbra::atmosphere
