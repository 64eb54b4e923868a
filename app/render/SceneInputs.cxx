#include "SceneInputs.h"

#include "ShadowLut.hpp"  // luminance()
#include "scene/Scene.hpp"

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
  in.camera.positionM = s.camera.positionM;
  in.camera.targetM = s.camera.targetM;
  in.camera.up = s.camera.up;
  in.camera.fovDeg = s.camera.fovDeg;
  return in;
}

} // namespace umbra::render
