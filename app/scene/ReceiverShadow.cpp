#include "scene/ReceiverShadow.hpp"

#include "ShadowLut.hpp"  // occluderSeenBy
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
  // The receiver as the camera sees it, a light time back (as the renderer draws it).
  const eclipse::Occluder drawn = eclipse::seenFromCamera(occluderOf(scene, *receiver), scene.camera.positionM);
  const glm::dvec3 receiverM = drawn.centreM;
  const Body* occluder = nullptr;
  eclipse::Occluder seen;
  double bestV = std::numeric_limits<double>::infinity();
  for (const Body& body : scene.bodies) {
    if (&body == receiver || body.isSun()) continue;
    const eclipse::Occluder o = eclipse::occluderSeenBy(occluderOf(scene, body), receiverM, receiver->radiusM, drawn.lightDelayS);
    if (!eclipse::occluderInFront(receiverM, sun.positionM, o.centreM)) continue;
    // behind the body as seen from the Sun
    if (!(glm::dot(receiverM - o.centreM, o.centreM - sun.positionM) > 0.0)) continue;
    const auto angles = eclipse::shadowAngles(receiverM, sun.positionM, sun.radiusM, o.centreM, o.radiusM, o.figure);
    const double v = eclipse::lutCoords(angles).v;
    if (v < bestV) {
      bestV = v;
      occluder = &body;
      seen = o;
    }
  }
  r.receiver = receiver->name;
  r.receiverRadiusM = receiver->radiusM;
  if (!occluder) {
    r.why = "no body lies between the Sun and " + receiver->name + " to shadow it";
    return r;
  }
  r.occluder = occluder->name;
  r.occluderRadiusM = eclipse::outlineRadiusTowardsSunM(receiverM, sun.positionM, seen.centreM, seen.radiusM, seen.figure);
  r.sunRadiusM = sun.radiusM;
  const glm::dvec3 axis = seen.centreM - sun.positionM;
  r.sunOccluderDistanceM = glm::length(axis);
  const glm::dvec3 dir = axis / r.sunOccluderDistanceM;
  const glm::dvec3 rel = receiverM - seen.centreM;
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
