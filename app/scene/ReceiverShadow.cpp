#include "scene/ReceiverShadow.hpp"

#include "ShadowMapping.hpp"

#include <glm/geometric.hpp>

#include <limits>

namespace umbra::scene {

ReceiverShadow receiverShadow(const Scene& scene) {
  ReceiverShadow r;
  const Body* receiver = scene.camera.targetBody.empty() ? nullptr : scene.find(scene.camera.targetBody);
  if (!receiver || receiver->isSun()) {
    r.why = "the camera's target is not a body that can be shadowed";
    return r;
  }
  const Body& sun = scene.sun();
  const Body* occluder = nullptr;
  double bestV = std::numeric_limits<double>::infinity();
  for (const Body& body : scene.bodies) {
    if (&body == receiver || body.isSun()) continue;
    if (!eclipse::occluderInFront(receiver->positionM, sun.positionM, body.positionM)) continue;
    // behind the body as seen from the Sun
    if (!(glm::dot(receiver->positionM - body.positionM, body.positionM - sun.positionM) > 0.0)) continue;
    const auto angles = eclipse::shadowAngles(receiver->positionM, sun.positionM, sun.radiusM, body.positionM,
                                              body.radiusM);
    const double v = eclipse::lutCoords(angles).v;
    if (v < bestV) {
      bestV = v;
      occluder = &body;
    }
  }
  r.receiver = receiver->name;
  r.receiverRadiusM = receiver->radiusM;
  if (!occluder) {
    r.why = "no body lies between the Sun and " + receiver->name + " to shadow it";
    return r;
  }
  r.occluder = occluder->name;
  r.occluderRadiusM = occluder->radiusM;
  r.sunRadiusM = sun.radiusM;
  const glm::dvec3 axis = occluder->positionM - sun.positionM;
  r.sunOccluderDistanceM = glm::length(axis);
  const glm::dvec3 dir = axis / r.sunOccluderDistanceM;
  const glm::dvec3 rel = receiver->positionM - occluder->positionM;
  r.receiverDistanceM = glm::dot(rel, dir);
  r.offsetM = glm::length(rel - r.receiverDistanceM * dir);
  if (!(r.sunOccluderDistanceM > r.sunRadiusM)) {
    r.why = occluder->name + " is inside the Sun";
    return r;
  }
  const auto cones = eclipse::shadowConeRadii({r.sunRadiusM, r.occluderRadiusM, r.sunOccluderDistanceM},
                                              r.receiverDistanceM);
  r.umbraRadiusM = cones.umbraRadiusM;
  r.antumbraRadiusM = cones.antumbraRadiusM;
  r.penumbraRadiusM = cones.penumbraRadiusM;
  r.valid = true;
  return r;
}

} // namespace umbra::scene
