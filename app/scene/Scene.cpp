#include "scene/Scene.hpp"

#include "SceneDetail.hpp"
#include "JsonErrors.hpp"  // readJsonFileText
#include "scene/Bodies.hpp"
#include "scene/Ephemeris.hpp"

#include "ShadowLut.hpp"

#include <GeographicLib/Geocentric.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace umbra::scene {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
} // namespace

namespace detail {

void fail(const std::string& file, const std::string& field, const std::string& message) {
  throw SceneError(field.empty() ? file + ": " + message
                                 : file + ": " + field + ": " + message);
}

namespace {

/// True when a and b (non-zero) are within about 0.06 deg of parallel.
bool nearlyParallel(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 1e-3;
}

const Body& findBody(const Scene& scene, const std::string& name, const std::string& field) {
  const Body* body = scene.find(name);
  if (body == nullptr) fail(scene.path, field, "unknown body '" + name + "'");
  return *body;
}

/// The camera's up: the file's (a vector, or "zenith": away from the observer body's
/// centre), else the observer body's north pole, else ICRS +z;
/// when that is parallel to the view direction, the first ICRS axis that is not.
/// Returned orthogonal to the view direction and normalized.
glm::dvec3 chooseUp(const Scene& scene, const glm::dvec3& viewDir) {
  glm::dvec3 up(0.0, 0.0, 1.0);
  if (scene.camera.requestedUp) {
    up = *scene.camera.requestedUp;
  } else if (scene.camera.upIsZenith && scene.camera.observer) {
    const Body& body = findBody(scene, scene.camera.observer->body, "camera.observer.body");
    up = scene.camera.positionM - body.positionM;
  } else if (scene.camera.observer) {
    const Body& body = findBody(scene, scene.camera.observer->body, "camera.observer.body");
    up = bodyFixedToInertial(body.preset, scene.time) * glm::dvec3(0.0, 0.0, 1.0);
  }
  const glm::dvec3 fallbacks[] = {up, {0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  for (const glm::dvec3& candidate : fallbacks) {
    if (nearlyParallel(candidate, viewDir)) continue;
    const glm::dvec3 dir = glm::normalize(viewDir);
    return glm::normalize(candidate - glm::dot(candidate, dir) * dir);
  }
  return {0.0, 0.0, 1.0}; // unreachable: three axes cannot all be parallel to dir
}

} // namespace

void resolve(Scene& scene) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    Body& body = scene.bodies[i];
    if (!body.positionFromEphemeris) continue;
    try {
      body.positionM = heliocentricPositionM(body.preset, scene.time);
      body.velocityMps = heliocentricVelocityMps(body.preset, scene.time);
    } catch (const std::invalid_argument& e) {
      fail(scene.path, "bodies[" + std::to_string(i) + "].position", e.what());
    }
  }

  Camera& camera = scene.camera;
  if (camera.observer) {
    const Body& body = findBody(scene, camera.observer->body, "camera.observer.body");
    try {
      camera.positionM = observerPositionM(body, *camera.observer, scene.time);
    } catch (const std::exception& e) {
      fail(scene.path, "camera.observer.body", e.what());
    }
  }
  if (!camera.targetBody.empty())
    camera.targetM = findBody(scene, camera.targetBody, "camera.target").positionM;
  if (camera.targetDirection && camera.observer) {
    const Body& body = findBody(scene, camera.observer->body, "camera.observer.body");
    // 1000 km ahead: the direction exact to ~1e-10 rad at heliocentric magnitudes.
    camera.targetM = camera.positionM + 1e6 * horizontalDirection(body, *camera.observer, *camera.targetDirection,
                                                                  scene.time);
  }

  const glm::dvec3 viewDir = camera.targetM - camera.positionM;
  if (!(glm::length(viewDir) > 0.0))
    fail(scene.path, "camera.target", "the target is at the camera position");
  camera.up = chooseUp(scene, viewDir);
}

} // namespace detail

const Body& Scene::sun() const {
  for (const Body& body : bodies)
    if (body.isSun()) return body;
  throw SceneError(path + ": bodies: no Sun");
}

const Body* Scene::find(const std::string& bodyName) const {
  for (const Body& body : bodies)
    if (body.name == bodyName) return &body;
  return nullptr;
}

