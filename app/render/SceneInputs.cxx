#include "SceneInputs.h"

#include "ShadowLut.hpp"  // luminance()
#include "scene/Scene.hpp"

#include <glm/geometric.hpp>

#include <algorithm>

namespace umbra::render {

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
  }
  // Bodies are spheres of their mean radius, but an observer stands on the ellipsoid:
  // near the poles that is below the mean radius, inside the sphere. Such a sphere is
  // shrunk to just below the observer, so that it still casts its shadow.
  for (SphereBody& b : in.bodies)
    b.radiusM = std::min(b.radiusM, glm::length(s.camera.positionM - b.centreM) * (1.0 - 1e-6));
  in.camera.positionM = s.camera.positionM;
  in.camera.targetM = s.camera.targetM;
  in.camera.up = s.camera.up;
  in.camera.fovDeg = s.camera.fovDeg;
  return in;
}

} // namespace umbra::render
