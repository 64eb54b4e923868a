#include "EclipseAtmosphere.hpp"

#include "Describe.hpp"
#include "SightLines.hpp"

#include <sstream>
#include <stdexcept>

namespace umbra::eclipse {
namespace {
std::string number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}
} // namespace

std::unique_ptr<EclipseAtmosphere> prepareEclipseAtmosphere(const atmosphere::Atmosphere& atm,
                                                            const std::string& occluderName,
                                                            double sunOccluderDistanceM,
                                                            const EclipseAtmosphereOptions& options,
                                                            const EclipseProgress& progress) {
  if (options.refractionWidth < 2 || options.refractionHeight < 2 || !(options.refractionStepM > 0.0) ||
      options.profileSamples < 2)
    throw std::invalid_argument("eclipse atmosphere: refraction table >= 2x2, step > 0, profile samples >= 2");
  auto e = std::make_unique<EclipseAtmosphere>();
  e->atmosphere = atm;
  atmosphere::PrecomputeOptions po = options.tables;
  po.refraction = options.refraction;
  po.refractionStepM = options.refractionStepM;
  // The Bruneton tables take most of the time; the refraction table about a tenth.
  e->tables = atmosphere::precompute(e->atmosphere, po, [&](double f, const std::string& stage) {
    return !progress || progress(0.9 * f, stage);
  });
  if (options.refraction) {
    if (progress && !progress(0.9, "refraction")) throw atmosphere::PrecomputeCancelled();
    e->refraction = atmosphere::buildRefractionTable(
        atmosphere::refractiveMedium(e->atmosphere, e->atmosphere.refractivityReferenceWavelengthNm),
        options.refractionWidth, options.refractionHeight, options.refractionStepM);
  }
  AtmosphericShadowModel& m = e->model;
  m.system = {kSunRadiusM, atm.bottomRadiusM, sunOccluderDistanceM};
  m.rays = limbRayProfile(e->tables, options.refraction ? &e->refraction : nullptr, options.profileSamples);
  m.tables = &e->tables;
  m.atmosphere = &e->atmosphere;
  m.terrain = defaultTerrain(occluderName);
  if (options.terrainMeanElevationM >= 0.0) m.terrain.meanElevationM = options.terrainMeanElevationM;
  if (const std::string err = m.validate(); !err.empty()) throw std::invalid_argument("eclipse atmosphere: " + err);
  if (progress) progress(1.0, "done");
  return e;
}

std::map<std::string, std::string> eclipseAtmosphereParameters(const EclipseAtmosphere& e,
                                                               const EclipseAtmosphereOptions& o) {
  std::map<std::string, std::string> p = atmosphere::atmosphereParameters(e.atmosphere);
  const atmosphere::PrecomputeOptions& t = e.tables.options;
  std::ostringstream s;
  s << t.transmittanceWidth << "x" << t.transmittanceHeight << " " << t.scatteringR << "," << t.scatteringMu << ","
    << t.scatteringMuS << "," << t.scatteringNu << " " << t.irradianceWidth << "x" << t.irradianceHeight << " orders "
    << t.orders << " samples " << t.transmittanceSamples << " " << t.singleScatteringSamples << " "
    << t.multipleScatteringSamples << " " << t.opticalDepthSubsamples << " " << t.sphereSamples << " "
    << t.irradianceSamples << " muSMin " << number(t.muSMin) << " sun " << number(t.sunAngularRadiusRad);
  p["atmosphereTables"] = s.str();
  p["refraction"] = o.refraction ? std::to_string(o.refractionWidth) + "x" + std::to_string(o.refractionHeight) +
                                       " step " + number(o.refractionStepM)
                                 : "off";
  p["profileSamples"] = std::to_string(o.profileSamples);
  p["terrainMeanElevationM"] = number(e.model.terrain.meanElevationM);
  p["sunRadiusM"] = number(e.model.system.sunRadiusM);
  p["occluderRadiusM"] = number(e.model.system.occluderRadiusM);
  p["sunOccluderDistanceM"] = number(e.model.system.sunOccluderDistanceM);
  p["limbDarkening"] = number(e.model.limbDarkening);
  return p;
}

} // namespace umbra::eclipse
