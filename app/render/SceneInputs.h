#pragma once
// What the renderer needs from a scene: the Sun as the light, the other bodies as
// spheres (each a receiver, shadowed by the rest), and the camera.
#include "BodyView.h"
#include "EclipseShading.h"

#include <vector>

namespace umbra::scene { struct Scene; }

namespace umbra::render {

struct SceneInputs {
  SunLight sun;
  std::vector<SphereBody> bodies;
  ViewCamera camera;
};

/// The scene at its current time. A body's Lambertian albedo is 3/2 of its geometric
/// albedo (exact for a Lambertian sphere), tinted by its display colour at equal luminance.
/// A body whose sphere would enclose the camera (an observer near a pole, below the mean
/// radius) is shrunk to just below the camera.
SceneInputs sceneInputs(const scene::Scene& scene);

} // namespace umbra::render