Body presetBody(const std::string& name, UtcTime time) {
  const BodyPreset* preset = findPreset(name);
  if (!preset) throw std::invalid_argument("no body preset '" + name + "'");
  const BodyPreset& p = *preset;
  Body b;
  b.name = b.preset = p.name;
  b.radiusM = p.meanRadiusM;
  b.equatorialRadiusM = p.equatorialRadiusM;
  b.polarRadiusM = p.polarRadiusM;
  b.albedo = p.geometricAlbedo;
  b.photometry = p.photometry;
  b.positionM = heliocentricPositionM(name, time);
  b.velocityMps = heliocentricVelocityMps(name, time);
  return b;
}

glm::dvec3 observerPositionM(const Body& body, const Observer& observer, UtcTime time) {
  const double flattening =
      (body.equatorialRadiusM - body.polarRadiusM) / body.equatorialRadiusM;
  const GeographicLib::Geocentric ellipsoid(body.equatorialRadiusM, flattening);
  glm::dvec3 local;
  ellipsoid.Forward(observer.latDeg, observer.lonDeg, observer.altM, local.x, local.y,
                    local.z);
  return body.positionM + bodyFixedToInertial(body.preset, time) * local;
}

glm::dvec3 horizontalDirection(const Body& body, const Observer& observer, const HorizontalDirection& direction,
                               UtcTime time) {
  const double lat = observer.latDeg * kDeg, lon = observer.lonDeg * kDeg;
  const double az = direction.azimuthDeg * kDeg, el = direction.elevationDeg * kDeg;
  // East, north and up of the geodetic horizon, body-fixed.
  const glm::dvec3 east(-std::sin(lon), std::cos(lon), 0.0);
  const glm::dvec3 north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  const glm::dvec3 up(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  const glm::dvec3 local = std::cos(el) * (std::sin(az) * east + std::cos(az) * north) + std::sin(el) * up;
  return bodyFixedToInertial(body.preset, time) * local;
}

std::optional<double> sunElevationDeg(const Scene& scene) {
  if (!scene.camera.observer) return std::nullopt;
  const Body* body = scene.find(scene.camera.observer->body);
  if (!body) return std::nullopt;
  const glm::dvec3 up = horizontalDirection(*body, *scene.camera.observer, {0.0, 90.0}, scene.time);
  const glm::dvec3 toSun = glm::normalize(scene.sun().positionM - scene.camera.positionM);
  return std::asin(std::clamp(glm::dot(up, toSun), -1.0, 1.0)) / kDeg;
}

eclipse::Oblateness shadowFigure(const Scene& scene, const Body& b) {
  if (!scene.hasTime || b.preset.empty() || !hasRotationModel(b.preset) || !(b.equatorialRadiusM > b.polarRadiusM))
    return {};
  return {bodyFixedToInertial(b.preset, scene.time)[2], (b.equatorialRadiusM - b.polarRadiusM) / b.equatorialRadiusM};
}

eclipse::Occluder occluderOf(const Scene& scene, const Body& b) {
  return {b.positionM, b.radiusM, shadowFigure(scene, b), b.velocityMps};
}

std::optional<double> sunVisibleFractionAtCamera(const Scene& scene) {
  const Body& sun = scene.sun();
  const std::string own = scene.camera.observer ? scene.camera.observer->body : std::string();
  double least = 1.0;
  for (const Body& b : scene.bodies) {
    if (b.isSun() || b.name == own) continue;
    const glm::dvec3 f =
        eclipse::eclipseFactor(scene.camera.positionM, sun.positionM, sun.radiusM,
                               eclipse::occluderSeenBy(occluderOf(scene, b), scene.camera.positionM, 0.0, 0.0), nullptr);
    least = std::min(least, f.g);
  }
  if (!(least < 1.0)) return std::nullopt;
  return least;
}

std::string describeSunVisible(double fraction) {
  if (!(fraction > 0.0)) return "Sun hidden";
  char text[48];
  std::snprintf(text, sizeof text, "Sun %.1f %% visible", 100.0 * fraction);
  return text;
}

bool nightAtCamera(const Scene& scene) {
  const std::optional<double> e = sunElevationDeg(scene);
  return e && *e < 0.0;
}

std::string describeSunElevation(double elevationDeg) {
  char text[64];
  std::snprintf(text, sizeof text, "Sun %.1f deg %s the horizon", std::abs(elevationDeg),
                elevationDeg < 0.0 ? "below" : "above");
  return text;
}

void setTime(Scene& scene, UtcTime time) {
  scene.time = time;
  scene.hasTime = true;
  detail::resolve(scene);
}

Scene loadScene(const std::string& path) {
  atmosphere::FileText f = atmosphere::readJsonFileText(path);
  if (!f.error.empty()) throw SceneError(f.error);
  return parseScene(f.text, path);
}

} // namespace umbra::scene
