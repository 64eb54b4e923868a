#pragma once
// Where the camera's target lies in the shadow of another body: the GUI's plot panel and
// `umbra profile shadow --scene` show the cross-section of that body's shadow at the
// target's distance. Plain C++ (no Qt, no VTK).
#include "scene/Scene.hpp"

#include <string>

namespace umbra::scene {

struct ReceiverShadow {
  /// A receiver (the camera's target body) and an occluder (a body between it and the
  /// Sun) were found; otherwise `why` says what is missing.
  bool valid = false;
  std::string why;

  std::string receiver;          ///< the camera's target body
  std::string occluder;          ///< the body whose shadow is closest to the receiver's centre
  double receiverRadiusM = 0.0;
  /// The radius of the occluder's outline towards the Sun seen from the receiver's centre
  /// (eclipse::outlineRadiusTowardsSunM: the circle the scenes' shading takes for an
  /// oblate occluder, whose shadow's cross-section is an ellipse); its mean radius for a sphere.
  double occluderRadiusM = 0.0;
  double sunRadiusM = 0.0;
  double sunOccluderDistanceM = 0.0;
  /// Distance of the receiver's centre behind the occluder's centre, along the axis from
  /// the Sun through the occluder (positive behind it).
  double receiverDistanceM = 0.0;
  /// Distance of the receiver's centre from that axis.
  double offsetM = 0.0;
  /// Geometric umbra, antumbra (one of the two is 0) and penumbra radii at receiverDistanceM.
  double umbraRadiusM = 0.0;
  double antumbraRadiusM = 0.0;
  double penumbraRadiusM = 0.0;
};

/// The receiver is the camera's target body (not the Sun). The occluder is, among the
/// other bodies lying between the Sun and the receiver, the one whose shadow axis passes
/// closest to the receiver's centre in units of the penumbra (smallest v of Eq. 4).
/// Both are placed as the renderer places them: the receiver where the camera sees it, a
/// light time back, and the occluder where the light that reaches the receiver passed it
/// (eclipse::occluderSeenBy), with its figure (scene::shadowFigure).
ReceiverShadow receiverShadow(const scene::Scene& scene);

} // namespace umbra::scene
