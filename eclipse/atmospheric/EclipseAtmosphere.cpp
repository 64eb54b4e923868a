#include "EclipseAtmosphere.hpp"

#include "Describe.hpp"
#include "SightLines.hpp"

#include <sstream>
#include <stdexcept>

namespace umbra::eclipse {
namespace {

void checkOptions(const EclipseAtmosphereOptions& options) {
  if (options.refractionWidth < 2 || options.refractionHeight < 2 || !(options.refractionStepM > 0.0) ||
      options.profileSamples < 2)
    throw std::invalid_argument("eclipse atmosphere: refraction table >= 2x2, step > 0, profile samples >= 2");
}

/// The refraction table's top two rows: the limb ray profile samples the table at the top
/// of the atmosphere only, and these rows are the whole table's there, to the bit.
atmosphere::RefractionTable limbRefraction(const atmosphere::Atmosphere& atm, const EclipseAtmosphereOptions& o) {
  return atmosphere::buildRefractionTable(atmosphere::refractiveMedium(atm, atm.refractivityReferenceWavelengthNm),
                                          o.refractionWidth, o.refractionHeight, o.refractionStepM, {},
                                          o.refractionHeight - 2);
}

/// The shadow model over the prepared tables of `e`.
void finishModel(EclipseAtmosphere& e, const std::string& occluderName, double sunOccluderDistanceM,
                 const EclipseAtmosphereOptions& options) {
  AtmosphericShadowModel& m = e.model;
  m.system = {kSunRadiusM, e.atmosphere.bottomRadiusM, sunOccluderDistanceM};
  m.rays = limbRayProfile(e.tables, options.refraction ? &e.refraction : nullptr, options.profileSamples);
  m.tables = &e.tables;
  m.atmosphere = &e.atmosphere;
  m.terrain = defaultTerrain(occluderName);
  if (options.terrainMeanElevationM >= 0.0) m.terrain.meanElevationM = options.terrainMeanElevationM;
  if (const std::string err = m.validate(); !err.empty()) throw std::invalid_argument("eclipse atmosphere: " + err);
}

} // namespace

std::unique_ptr<EclipseAtmosphere> prepareEclipseAtmosphere(const atmosphere::Atmosphere& atm,
                                                            const std::string& occluderName,
                                                            double sunOccluderDistanceM,
                                                            const EclipseAtmosphereOptions& options,
                                                            const EclipseProgress& progress) {
  checkOptions(options);
  auto e = std::make_unique<EclipseAtmosphere>();
  e->atmosphere = atm;
  atmosphere::PrecomputeOptions po = options.tables;
  po.refraction = options.refraction;
  po.refractionStepM = options.refractionStepM;
  e->tables = atmosphere::precompute(e->atmosphere, po, [&](double f, const std::string& stage) {
    return !progress || progress(0.99 * f, stage);
  });
  if (options.refraction) {
    if (progress && !progress(0.99, "refraction")) throw atmosphere::PrecomputeCancelled();
    e->refraction = limbRefraction(e->atmosphere, options);
  }
  finishModel(*e, occluderName, sunOccluderDistanceM, options);
  if (progress) progress(1.0, "done");
  return e;
}

std::unique_ptr<EclipseAtmosphere> prepareEclipseAtmosphere(const atmosphere::Atmosphere& atm,
                                                            atmosphere::AtmosphereTables tables,
                                                            atmosphere::RefractionTable refraction,
                                                            const std::string& occluderName,
                                                            double sunOccluderDistanceM,
                                                            const EclipseAtmosphereOptions& options) {
  checkOptions(options);
  if (tables.wavelengthsNm != atm.wavelengthsNm || tables.bottomRadiusM != atm.bottomRadiusM ||
      tables.topRadiusM != atm.topRadiusM)
    throw std::invalid_argument("eclipse atmosphere: the tables were made for another atmosphere (radii or wavelengths)");
  if (options.refraction && !refraction.deviationRad.empty() &&
      (refraction.bottomRadiusM != atm.bottomRadiusM || refraction.topRadiusM != atm.topRadiusM))
    throw std::invalid_argument("eclipse atmosphere: the refraction table was made for another atmosphere (radii)");
  auto e = std::make_unique<EclipseAtmosphere>();
  e->atmosphere = atm;
  e->tables = std::move(tables);
  if (options.refraction)
    e->refraction = refraction.deviationRad.empty() ? limbRefraction(atm, options) : std::move(refraction);
  finishModel(*e, occluderName, sunOccluderDistanceM, options);
  return e;
}

std::map<std::string, std::string> eclipseAtmosphereParameters(const atmosphere::Atmosphere& atm,
                                                               const std::string& occluderName,
                                                               double sunOccluderDistanceM,
                                                               const EclipseAtmosphereOptions& o) {
  std::map<std::string, std::string> p = atmosphere::atmosphereParameters(atm);
  const atmosphere::PrecomputeOptions& t = o.tables;
  std::ostringstream s;
  s << t.transmittanceWidth << "x" << t.transmittanceHeight << " " << t.scatteringR << "," << t.scatteringMu << ","
    << t.scatteringMuS << "," << t.scatteringNu << " " << t.irradianceWidth << "x" << t.irradianceHeight << " orders "
    << t.orders << " samples " << t.transmittanceSamples << " " << t.singleScatteringSamples << " "
    << t.multipleScatteringSamples << " " << t.opticalDepthSubsamples << " " << t.sphereSamples << " "
    << t.irradianceSamples << " muSMin " << atmosphere::formatNumber(t.muSMin) << " sun "
    << atmosphere::formatNumber(t.sunAngularRadiusRad) << " density " << atmosphere::kDensityQuadrature;
  p["atmosphereTables"] = s.str();
  p["refraction"] = o.refraction ? std::to_string(o.refractionWidth) + "x" + std::to_string(o.refractionHeight) +
                                       " step " + atmosphere::formatNumber(o.refractionStepM)
                                 : "off";
  p["profileSamples"] = std::to_string(o.profileSamples);
  const double terrain =
      o.terrainMeanElevationM >= 0.0 ? o.terrainMeanElevationM : defaultTerrain(occluderName).meanElevationM;
  p["terrainMeanElevationM"] = atmosphere::formatNumber(terrain);
  p["sunRadiusM"] = atmosphere::formatNumber(kSunRadiusM);
  p["occluderRadiusM"] = atmosphere::formatNumber(atm.bottomRadiusM);
  p["sunOccluderDistanceM"] = atmosphere::formatNumber(sunOccluderDistanceM);
  return p;
}

} // namespace umbra::eclipse
