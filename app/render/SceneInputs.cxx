#include "SceneInputs.h"

#include "Atmosphere.hpp"
#include "Spectrum.hpp"
#include "AtmosphereTablesBlocks.h"
#include "FieldParameters.h"
#include "vtkAtmosphereTablesSource.h"

#include <vtkImageData.h>
#include <vtkMultiBlockDataSet.h>

#include "AtmosphericShadow.hpp"  // defaultTerrain()
#include "ShadowLut.hpp"  // luminance()
#include "scene/Scene.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <stdexcept>

namespace umbra::render {

namespace {
vtkImageData* refractionBlock(vtkMultiBlockDataSet* blocks) {
  for (unsigned i = 0; i < blocks->GetNumberOfBlocks(); ++i) {
    const auto p = filters::fieldParameters(blocks->GetBlock(i));
    const auto kind = p.find("kind");
    if (kind != p.end() && kind->second == "atmosphere-refraction") return vtkImageData::SafeDownCast(blocks->GetBlock(i));
  }
  throw std::runtime_error("atmosphere tables: no refraction block");
}
} // namespace

SceneInputs sceneInputs(const scene::Scene& s) {
  SceneInputs in;
  const scene::Body& sun = s.sun();
  in.sun.positionM = sun.positionM;
  in.sun.radiusM = sun.radiusM;
  for (const scene::Body& b : s.bodies) {
    if (b.isSun()) continue;
    const double tintLuminance = eclipse::luminance(b.color);
    const glm::dvec3 tint = tintLuminance > 0.0 ? b.color / tintLuminance : glm::dvec3(1.0);
    in.bodies.push_back({b.name, b.positionM, b.radiusM, 1.5 * b.albedo * tint});
    if (b.atmosphereModel.empty()) continue;
    if (in.atmosphere) {
      throw std::invalid_argument("only one atmosphere per view is drawn so far ('" + in.atmosphere->body +
                                  "' and '" + b.name + "' ask for one)");
    }
    const atmosphere::Atmosphere model = atmosphere::loadAtmosphere(b.atmosphereModel, atmosphere::WavelengthSet::rgb().nm);
    in.atmosphere = SceneAtmosphere{b.name, b.atmosphereModel, model.bottomRadiusM, model.topRadiusM};
    in.bodies.back().radiusM = model.bottomRadiusM;
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
  // near the poles that is below the mean radius, inside the sphere. Such a sphere is
  // shrunk to just below the observer, so that it still casts its shadow.
  for (SphereBody& b : in.bodies)
    b.radiusM = std::min(b.radiusM, glm::length(in.camera.positionM - b.centreM) * (1.0 - 1e-6));
  in.camera.up = s.camera.up;
  in.camera.fovDeg = s.camera.fovDeg;
  return in;
}

void applySceneAtmosphere(BodyView& view, const SceneInputs& in, vtkAtmosphereTablesSource* source,
                          bool refraction) {
  if (!in.atmosphere) {
    view.GetAtmosphere().ClearAtmosphere();
    return;
  }
  const SceneAtmosphere& a = *in.atmosphere;
  const auto body = std::find_if(in.bodies.begin(), in.bodies.end(), [&](const SphereBody& b) { return b.name == a.body; });
  if (body == in.bodies.end()) throw std::logic_error("no body '" + a.body + "' for its atmosphere");
  source->SetAtmosphere(a.model.c_str());
  source->SetWavelengths(3);
  source->SetTables(vtkAtmosphereTablesSource::Bruneton | (refraction ? vtkAtmosphereTablesSource::Refraction : 0));
  source->SetRefractedPaths(refraction);
  source->Update();
  if (!source->GetLastError().empty())
    throw std::runtime_error("atmosphere of '" + a.body + "': " + source->GetLastError());
  const atmosphere::Atmosphere model = atmosphere::loadAtmosphere(a.model, atmosphere::WavelengthSet::rgb().nm);
  view.GetAtmosphere().SetAtmosphere(model, filters::tablesFromBlocks(source->GetOutput(), model), body->centreM,
                                     body->albedoRgb);
  view.GetAtmosphere().SetRefraction(refraction ? refractionBlock(source->GetOutput()) : nullptr);
  view.GetAtmosphere().SetTerrainMeanElevation(eclipse::defaultTerrain(a.body).meanElevationM);
}

void useSmallAtmosphereTables(vtkAtmosphereTablesSource* source) {
  source->SetTransmittanceSize(64, 16);
  source->SetScatteringSize(8, 32, 8, 4);
  source->SetIrradianceSize(16, 4);
  source->SetOrders(3);
}

} // namespace umbra::render
