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

/// The patch of a scene body's terrain: the height field (synthetic crater field or DEM),
/// the body's centre and rotation at the scene time, the albedo of the body's sphere in
/// `in`. Throws std::invalid_argument naming the body.
TerrainPatch sceneTerrainPatch(const scene::Scene& scene, const std::string& bodyName, const SceneInputs& in,
                               const DemLoader& loadDem);

/// Every terrain of the scene, added to the view's renderer (call after view.SetCamera:
/// the origin is the camera position).
std::vector<std::unique_ptr<TerrainRendering>> addSceneTerrains(BodyView& view, const scene::Scene& scene,
                                                                const SceneInputs& in, const DemLoader& loadDem);

/// The terrains of addSceneTerrains moved to the scene's present time (another frame of
/// an animation: the scene and `in` at the new time, the view's camera set): each body's
/// centre and rotation, the Sun, the camera origin. The meshes, mipmaps and textures are
/// kept (the height fields do not change with time).
void placeSceneTerrains(const std::vector<std::unique_ptr<TerrainRendering>>& terrains, BodyView& view,
                        const scene::Scene& scene, const SceneInputs& in);

} // namespace umbra::pipeline
