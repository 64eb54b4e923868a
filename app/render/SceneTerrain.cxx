#include "SceneTerrain.h"

#include "CraterField.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Scene.hpp"

#include <vtkRenderer.h>

#include <stdexcept>

namespace umbra::render {

TerrainPatch sceneTerrainPatch(const scene::Scene& scene, const std::string& bodyName, const SceneInputs& in,
                               const DemLoader& loadDem) {
  const scene::Body* body = scene.find(bodyName);
  if (!body || !body->terrain) throw std::invalid_argument("body '" + bodyName + "' has no terrain");
  const scene::Terrain& t = *body->terrain;
  const SphereBody* sphere = nullptr;
  for (const SphereBody& b : in.bodies)
    if (b.name == bodyName) sphere = &b;
  if (!sphere) throw std::invalid_argument("body '" + bodyName + "' is not drawn (the Sun cannot carry a terrain)");
  TerrainPatch patch;
  if (t.demPath.empty()) {
    terrain::CraterFieldOptions o;
    o.seed = t.seed;
    o.size = t.size;
    o.spacingM = t.spacingM;
    o.bodyRadiusM = body->radiusM;
    patch.field = terrain::makeCraterField(o);
  } else {
    if (!loadDem) throw std::invalid_argument("body '" + bodyName + "': no DEM reader for " + t.demPath);
    patch.field = loadDem(t.demPath, t.spacingM, body->radiusM);
  }
  patch.bodyCentreM = sphere->centreM;
  patch.albedoRgb = sphere->albedoRgb;
  // Tangent frame -> body-fixed -> inertial (the world of the scene).
  patch.tangentToWorld = scene::bodyFixedToInertial(body->preset, scene.time) *
                         glm::transpose(terrain::bodyFixedToTangent(t.latDeg, t.lonDeg));
  return patch;
}

std::vector<std::unique_ptr<TerrainRendering>> addSceneTerrains(BodyView& view, const scene::Scene& scene,
                                                                const SceneInputs& in, const DemLoader& loadDem) {
  std::vector<std::unique_ptr<TerrainRendering>> out;
  for (const scene::Body& b : scene.bodies) {
    if (!b.terrain) continue;
    auto t = std::make_unique<TerrainRendering>();
    t->SetTerrain(sceneTerrainPatch(scene, b.name, in, loadDem));
    t->SetSun(in.sun);
    t->SetOrigin(view.GetCamera().positionM);
    view.GetRenderer()->AddActor(t->GetActor());
    out.push_back(std::move(t));
  }
  return out;
}

} // namespace umbra::render
