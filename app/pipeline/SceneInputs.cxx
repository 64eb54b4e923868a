#include "SceneInputs.h"

#include "Atmosphere.hpp"
#include "Sky.hpp"  // skyLowestSunZenithRad
#include "Spectrum.hpp"
#include "AtmosphereTablesBlocks.h"
#include "FieldParameters.h"
#include "vtkAtmosphereTablesSource.h"

#include <vtkImageData.h>
#include <vtkMultiBlockDataSet.h>

#include "AtmosphericShadow.hpp"  // defaultTerrain()
#include "Colour.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Planets.hpp"
#include "scene/Scene.hpp"
#include "scene/Stars.hpp"
#include "MilkyWay.hpp"
#include "StarCatalogue.hpp"
#include "StarCatalogueCache.h"
#include "StarLight.hpp"
#include "scene/Units.hpp"  // kAuM

#include "Earthshine.hpp"
#include "MoonGeometry.hpp"  // angleBetween
#include "Photometry.hpp"
#include "PlanetMagnitudes.hpp"  // planetBMinusV, kSunBMinusV

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <cmath>
#include <stdexcept>

namespace umbra::pipeline {

namespace {
vtkImageData* refractionBlock(vtkMultiBlockDataSet* blocks) {
  for (unsigned i = 0; i < blocks->GetNumberOfBlocks(); ++i) {
    const auto p = filters::fieldParameters(blocks->GetBlock(i));
    const auto kind = p.find("kind");
    if (kind != p.end() && kind->second == "atmosphere-refraction") return vtkImageData::SafeDownCast(blocks->GetBlock(i));
  }
  throw std::runtime_error("atmosphere tables: no refraction block");
}

// The body in.atmosphere surrounds; nullptr without one.
const SphereBody* findAtmosphereBody(const SceneInputs& in) {
  if (!in.atmosphere) return nullptr;
  const auto body = std::find_if(in.bodies.begin(), in.bodies.end(),
                                 [&](const SphereBody& b) { return b.name == in.atmosphere->body; });
  return body == in.bodies.end() ? nullptr : &*body;
}
const SphereBody& atmosphereBody(const SceneInputs& in) {
  if (!in.atmosphere) throw std::logic_error("the scene has no atmosphere");
  const SphereBody* body = findAtmosphereBody(in);
  if (!body) throw std::logic_error("no body '" + in.atmosphere->body + "' for its atmosphere");
  return *body;
}
// The albedo of a scene body as its SphereBody takes it: Lambert's 3/2 of the geometric
// albedo (exact for a Lambertian sphere), Hapke's A = p / I(0) (sky::albedoForGeometricAlbedo).
double bodyAlbedo(const scene::Body& b) {
  return b.photometry.law == sky::Photometry::Law::Hapke ? sky::albedoForGeometricAlbedo(b.albedo, b.photometry.hapke)
                                                          : 1.5 * b.albedo;
}

// A body's colour in the frames' white balance at unit luminance: its "color" read as its
// reflectance at 680, 550, 440 nm (sky::reflectanceTint); white when that is all zero.
glm::dvec3 bodyTint(const scene::Body& b) {
  return b.color.x + b.color.y + b.color.z > 0.0 ? sky::reflectanceTint(b.color) : glm::dvec3(1.0);
}

// The earthshine on `body` (sky::earthshineIrradiance), with its colour: W m^-2 per channel.
glm::dvec3 earthshineOn(const scene::Body& body, const scene::Body& earth, const glm::dvec3& sunM) {
  const glm::dvec3 toSun = sunM - earth.positionM, toBody = body.positionM - earth.positionM;
  const double auOverR = scene::kAuM / glm::length(toSun);
  const double e = sky::earthshineIrradiance(sky::kSolarConstantWm2 * auOverR * auOverR, earth.albedo, earth.radiusM,
                                             glm::length(toBody), sky::angleBetween(toSun, toBody));
  return e * sky::earthshineColour();
}

// The scene's stars to its limiting magnitude, seen from its camera; with scintillation
// when the camera is in an atmosphere (`air`: the planet's centre and top radius). Then the
// planets as bright as that (scene/Planets.hpp: astrometric places, reflected sunlight
// taken with the Sun's colour), when the scene has a time.
std::vector<StarPoint> sceneStars(const scene::Scene& s, const glm::dvec3& cameraM, double sunIrradianceAt1AuWm2,
                                  const std::optional<std::pair<glm::dvec3, double>>& air) {
  const auto all = starCatalogue(s.stars->cataloguePath);
  std::vector<sky::CatalogueStar> bright;
  for (const sky::CatalogueStar& star : *all)
    if (star.vMag <= s.stars->limitingMagnitude) bright.push_back(star);
  const std::vector<glm::dvec3> directions =
      scene::apparentStarDirections(bright, s.time, scene::starObserverOf(s));
  std::vector<StarPoint> stars(bright.size());
  const bool twinkle = s.stars->scintillation > 0.0 && air && glm::length(cameraM - air->first) < air->second;
  const glm::dvec3 zenith = air ? glm::normalize(cameraM - air->first) : glm::dvec3(0.0, 0.0, 1.0);
  // The frame's time mixed into the seed (milliseconds since J2000.0).
  static const scene::UtcTime j2000 = scene::parseUtc("2000-01-01T12:00:00Z");
  const auto ms = static_cast<std::int64_t>(std::llround(1e3 * scene::secondsBetween(j2000, s.time)));
  const std::uint64_t seed = s.stars->seed * 0x9e3779b97f4a7c15ull ^ static_cast<std::uint64_t>(ms);
  for (std::size_t i = 0; i < bright.size(); ++i) {
    stars[i] = {directions[i], sky::starFrameIrradianceWm2(bright[i].vMag, bright[i].bMinusV, sunIrradianceAt1AuWm2)};
    const double cosZ = glm::dot(zenith, directions[i]);
    if (twinkle && cosZ > 0.0) {
      const double airMass = sky::airMass(std::acos(std::min(cosZ, 1.0)));
      stars[i].irradianceWm2 *= sky::scintillationFactor(s.stars->scintillation, airMass, seed, i);
    }
  }
  if (s.hasTime)
    for (const scene::PlanetSeen& p : scene::planetsSeenFrom(cameraM, s.time))
      if (p.magnitudeV <= s.stars->limitingMagnitude)
        stars.push_back({p.directionIcrs, sunIrradianceAt1AuWm2 * sky::irradianceRelativeToSun(p.magnitudeV) *
                                              sky::reflectedFrameColour(sky::planetBMinusV(p.name), sky::kSunBMinusV)});
  return stars;
}

// The Moon's light and the night glow of in.atmosphere (SceneAtmosphere), for a camera in
// the air at night.
void nightLights(const scene::Scene& s, SceneInputs& in) {
  SceneAtmosphere& a = *in.atmosphere;
  const scene::Body* planet = s.find(a.body);
  if (!planet) return;
  const glm::dvec3 cam = in.camera.positionM, up = glm::normalize(cam - planet->positionM);
  if (glm::length(cam - planet->positionM) >= a.topRadiusM) return;
  const auto elevationDeg = [&](const glm::dvec3& p) {
    return 90.0 - sky::angleBetween(up, p - cam) * 180.0 / glm::pi<double>();
  };
  if (elevationDeg(in.sun.positionM) >= 0.0) return;
  if (planet->preset == "Earth") {
    const double milkyWayMean =
        in.milkyWay ? in.milkyWay->sphereMeanRadiancePerSunIrradiance * in.sun.irradianceAt1AuWm2 : 0.0;
    a.nightGlowWm2Sr = sky::nightGlowAboveAirWm2Sr(a.zenithOpticalDepth550, in.sun.irradianceAt1AuWm2, milkyWayMean);
  }
  for (const scene::Body& b : s.bodies) {
    if (b.preset != "Moon" || b.name == a.body || elevationDeg(b.positionM) < -5.0) continue;
    const sky::HapkeParameters hapke =
        b.photometry.law == sky::Photometry::Law::Hapke ? b.photometry.hapke : sky::moonParameters();
    const glm::dvec3 toSun = in.sun.positionM - b.positionM, toCamera = cam - b.positionM;
    const double v = sky::apparentMagnitudeV(b.albedo, hapke, sky::angleBetween(toSun, toCamera), b.radiusM,
                                             glm::length(toSun), glm::length(toCamera));
    // The planet's shadow on the Moon as the camera sees it (eclipse::occluderSeenBy).
    const eclipse::Occluder moon = eclipse::seenFromCamera(scene::occluderOf(s, b), cam);
    eclipse::Occluder air = scene::occluderOf(s, *planet);
    air.radiusM = a.bottomRadiusM;
    const glm::dvec3 shadow =
        eclipse::eclipseFactor(moon.centreM, in.sun.positionM, in.sun.radiusM,
                               eclipse::occluderSeenBy(air, moon.centreM, b.radiusM, moon.lightDelayS), nullptr);
    a.moonPositionM = b.positionM;
    a.moonIrradianceWm2 = in.sun.irradianceAt1AuWm2 * sky::irradianceRelativeToSun(v) * bodyTint(b) * shadow;
    return;
  }
}
// The cloud layers of in.atmosphere's body as the renderer draws them (SceneAtmosphere).
void sceneClouds(const scene::Scene& s, SceneInputs& in) {
  SceneAtmosphere& a = *in.atmosphere;
  const scene::Body* planet = s.find(a.body);
  if (!planet || planet->clouds.empty()) return;
  const bool fixed = !planet->preset.empty() && scene::hasRotationModel(planet->preset) && s.hasTime;
  const glm::dmat3 toBody = fixed ? glm::transpose(scene::bodyFixedToInertial(planet->preset, s.time)) : glm::dmat3(1.0);
  const glm::dvec3 foot = toBody * (in.camera.positionM - planet->positionM);
  const double seconds = s.hasTime ? scene::secondsBetween(s.fileTime, s.time) : 0.0;
  for (const sky::CloudLayer& l : planet->clouds)
    a.clouds.push_back({l, sky::cloudDrift(l, foot, a.bottomRadiusM + l.altitudeM, 0.0, seconds) * toBody});
  const auto receiver = std::find_if(in.bodies.begin(), in.bodies.end(), [&](const SphereBody& b) { return b.name == a.body; });
  for (const SphereBody& b : in.bodies)
    if (b.name != a.body)
      a.cloudSunFactor *= eclipse::eclipseFactor(in.camera.positionM, in.sun.positionM, in.sun.radiusM,
                                                 occluderOf(receiver == in.bodies.end() ? b : occluderSeenBy(b, *receiver)),
                                                 nullptr);
}
} // namespace

SceneInputs sceneInputs(const scene::Scene& s) {
  SceneInputs in;
  const scene::Body& sun = s.sun();
  in.sun.positionM = sun.positionM;
  in.sun.radiusM = sun.radiusM;
  const scene::Body* earth = nullptr;
  for (const scene::Body& b : s.bodies)
    if (b.preset == "Earth") earth = &b;
  for (const scene::Body& b : s.bodies) {
    if (b.isSun()) continue;
    SphereBody body{b.name, b.positionM, b.radiusM,
                    b.albedoMapReflectance ? glm::dvec3(1.0) : bodyAlbedo(b) * bodyTint(b)};
    body.photometry = b.photometry;
    if (!b.albedoMapPath.empty())
      body.albedoMap = mapTexels(b.albedoMapPath, b.albedoMapReflectance ? MapKind::Reflectance : MapKind::RelativeAlbedo);
    body.albedoMapReflectance = b.albedoMapReflectance;
    if (!b.normalMapPath.empty()) body.normalMap = mapTexels(b.normalMapPath, MapKind::Normals);
    body.reliefStrength = b.reliefStrength;
    body.velocityMps = b.velocityMps;
    if (!b.preset.empty() && scene::hasRotationModel(b.preset) && s.hasTime)
      body.bodyFixedToInertial = scene::bodyFixedToInertial(b.preset, s.time);
    body.flattening = scene::shadowFigure(s, b).flattening;  // about bodyFixedToInertial's z
    if (earth && earth != &b && b.photometry.law == sky::Photometry::Law::Hapke) {
      body.earthCentreM = earth->positionM;
      body.earthshineWm2 = earthshineOn(b, *earth, sun.positionM);
    }
    in.bodies.push_back(body);
    if (!b.atmosphere) continue;
    if (in.atmosphere) {
      throw std::invalid_argument("only one atmosphere per view is drawn ('" + in.atmosphere->body +
                                  "' and '" + b.name + "' ask for one)");
    }
    const atmosphere::Atmosphere& model = b.atmosphere->rgb();
    in.atmosphere = SceneAtmosphere{b.name, b.atmosphere, model.bottomRadiusM, model.topRadiusM};
    in.atmosphere->zenithOpticalDepth550 = model.verticalOpticalDepth(0.0, model.thicknessM())[1];  // 680, 550, 440 nm
    in.bodies.back().radiusM = model.bottomRadiusM;
    // A reflectance map is the ground's albedo in the composite, which draws the ground
    // anew; the receiver under it has a uniform albedo, so that the frame gives back the
    // eclipse alone (the same map sampled twice would not agree to the pixel).
    if (b.albedoMapReflectance) {
      in.atmosphere->groundAlbedoMap = in.bodies.back().albedoMap;
      in.bodies.back().albedoMap.reset();
      in.bodies.back().albedoMapReflectance = false;
    }
  }
  in.camera.positionM = s.camera.positionM;
  in.camera.targetM = s.camera.targetM;
  // An observer on the body with the atmosphere stands on its ground sphere.
  if (in.atmosphere && s.camera.observer && s.camera.observer->body == in.atmosphere->body) {
    for (const SphereBody& b : in.bodies) {
      if (b.name != in.atmosphere->body) continue;
      const glm::dvec3 up = glm::normalize(s.camera.positionM - b.centreM);
      const glm::dvec3 moved = b.centreM + up * (b.radiusM + std::max(s.camera.observer->altM, 1.0));
      in.camera.targetM += moved - in.camera.positionM;
      in.camera.positionM = moved;
    }
  }
  // Bodies are spheres of their mean radius, but an observer stands on the ellipsoid:
  // near the poles that is below the mean radius (by up to 0.3 % for the Earth, 0.6 %
  // for Mars), inside the sphere. Such a sphere is shrunk to just below the observer, so
  // that it still casts its shadow; a camera deeper inside a body is an error.
  for (SphereBody& b : in.bodies) {
    const double d = glm::length(in.camera.positionM - b.centreM);
    if (!(d > 0.98 * b.radiusM))
      throw std::invalid_argument("the camera is inside '" + b.name + "' (" + std::to_string(std::lround(d)) +
                                  " m from its centre, radius " + std::to_string(std::lround(b.radiusM)) + " m)");
    b.radiusM = std::min(b.radiusM, d * (1.0 - 1e-6));
  }
  // Each body as the camera sees it: where it was a light time before (from its near
  // surface); the Sun stays, at rest. A body the camera stands on does not move, and the
  // camera keeps a body it targets at the centre.
  for (SphereBody& b : in.bodies) {
    const eclipse::Occluder drawn = eclipse::seenFromCamera(occluderOf(b), in.camera.positionM);
    if (b.name == s.camera.targetBody) in.camera.targetM += drawn.centreM - b.centreM;
    b.centreM = drawn.centreM;
    b.lightDelayS = drawn.lightDelayS;
  }
  in.camera.up = s.camera.up;
  in.camera.fovDeg = s.camera.fovDeg;
  if (s.stars) {
    std::optional<std::pair<glm::dvec3, double>> air;
    if (in.atmosphere)
      if (const scene::Body* planet = s.find(in.atmosphere->body)) air = {{planet->positionM, in.atmosphere->topRadiusM}};
    in.stars = sceneStars(s, in.camera.positionM, in.sun.irradianceAt1AuWm2, air);
    if (!s.stars->milkyWayPath.empty()) {
      in.milkyWay = milkyWayTexels(s.stars->milkyWayPath, s.stars->cataloguePath,
                                   std::min(s.stars->limitingMagnitude, sky::kMilkyWayStarsShownToV));
      in.milkyWayRadianceScale = in.milkyWay->radiancePerSunIrradiance * in.sun.irradianceAt1AuWm2;
    }
  }
  if (in.atmosphere) {
    nightLights(s, in);
    sceneClouds(s, in);
  }
  return in;
}

AtmosphereTableChoice atmosphereTableChoice(const SceneInputs& in) {
  const SphereBody* body = findAtmosphereBody(in);
  if (!body) return {};
  const double b = in.atmosphere->bottomRadiusM, t = in.atmosphere->topRadiusM;
  if (!(b > 0.0 && t > b)) return {};
  const glm::dvec3 up = in.camera.positionM - body->centreM;
  if (glm::length(up) >= t) return {};
  const double deg = glm::pi<double>() / 180.0, kHalfPi = glm::half_pi<double>();
  const double sunZenithRad =
      std::acos(std::clamp(glm::dot(glm::normalize(up), glm::normalize(in.sun.positionM - in.camera.positionM)), -1.0, 1.0));
  // Night: 10 deg past the depression at which the top of the atmosphere on the horizon
  // falls into the shadow (Earth 30 deg, Mars 35 deg).
  const double nightRad = 2.0 * std::acos(b / t) + 10.0 * deg;
  if (sunZenithRad <= 91.0 * deg || sunZenithRad > kHalfPi + nightRad) return {};
  // The sky command's lowest Sun, on a 10 deg grid.
  const double lowest = std::ceil(atmosphere::skyLowestSunZenithRad(sunZenithRad) / (10.0 * deg) - 1e-9) * 10.0 * deg;
  return {true, std::max(lowest, 120.0 * deg)};
}

void configureAtmosphereTables(vtkAtmosphereTablesSource* source, AtmosphereTableSizes sizes,
                               const AtmosphereTableChoice& choice) {
  const bool small = sizes == AtmosphereTableSizes::Small, twilight = choice.twilight;
  const atmosphere::TableSizes& s = small ? atmosphere::kSmallTableSizes : atmosphere::kDefaultTableSizes;
  // Twilight: 4 times the mu_s cells, and half the r cells of the default tables.
  const int finer = twilight ? 4 : 1, fewerR = twilight && !small ? 2 : 1;
  source->SetTransmittanceSize(s.transmittance[0], s.transmittance[1]);
  source->SetScatteringSize(s.scattering[0] / fewerR, s.scattering[1], s.scattering[2] * finer, s.scattering[3]);
  source->SetIrradianceSize(s.irradiance[0] * finer, s.irradiance[1]);
  source->SetOrders(s.orders);
  source->SetMuSMin(twilight ? std::cos(choice.lowestSunZenithRad) : atmosphere::PrecomputeOptions().muSMin);
  source->SetMinimumDensityDirections(twilight ? 24 : 0);
}

void configureSceneAtmosphereTables(vtkAtmosphereTablesSource* source, const SceneInputs& in, bool refraction,
                                    AtmosphereTableSizes sizes) {
  atmosphereBody(in);
  configureAtmosphereTables(source, sizes, atmosphereTableChoice(in));
  source->SetAtmosphereModel(in.atmosphere->model);
  source->SetWavelengths(3);
  source->SetTables(vtkAtmosphereTablesSource::Bruneton | (refraction ? vtkAtmosphereTablesSource::Refraction : 0));
  source->SetRefractedPaths(refraction);
}

void showSceneAtmosphereTables(BodyView& view, const SceneInputs& in, vtkAtmosphereTablesSource* source) {
  const SphereBody& body = atmosphereBody(in);
  const SceneAtmosphere& a = *in.atmosphere;
  source->Update();
  if (!source->GetLastError().empty())
    throw std::runtime_error("atmosphere of '" + a.body + "': " + source->GetLastError());
  const bool refraction = source->GetRefractedPaths();
  const atmosphere::Atmosphere& model = a.model->rgb();
  view.GetAtmosphere().SetAtmosphere(model, filters::tablesFromBlocks(source->GetOutput(), model), body.centreM,
                                     body.albedoRgb);
  // A reflectance map (the Earth's colour) is the ground's albedo under the air.
  view.GetAtmosphere().SetGroundAlbedoMap(a.groundAlbedoMap, body.bodyFixedToInertial);
  view.GetAtmosphere().SetRefraction(refraction ? refractionBlock(source->GetOutput()) : nullptr);
  view.GetAtmosphere().SetTerrainMeanElevation(eclipse::defaultTerrain(a.body).meanElevationM);
}

void showSceneSky(BodyView& view, const SceneInputs& in) {
  view.SetStars(in.stars);
  view.SetMilkyWay(in.milkyWay ? in.milkyWay->map : nullptr, in.milkyWayRadianceScale);
  const SceneAtmosphere none;
  const SceneAtmosphere& a = in.atmosphere ? *in.atmosphere : none;
  view.GetAtmosphere().SetMoonLight(a.moonPositionM, a.moonIrradianceWm2);
  view.GetAtmosphere().SetNightGlow(a.nightGlowWm2Sr);
  view.GetAtmosphere().SetClouds(a.clouds, a.cloudSunFactor);
}

void applySceneAtmosphere(BodyView& view, const SceneInputs& in, vtkAtmosphereTablesSource* source, bool refraction,
                          AtmosphereTableSizes sizes) {
  if (!in.atmosphere) {
    view.GetAtmosphere().ClearAtmosphere();
    return;
  }
  configureSceneAtmosphereTables(source, in, refraction, sizes);
  showSceneAtmosphereTables(view, in, source);
}

void useSmallAtmosphereTables(vtkAtmosphereTablesSource* source) {
  configureAtmosphereTables(source, AtmosphereTableSizes::Small);
}

} // namespace umbra::pipeline
