#pragma once
// Scenes: the bodies, the camera and the render settings of a JSON scene file
// (format: docs/scene-format.md), with positions resolved at the scene time.
#include "scene/Time.hpp"

#include "Clouds.hpp"
#include "AtmosphereModel.hpp"
#include "Photometry.hpp"
#include "ShadowLut.hpp"  // Occluder, Oblateness

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace umbra::scene {

/// A scene file problem: "<file>: <field path>: <what was expected>".
class SceneError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A terrain patch on a body (`umbra render` draws it with soft horizon shadows): a
/// height field on a gnomonic grid centred on (latDeg, lonDeg), from a DEM file or a
/// synthetic crater field.
struct Terrain {
  std::string demPath;      ///< absolute path of a GeoTIFF DEM; "" for a synthetic field
  std::uint64_t seed = 1;   ///< synthetic crater field
  int size = 512;           ///< synthetic: samples a side
  double spacingM = 30.0;   ///< synthetic; a DEM without a geotransform
  double latDeg = 0.0;      ///< the grid's centre, planetocentric
  double lonDeg = 0.0;
};

struct Body {
  std::string name;              ///< unique in the scene
  std::string preset;            ///< canonical preset name ("Moon"), or "" for none
  double radiusM = 0.0;          ///< mean radius
  double equatorialRadiusM = 0.0;
  double polarRadiusM = 0.0;
  glm::dvec3 positionM{0.0};     ///< heliocentric, ICRS axes
  /// Heliocentric, m/s, from the ephemeris (heliocentricVelocityMps); zero for a body at a
  /// given position. It places the body a light time back where it is seen or casts a
  /// shadow (eclipse::occluderSeenBy).
  glm::dvec3 velocityMps{0.0};
  bool positionFromEphemeris = false;
  bool hasAtmosphere = false;
  /// The atmosphere `umbra render` draws, read once with the scene: a preset ("earth") or
  /// a file (its name() the absolute path); null for none. Set only when the scene asks
  /// for it (`"atmosphere": true`, a preset name or a file), never by a preset's default.
  atmosphere::AtmosphereModelPtr atmosphere;
  double albedo = 0.0;           ///< geometric albedo
  glm::dvec3 color{1.0};         ///< relative reflectance at 680, 550, 440 nm, in [0, 1]
  sky::Photometry photometry;    ///< Lambert's or Hapke's law (the preset's; "photometry")
  /// An equirectangular albedo map (sky/AlbedoMap.hpp): an absolute path, "" for a uniform
  /// albedo. The Moon's preset takes the Clementine mosaic when it is installed.
  std::string albedoMapPath;
  /// The albedo map's sRGB colour is the surface's reflectance ("bluemarble"), taken as it
  /// is: the body's albedo and colour do not scale it.
  bool albedoMapReflectance = false;
  /// An equirectangular normal map of the relief (sky/NormalMap.hpp): an absolute path, ""
  /// for the sphere's normals. The Moon's preset takes stellarium-data's when installed.
  std::string normalMapPath;
  /// How much of the normal map's slopes the shading takes: 0 the sphere, 1 as the map has them.
  double reliefStrength = 1.0;
  std::optional<Terrain> terrain;
  /// Cloud layers over its atmosphere ("clouds"; at most sky::kMaxCloudLayers), drawn with
  /// it; their wind moves them from the scene file's time (Scene::fileTime).
  std::vector<sky::CloudLayer> clouds;

  bool isSun() const { return preset == "Sun"; }
};

/// A point on a body's reference ellipsoid: geodetic latitude, east longitude and
/// height above the ellipsoid.
struct Observer {
  std::string body;
  double latDeg = 0.0;
  double lonDeg = 0.0;
  double altM = 0.0;
};

/// A direction in an observer's horizon: azimuth from north through east, elevation above
/// the horizontal plane of the ellipsoid (geodetic), degrees.
struct HorizontalDirection {
  double azimuthDeg = 0.0;
  double elevationDeg = 0.0;
};

/// The unit vector (ICRS axes) of `direction` for `observer` on `body` at `time`.
glm::dvec3 horizontalDirection(const Body& body, const Observer& observer, const HorizontalDirection& direction,
                               UtcTime time);

struct Camera {
  std::optional<Observer> observer; ///< when set, positionM follows the body's rotation
  glm::dvec3 positionM{0.0};        ///< heliocentric, ICRS axes
  /// The file's target as an azimuth and elevation (with an observer): targetM follows it.
  std::optional<HorizontalDirection> targetDirection;
  std::string targetBody;           ///< "" when the target is a fixed point
  glm::dvec3 targetM{0.0};          ///< heliocentric, ICRS axes
  glm::dvec3 up{0.0, 0.0, 1.0};     ///< unit, orthogonal to the view direction
  std::optional<glm::dvec3> requestedUp; ///< the file's "up"; empty: the default
  bool upIsZenith = false;          ///< the file's "up": "zenith" (the observer's vertical)
  double fovDeg = 45.0;             ///< vertical field of view
};

/// The stars a scene draws behind everything ("stars": docs/scene-format.md).
struct StarSky {
  std::string cataloguePath;        ///< a catalogue in KStars' stars.dat format (absolute)
  double limitingMagnitude = 6.5;   ///< the faintest V drawn
  /// Scintillation seen through an atmosphere: the log's spread at the zenith
  /// (sky::scintillationFactor; 0: none), and the seed of its draws (each frame's time is
  /// mixed in, so that an animation twinkles).
  double scintillation = 0.0;
  std::uint64_t seed = 1;
  /// The Milky Way drawn behind the stars (sky/MilkyWay.hpp): a panorama's absolute path,
  /// "" for none. stellarium-data's by default, when installed.
  std::string milkyWayPath;
};

struct Scene {
  std::string path;     ///< the file it came from (for messages)
  std::string name;
  UtcTime time;
  bool hasTime = false; ///< false: the file gave no time (no ephemeris was needed)
  UtcTime fileTime;     ///< the file's time (setTime leaves it): where the clouds' drift starts
  std::vector<Body> bodies;
  Camera camera;
  double exposureEv = 0.0;
  int width = 960;
  int height = 720;
  int shadowLutSize = 256;
  std::optional<StarSky> stars;  ///< none: no stars
  /// What the user should know but that is no error (a preset's albedo map not installed:
  /// a uniform albedo instead), one line each, for stderr or a status line.
  std::vector<std::string> notes;

  /// The body with preset Sun (a valid scene has exactly one).
  const Body& sun() const;
  /// The body with this exact name, or nullptr.
  const Body* find(const std::string& name) const;
};

/// Reads, validates and resolves a scene file. Throws SceneError.
Scene loadScene(const std::string& path);

/// Validates and resolves scene JSON text; messages name pathForMessages.
/// Throws SceneError.
Scene parseScene(const std::string& jsonText, const std::string& pathForMessages);

/// Moves the scene to another time: recomputes the ephemeris positions, the observer
/// camera, a body target and the default up direction. Throws SceneError.
void setTime(Scene& scene, UtcTime time);

/// Heliocentric position (metres, ICRS axes) of an observer on a scene body.
glm::dvec3 observerPositionM(const Body& body, const Observer& observer, UtcTime time);

/// The body of preset `name` (its radii, albedo, photometry) where it is at `time`
/// (heliocentricPositionM). Throws std::invalid_argument for a preset without an ephemeris.
Body presetBody(const std::string& name, UtcTime time);

/// The Sun's centre above the geodetic horizon of the camera's observer, degrees (geometric:
/// no refraction; negative below it); nothing without an observer.
std::optional<double> sunElevationDeg(const Scene& scene);
/// The figure a body's shadow is cast by: the spheroid of its equatorial and polar radii
/// about its pole (eclipse::Oblateness; the Earth's flattening 1/298.257) when the scene
/// has a time and the body a rotation model (hasRotationModel), else its sphere. The body
/// is drawn as the sphere of its mean radius.
eclipse::Oblateness shadowFigure(const Scene& scene, const Body& body);
/// The body as an occluder where it is at the scene's time: its position, mean radius,
/// shadowFigure and velocity (light delay 0; eclipse::occluderSeenBy moves it).
eclipse::Occluder occluderOf(const Scene& scene, const Body& body);
/// The share of the Sun's light (Eq. 1's limb-darkened disc, eclipse::eclipseFactor
/// computed exactly) that reaches the camera past the scene's bodies in front of the Sun
/// (the least over them: exact for one occluder), the camera's own body left out; nothing
/// when no body covers any of the Sun. The GUI's status line shows it.
std::optional<double> sunVisibleFractionAtCamera(const Scene& scene);
/// "Sun 37.2 % visible" (one decimal), or "Sun hidden" at 0.
std::string describeSunVisible(double fraction);

/// Whether the camera's observer has the Sun's centre below the geometric horizon: a night
/// scene, which `umbra render` shows as the eye sees it in a PNG (night vision and glare).
/// False without an observer.
bool nightAtCamera(const Scene& scene);
/// "Sun 10.7 deg below the horizon" (one decimal; "above" from 0 up), as the CLI and the
/// GUI show sunElevationDeg.
std::string describeSunElevation(double elevationDeg);

} // namespace umbra::scene
