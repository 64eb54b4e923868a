#pragma once
// What the renderer needs from a scene: the Sun as the light, the other bodies as
// spheres (each a receiver, shadowed by the rest), and the camera.
#include "BodyView.h"
#include "EclipseShading.h"

#include <optional>
#include <string>
#include <vector>

class vtkAtmosphereTablesSource;

namespace umbra::scene { struct Scene; }

namespace umbra::render {

/// The atmosphere a scene asks to draw (scene::Body::atmosphereModel).
struct SceneAtmosphere {
  std::string body;   ///< the body it surrounds (its SphereBody has the same name)
  std::string model;  ///< preset name or file (vtkAtmosphereTablesSource::SetAtmosphere)
  /// The model's ground and top radii (sceneInputs sets them; 0: not known, the body's
  /// sphere and the model are read where needed). The eclipse tables are made for the
  /// ground radius, not for the body's sphere, which an observer on it may shrink.
  double bottomRadiusM = 0.0, topRadiusM = 0.0;
};

struct SceneInputs {
  SunLight sun;
  std::vector<SphereBody> bodies;
  ViewCamera camera;
  std::optional<SceneAtmosphere> atmosphere;
};

/// The scene at its current time. A body's Lambertian albedo is 3/2 of its geometric
/// albedo (exact for a Lambertian sphere), tinted by its display colour at equal luminance.
/// A body whose sphere would enclose the camera (an observer near a pole, below the mean
/// radius) is shrunk to just below the camera.
///
/// A body with an atmosphere to draw (at most one per scene so far; std::invalid_argument
/// otherwise) is a sphere of the atmosphere's bottom radius (the ground of its tables),
/// and an observer standing on it is placed at that radius plus its altitude (at least
/// 1 m), in the same direction from the centre; the target moves with it.
SceneInputs sceneInputs(const scene::Scene& scene);

/// Hands the tables of in.atmosphere to view.GetAtmosphere() (call after SetBodies): they
/// come from `source` (its cache, sizes and orders as the caller set them; this sets the
/// atmosphere, 3 wavelengths and the Bruneton tables only). Without an atmosphere, clears
/// the view's. With `refraction`, the source also makes the refraction table and
/// integrates along refracted paths, and the view bends its rays
/// (AtmosphereRendering::SetRefraction). Throws std::runtime_error naming the body when the
/// tables cannot be made.
void applySceneAtmosphere(BodyView& view, const SceneInputs& in, vtkAtmosphereTablesSource* source,
                          bool refraction = false);

/// Small atmosphere tables for quick looks and tests: 64x16 transmittance, 8,32,8,4
/// scattering, 16x4 irradiance, 3 orders (about a second to compute).
void useSmallAtmosphereTables(vtkAtmosphereTablesSource* source);

} // namespace umbra::render
