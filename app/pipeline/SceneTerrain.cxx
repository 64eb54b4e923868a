#include "SceneTerrain.h"

#include "CraterField.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Scene.hpp"

#include <vtkRenderer.h>

#include <stdexcept>

namespace umbra::pipeline {

namespace {

/// The patch's placement at the scene time: the body's centre, the rotation tangent frame
/// -> body-fixed -> inertial (the world of the scene), the albedo of the body's sphere.
TerrainPatch placement(const scene::Scene& scene, const std::string& bodyName, const SceneInputs& in) {
  const scene::Body* body = scene.find(bodyName);
  if (!body || !body->terrain) throw std::invalid_argument("body '" + bodyName + "' has no terrain");
  const SphereBody* sphere = nullptr;
  for (const SphereBody& b : in.bodies)
    if (b.name == bodyName) sphere = &b;
  if (!sphere) throw std::invalid_argument("body '" + bodyName + "' is not drawn (the Sun cannot carry a terrain)");
  TerrainPatch patch;
  patch.bodyCentreM = sphere->centreM;
  patch.albedoRgb = sphere->albedoRgb;
  patch.tangentToWorld = scene::bodyFixedToInertial(body->preset, scene.time) *
                         glm::transpose(terrain::bodyFixedToTangent(body->terrain->latDeg, body->terrain->lonDeg));
  return patch;
}

} // namespace

TerrainPatch sceneTerrainPatch(const scene::Scene& scene, const std::string& bodyName, const SceneInputs& in,
                               const DemLoader& loadDem) {
  TerrainPatch patch = placement(scene, bodyName, in);
  const scene::Body* body = scene.find(bodyName);
  const scene::Terrain& t = *body->terrain;
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
  return patch;
}

void placeSceneTerrains(const std::vector<std::unique_ptr<TerrainRendering>>& terrains, BodyView& view,
                        const scene::Scene& scene, const SceneInputs& in) {
  std::size_t k = 0;
  for (const scene::Body& b : scene.bodies) {
    if (!b.terrain) continue;
    if (k >= terrains.size()) throw std::invalid_argument("placeSceneTerrains: more terrains in the scene than given");
    const TerrainPatch p = placement(scene, b.name, in);
    TerrainRendering& t = *terrains[k++];
    t.SetPlacement(p.bodyCentreM, p.tangentToWorld);
    t.SetSun(in.sun);
    t.SetOrigin(view.GetCamera().positionM);
  }
  if (k != terrains.size()) throw std::invalid_argument("placeSceneTerrains: fewer terrains in the scene than given");
}

std::vector<std::unique_ptr<TerrainRendering>> addSceneTerrains(BodyView& view, const scene::Scene& scene,
                                                                const SceneInputs& in, const DemLoader& loadDem) {
  std::vector<std::unique_ptr<TerrainRendering>> out;
  for (const scene::Body& b : scene.bodies) {
    if (!b.terrain) continue;
    auto t = std::make_unique<TerrainRendering>();
    t->SetTerrain(sceneTerrainPatch(scene, b.name, in, loadDem));
    view.GetRenderer()->AddActor(t->GetActor());
    out.push_back(std::move(t));
  }
  placeSceneTerrains(out, view, scene, in);  // the Sun, the origin
  return out;
}

} // namespace umbra::pipeline
