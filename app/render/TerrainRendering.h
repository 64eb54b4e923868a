#pragma once
// A terrain patch drawn with soft horizon shadows of the Sun (terrain paper, section 4).
//
// The height field (terrain::HeightField, a gnomonic grid on the body's sphere) becomes a
// pre-displaced triangle mesh, one vertex every MeshStep samples at (R + h) times the unit
// vector through the sample, lowered just enough to stay below the bilinear surface (a
// camera above the ground is then above the mesh, and every view ray that meets the
// ground meets the mesh first). Per fragment (glsl/TerrainFragment.glsl) the view ray through
// the rasterised mesh point is refined onto the bilinear height field, the visible
// fraction of the solar disc is found there, and the point is shaded Lambertian. The
// fraction: with a shadow table (SetShadowTable; terrain/ShadowTable.hpp), the GLSL twin of
// the DP search (terrain/glsl/TerrainShadow.glsl, heights and maximum mipmap as float
// textures) over the first texels of the footprint and the table's far horizon looked up;
// without one, that search over the whole footprint, per pixel (the reference path):
//
//   radiance = albedo / pi * E_sun * max(0, n . l) * visible fraction   [W m^-2 sr^-1]
//
// the units of the eclipse receivers (EclipseShading), for vtkUmbraRenderPass's HDR buffer.
// n is the bilinear surface's normal; l and E_sun are taken at the patch centre (the Sun
// is 1.5e11 m away: over a 100 km patch the direction changes by < 1e-6 rad).
//
// Coordinates: the mesh is in patch coordinates (tangent frame minus (0, 0, R), small
// numbers); the actor maps them to the world (rotation tangent -> world) and places them
// at (tangent point - origin), the camera-relative convention of EclipseShading, so VTK's
// float matrices stay exact from orbit and from 2 m above the ground.
#include "EclipseShading.h"
#include "HeightField.hpp"
#include "MaximumMipmap.hpp"
#include "ShadowTable.hpp"
#include "SoftShadow.hpp"

#include <glm/glm.hpp>

#include <memory>

class vtkActor;

namespace umbra::render {

struct TerrainPatch {
  terrain::HeightField field;
  glm::dvec3 bodyCentreM{0.0};   ///< world (inertial) frame
  glm::dmat3 tangentToWorld{1.0};  ///< columns: the tangent frame's x, y, z in world axes
  glm::dvec3 albedoRgb{0.12};
  int meshStep = 0;              ///< samples per mesh cell; 0: at most 1024 cells a side
};

class TerrainRendering {
public:
  enum class Output { Radiance, GridAndFraction };  ///< GridAndFraction: (gx, gy, fraction) for tests

  TerrainRendering();
  ~TerrainRendering();
  TerrainRendering(const TerrainRendering&) = delete;
  TerrainRendering& operator=(const TerrainRendering&) = delete;

  /// Builds the mesh, the mipmap and the textures. Throws std::invalid_argument (bad
  /// field, no tangent rotation, bad albedo).
  void SetTerrain(const TerrainPatch& patch);
  /// Moves the patch (the body's centre and the tangent-to-world rotation, e.g. at another
  /// time of an animation) without rebuilding the mesh, mipmap or textures. Throws
  /// std::invalid_argument as SetTerrain.
  void SetPlacement(const glm::dvec3& bodyCentreM, const glm::dmat3& tangentToWorld);
  /// The Sun (position in the world frame). Throws std::invalid_argument.
  void SetSun(const SunLight& sun);
  /// Camera-relative placement: the actor goes to (tangent point - origin). The origin
  /// must be the camera's position (as BodyView sets it) for perspective views: the view
  /// rays start there, in double precision.
  void SetOrigin(const glm::dvec3& originM);
  void SetOutput(Output output);
  /// The far horizon from a table made for this patch's height field and a Sun near the
  /// present one (the search near each pixel then takes the table's Sun too; the shading
  /// keeps the exact one); null: the whole search per pixel. Throws std::invalid_argument
  /// for a table of another size.
  void SetShadowTable(std::shared_ptr<const terrain::ShadowTable> table);
  const terrain::ShadowTable* GetShadowTable() const;

  /// The actor to add to a renderer (valid after SetTerrain).
  vtkActor* GetActor() const;
  const TerrainPatch& GetPatch() const;
  const terrain::MaximumMipmap& GetMipmap() const;
  /// The Sun at the patch (tangent frame, angular radius); with a table, the search takes
  /// the table's.
  terrain::SunDisc GetSunDisc() const;
  /// The Sun's irradiance at the patch [W m^-2].
  double GetSunIrradiance() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

} // namespace umbra::render
