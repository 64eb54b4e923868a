#pragma once
// The terrain patches of a scene (scene::Body::terrain) for `umbra render`: one
// TerrainRendering per body with a terrain, placed on the body at the scene time and lit
// by the scene's Sun, drawn in a BodyView next to the bodies' spheres.
#include "SceneInputs.h"
#include "TerrainRendering.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace umbra::pipeline {

using render::TerrainPatch;
using render::TerrainRendering;

/// Reads a DEM file (heights above the sphere of radius bodyRadiusM); throws with a
/// message naming the file. (The CLI's is GDAL's: app/cli/TerrainDem.)
using DemLoader = std::function<terrain::HeightField(const std::string& path, double spacingM, double bodyRadiusM)>;

/// How the terrains' shadows are found: from shadow tables (terrain/ShadowTable.hpp: made
/// for the Sun rounded to sunStepRad, then read from the table cache; a new one when the
/// Sun has moved a step) or, without, by the whole DP search per pixel (the reference).
struct TerrainShadowSettings {
  bool tables = true;
  double sunStepRad = terrain::kDefaultSunStepRad;
  double nearTexels = terrain::kDefaultNearTexels;
  std::string cacheDirectory;  ///< "": tables::TableCache::defaultDirectory()
  bool useCache = true;
};

/// The patch of a scene body's terrain: the height field (synthetic crater field or DEM),
/// the body's centre and rotation at the scene time, the albedo of the body's sphere in
/// `in`. Throws std::invalid_argument naming the body.
TerrainPatch sceneTerrainPatch(const scene::Scene& scene, const std::string& bodyName, const SceneInputs& in,
                               const DemLoader& loadDem);

/// Every terrain of the scene, added to the view's renderer (call after view.SetCamera:
/// the origin is the camera position).
std::vector<std::unique_ptr<TerrainRendering>> addSceneTerrains(BodyView& view, const scene::Scene& scene,
                                                                const SceneInputs& in, const DemLoader& loadDem,
                                                                const TerrainShadowSettings& shadows = {});

/// The terrains of addSceneTerrains moved to the scene's present time (another frame of
/// an animation: the scene and `in` at the new time, the view's camera set): each body's
/// centre and rotation, the Sun, the camera origin. The meshes, mipmaps and textures are
/// kept (the height fields do not change with time); a shadow table is made or read when
/// the Sun has moved out of the present one's step.
void placeSceneTerrains(const std::vector<std::unique_ptr<TerrainRendering>>& terrains, BodyView& view,
                        const scene::Scene& scene, const SceneInputs& in, const TerrainShadowSettings& shadows = {});

/// The terrain's shadow table for its present Sun (rounded as `shadows` says), from the
/// cache or made and stored, unless the one it holds already serves; or none, without
/// tables. Returns whether a table was read from the cache.
bool updateShadowTable(TerrainRendering& terrain, const TerrainShadowSettings& shadows);

} // namespace umbra::pipeline
