#pragma once
// The naked-eye planets seen from a place in the solar system: where they stand (ERFA's
// eraPlan94, one light time back) and how bright they are (sky/PlanetMagnitudes.hpp, Mallama
// & Hilton 2018's phase curves; Mars with its rotation and season corrections, Saturn with
// its rings' tilt). Scenes with stars draw them as stars (app/pipeline/SceneInputs), in
// their colours (planetColourBMinusV).
#include "scene/Time.hpp"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace umbra::scene {

struct PlanetSeen {
  std::string name;
  glm::dvec3 directionIcrs{0.0, 0.0, 1.0};  ///< unit, from the observer (astrometric: no aberration)
  double distanceAu = 0.0;                  ///< from the observer, at the light's departure
  double sunDistanceAu = 0.0;               ///< from the Sun, then
  double phaseAngleDeg = 0.0;               ///< Sun - planet - observer
  double magnitudeV = 0.0;
  /// Saturn: the observer's saturnicentric latitude over the ring plane (the rings' tilt as
  /// almanacs give it, B; north positive) [deg]; 0 for the others.
  double ringTiltDeg = 0.0;
};

/// The planets whose phase curves umbra has: Mercury, Venus, Mars, Jupiter, Saturn.
const std::vector<std::string>& planetsWithMagnitudes();

/// Each of planetsWithMagnitudes() seen from `observerM` (heliocentric, ICRS axes, m) at
/// `time`: its place one light time before (iterated twice: below 1 ms), its distances and
/// phase angle, and its V magnitude; a planet within kNearPlanetM of the observer is left
/// out (a body of the scene there, not a point of light: an observer on Mars). Throws
/// std::invalid_argument for a non-finite position.
inline constexpr double kNearPlanetM = 1.0e9;
std::vector<PlanetSeen> planetsSeenFrom(const glm::dvec3& observerM, UtcTime time);

}  // namespace umbra::scene
