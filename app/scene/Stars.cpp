#include "scene/Stars.hpp"

#include "scene/Ephemeris.hpp"
#include "scene/Units.hpp"

#include <erfa.h>

#include <cmath>
#include <stdexcept>

namespace umbra::scene {
namespace {

constexpr double kMasRad = 3.14159265358979323846 / 180.0 / 3600.0 / 1000.0;

}  // namespace

StarObserver observerOnEarth(const Body& earth, const Observer& observer, UtcTime time) {
  // The velocity from the turning frame, by a central difference over 1 s.
  const glm::dvec3 before = observerPositionM(earth, observer, addSeconds(time, -1.0));
  const glm::dvec3 after = observerPositionM(earth, observer, addSeconds(time, 1.0));
  return {observerPositionM(earth, observer, time) - earth.positionM, (after - before) / 2.0};
}

namespace {

/// The observer's star-independent astrometry parameters at `time`.
eraASTROM astrometryFor(UtcTime time, const StarObserver& observer) {
  double tt1 = 0.0, tt2 = 0.0;
  toTt(time, tt1, tt2);  // TDB differs from TT by < 2 ms: nothing here
  double pv[2][3];
  for (int i = 0; i < 3; ++i) {
    pv[0][i] = observer.geocentricPositionM[i];
    pv[1][i] = observer.geocentricVelocityMPerS[i];
  }
  eraASTROM astrom;
  eraApcs13(tt1, tt2, pv, &astrom);  // ICRS to GCRS: its bpn is the identity
  if (astrom.em * kAuM < 1000.0) throw std::invalid_argument("star places: the observer is at the Sun's centre");
  return astrom;
}

glm::dvec3 directionWith(const sky::CatalogueStar& star, eraASTROM& astrom) {
  // ERFA takes the proper motion in RA as dRA/dt, the catalogue gives it times cos(Dec).
  const double cosDec = std::cos(star.decRad);
  const double pmRa = cosDec > 1e-12 ? star.pmRaCosDecMasPerYear * kMasRad / cosDec : 0.0;
  double ra = 0.0, dec = 0.0;
  eraAtciq(star.raRad, star.decRad, pmRa, star.pmDecMasPerYear * kMasRad, star.parallaxMas / 1000.0, 0.0, &astrom, &ra,
           &dec);
  return {std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra), std::sin(dec)};
}

}  // namespace

glm::dvec3 apparentStarDirection(const sky::CatalogueStar& star, UtcTime time, const StarObserver& observer) {
  eraASTROM astrom = astrometryFor(time, observer);
  return directionWith(star, astrom);
}

std::vector<glm::dvec3> apparentStarDirections(const std::vector<sky::CatalogueStar>& stars, UtcTime time,
                                               const StarObserver& observer) {
  eraASTROM astrom = astrometryFor(time, observer);
  std::vector<glm::dvec3> out;
  out.reserve(stars.size());
  for (const sky::CatalogueStar& s : stars) out.push_back(directionWith(s, astrom));
  return out;
}

StarObserver starObserverOf(const Scene& scene) {
  const Body* earth = nullptr;
  for (const Body& b : scene.bodies)
    if (b.preset == "Earth") earth = &b;
  const Camera& c = scene.camera;
  if (earth && c.observer && c.observer->body == earth->name) return observerOnEarth(*earth, *c.observer, scene.time);
  const glm::dvec3 earthM = earth ? earth->positionM : heliocentricPositionM("Earth", scene.time);
  return {c.positionM - earthM, glm::dvec3(0.0)};
}

}  // namespace umbra::scene
