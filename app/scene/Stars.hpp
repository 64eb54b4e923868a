#pragma once
// Where a catalogue star is seen: its apparent direction from an observer, in the scene's
// ICRS-aligned axes, by ERFA: proper motion and parallax to the date, the Sun's light
// deflection, and the aberration of the observer's motion (annual and, on a turning
// body, diurnal). Refraction is the atmosphere's, not this.
#include "StarCatalogue.hpp"
#include "scene/Scene.hpp"
#include "scene/Time.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace umbra::scene {

/// An observer of star places: position [m] and velocity [m/s] relative to the Earth's
/// centre, in GCRS (the scene's axes).
struct StarObserver {
  glm::dvec3 geocentricPositionM{0.0};
  glm::dvec3 geocentricVelocityMPerS{0.0};
};

/// A scene observer on the Earth (observerPositionM: the body's ellipsoid, turning with
/// it), at `time`; its velocity is the Earth's rotation.
StarObserver observerOnEarth(const Body& earth, const Observer& observer, UtcTime time);

/// Unit vector towards the star as `observer` sees it at `time`, in GCRS axes. The
/// catalogue's places are taken as of J2000.0. Throws std::invalid_argument for an
/// observer within 1 km of the Sun's centre (no light deflection to compute).
glm::dvec3 apparentStarDirection(const sky::CatalogueStar& star, UtcTime time, const StarObserver& observer);

/// apparentStarDirection for every star of `stars`, the observer's astrometry computed once.
std::vector<glm::dvec3> apparentStarDirections(const std::vector<sky::CatalogueStar>& stars, UtcTime time,
                                               const StarObserver& observer);

/// The star observer of a scene: its camera. A camera standing on the Earth
/// (camera.observer) turns with it (observerOnEarth); any other camera keeps its position
/// relative to the Earth's centre (the scene's Earth, else the ephemeris's) and moves with
/// the Earth (no velocity of its own: the aberration of a spacecraft's few km/s relative to
/// the Earth, a few arcseconds, is left out).
StarObserver starObserverOf(const Scene& scene);

}  // namespace umbra::scene
