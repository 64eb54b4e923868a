#include "SceneTerrain.h"

#include "CraterField.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Scene.hpp"
#include "umbra/tables/CachedTables.h"

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

bool updateShadowTable(TerrainRendering& t, const TerrainShadowSettings& o) {
  if (!o.tables) {
    t.SetShadowTable(nullptr);
    return false;
  }
  const terrain::SunDisc sun = terrain::roundedSun(t.GetSunDisc(), o.sunStepRad);
  if (const terrain::ShadowTable* held = t.GetShadowTable())
    if (held->sun.direction == sun.direction && held->sun.angularRadiusRad == sun.angularRadiusRad &&
        held->sun.limbDarkening == sun.limbDarkening && held->nearTexels == o.nearTexels)
      return false;
  const terrain::HeightField& f = t.GetPatch().field;
  const terrain::ShadowOptions search;
  tables::TableRequest request;
  request.kind = "terrain-shadow";
  request.parameters = terrain::shadowTableKey(f, sun, o.sunStepRad, search, o.nearTexels);
  request.width = f.width;
  request.height = f.height;
  request.channels = {"d"};
  const tables::TableCache cache(o.cacheDirectory.empty() ? tables::TableCache::defaultDirectory() : o.cacheDirectory);
  tables::CacheOutcome outcome;
  std::vector<tables::Table> made = tables::cachedOrComputed(
      cache, o.useCache, {request},
      [&] {
        const terrain::ShadowTable table = terrain::makeShadowTable(f, t.GetMipmap(), sun, search, o.nearTexels);
        tables::Table out;
        out.width = table.width;
        out.height = table.height;
        out.channels = {"d"};
        out.data = table.offsets;
        return std::vector<tables::Table>{std::move(out)};
      },
      outcome);
  auto table = std::make_shared<terrain::ShadowTable>();
  table->width = f.width;
  table->height = f.height;
  table->offsets = std::move(made.front().data);
  table->sun = sun;
  table->nearTexels = o.nearTexels;
  t.SetShadowTable(std::move(table));
  return outcome.hits > 0;
}

void placeSceneTerrains(const std::vector<std::unique_ptr<TerrainRendering>>& terrains, BodyView& view,
                        const scene::Scene& scene, const SceneInputs& in, const TerrainShadowSettings& shadows) {
  std::size_t k = 0;
  for (const scene::Body& b : scene.bodies) {
    if (!b.terrain) continue;
    if (k >= terrains.size()) throw std::invalid_argument("placeSceneTerrains: more terrains in the scene than given");
    const TerrainPatch p = placement(scene, b.name, in);
    TerrainRendering& t = *terrains[k++];
    t.SetPlacement(p.bodyCentreM, p.tangentToWorld);
    t.SetSun(in.sun);
    t.SetOrigin(view.GetCamera().positionM);
    updateShadowTable(t, shadows);
  }
  if (k != terrains.size()) throw std::invalid_argument("placeSceneTerrains: fewer terrains in the scene than given");
}

std::vector<std::unique_ptr<TerrainRendering>> addSceneTerrains(BodyView& view, const scene::Scene& scene,
                                                                const SceneInputs& in, const DemLoader& loadDem,
                                                                const TerrainShadowSettings& shadows) {
  std::vector<std::unique_ptr<TerrainRendering>> out;
  for (const scene::Body& b : scene.bodies) {
    if (!b.terrain) continue;
    auto t = std::make_unique<TerrainRendering>();
    t->SetTerrain(sceneTerrainPatch(scene, b.name, in, loadDem));
    view.GetRenderer()->AddActor(t->GetActor());
    out.push_back(std::move(t));
  }
  placeSceneTerrains(out, view, scene, in, shadows);  // the Sun, the origin, the shadow tables
  return out;
}

} // namespace umbra::pipeline
