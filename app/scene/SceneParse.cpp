// parseScene: JSON text -> validated Scene (format: docs/scene-format.md).
#include "Atmosphere.hpp"
#include "JsonErrors.hpp"
#include "Spectrum.hpp"
#include "StarCatalogue.hpp"
#include "scene/Scene.hpp"
#include "scene/Eclipses.hpp"

#include "SceneDetail.hpp"
#include "scene/Bodies.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Units.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>

namespace umbra::scene {

namespace {

using json = nlohmann::json;

/// "got <value>" text for messages, shortened.
std::string got(const json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return "got " + text;
}

std::string index(const std::string& field, std::size_t i) {
  return field + "[" + std::to_string(i) + "]";
}

/// Reads typed values out of the JSON tree; every failure names the file and field.
class Reader {
public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    detail::fail(file_, field, message);
  }

  void object(const json& value, const std::string& field,
              std::initializer_list<const char*> keys) const {
    if (!value.is_object()) fail(field, "expected an object, " + got(value));
    if (const auto unknown = atmosphere::firstUnknownKey(value, keys))
      fail(field.empty() ? unknown->key : field + "." + unknown->key, unknown->message);
  }

  std::string string(const json& value, const std::string& field) const {
    if (!value.is_string() || value.get<std::string>().empty())
      fail(field, "expected a non-empty string, " + got(value));
    return value.get<std::string>();
  }

  bool boolean(const json& value, const std::string& field) const {
    if (!value.is_boolean()) fail(field, "expected true or false, " + got(value));
    return value.get<bool>();
  }

  /// A finite number in [lo, hi] (open at the ends that say so).
  double number(const json& value, const std::string& field, double lo, double hi,
                const std::string& expected) const {
    if (!value.is_number()) fail(field, "expected " + expected + ", " + got(value));
    const double x = value.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
      fail(field, "expected " + expected + ", " + got(value));
    return x;
  }

  int integer(const json& value, const std::string& field, int lo, int hi) const {
    const std::string expected =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    const double x = number(value, field, lo, hi, expected);
    if (x != std::floor(x)) fail(field, "expected " + expected + ", " + got(value));
    return static_cast<int>(x);
  }

  /// A number (metres) or a length string such as "10km".
  double length(const json& value, const std::string& field, const std::string& expected) const {
    double metres = 0.0;
    if (value.is_number()) {
      metres = value.get<double>();
    } else if (value.is_string()) {
      try {
        metres = parseLengthM(value.get<std::string>());
      } catch (const std::invalid_argument& e) {
        fail(field, e.what());
      }
    } else {
      fail(field, "expected " + expected + ", " + got(value));
    }
    if (!std::isfinite(metres)) fail(field, "expected " + expected + ", " + got(value));
    return metres;
  }

  /// A radius: a length from 1 m to 1e12 m; a grid spacing: from 1 mm.
  double positiveLength(const json& value, const std::string& field, double minM = kMinRadiusM,
                        const char* range = "a length from 1 m to 1e12 m") const {
    const double metres = length(value, field, range);
    if (!(metres >= minM && metres <= kMaxRadiusM)) fail(field, std::string("expected ") + range + ", " + got(value));
    return metres;
  }

  /// [x, y, z]: numbers in metres or length strings.
  glm::dvec3 vector(const json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 3)
      fail(field, "expected [x, y, z] in metres, " + got(value));
    glm::dvec3 v;
    for (std::size_t i = 0; i < 3; ++i) {
      v[static_cast<int>(i)] = length(value[i], index(field, i), "a length in metres");
      if (std::abs(v[static_cast<int>(i)]) > kMaxDistanceM)
        fail(index(field, i), "expected a length within 1e15 m of the Sun, " + got(value[i]));
    }
    return v;
  }

  glm::dvec3 color(const json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 3)
      fail(field, "expected [r, g, b] with components in [0, 1], " + got(value));
    glm::dvec3 rgb;
    for (std::size_t i = 0; i < 3; ++i)
      rgb[static_cast<int>(i)] = number(value[i], index(field, i), 0.0, 1.0, "a number in [0, 1]");
    return rgb;
  }

private:
  std::string file_;
};

json parseJson(const std::string& text, const std::string& file) {
  atmosphere::ParsedJson<json> parsed = atmosphere::parseJsonFile<json>(text, file);
  if (!parsed.error.empty()) throw SceneError(parsed.error);
  return std::move(parsed.value);
}

/// The atmosphere a body's "atmosphere" key asks for: true (the atmosphere preset named
/// like the body's preset, else its name: earth, mars), false, a preset name, or a JSON file (relative to the scene file).
/// The model is read here, once, so that a bad one fails with the scene's file and field.
atmosphere::AtmosphereModelPtr parseAtmosphereModel(const Reader& in, const json& value, const std::string& field,
                                                    const std::string& bodyName, const std::string& sceneFile) {
  std::string model;
  if (value.is_boolean()) {
    if (!value.get<bool>()) return nullptr;
    std::string lower = bodyName;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    const auto names = atmosphere::presetNames();
    if (std::find(names.begin(), names.end(), lower) == names.end())
      in.fail(field, "no atmosphere preset named after '" + bodyName + "': give a preset name or a file");
    model = lower;
  } else if (value.is_string() && !value.get<std::string>().empty()) {
    model = value.get<std::string>();
    const bool isFile = model.find('/') != std::string::npos ||
                        (model.size() > 5 && model.compare(model.size() - 5, 5, ".json") == 0);
    if (isFile) {
      std::filesystem::path p(model);
      if (p.is_relative()) p = std::filesystem::path(sceneFile).parent_path() / p;
      model = p.lexically_normal().string();
    }
  } else {
    in.fail(field, "expected true, false, an atmosphere preset name or a file, " + got(value));
  }
  try {
    return atmosphere::AtmosphereModel::load(model);
  } catch (const std::exception& e) {
    in.fail(field, e.what());
  }
}

/// A body's "terrain": {"dem": FILE (relative to the scene) | "seed": N [, "size": N],
/// ["spacing": LENGTH,] "latDeg": ..., "lonDeg": ...}.
Terrain parseTerrain(const Reader& in, const json& value, const std::string& field, const std::string& sceneFile) {
  in.object(value, field, {"dem", "seed", "size", "spacing", "latDeg", "lonDeg"});
  const bool dem = value.contains("dem");
  if (dem == value.contains("seed"))
    in.fail(field, "expected either \"dem\" (a GeoTIFF file) or \"seed\" (a synthetic crater field)");
  for (const char* key : {"latDeg", "lonDeg"})
    if (!value.contains(key)) in.fail(field + "." + key, "required (the centre of the terrain)");
  Terrain t;
  if (dem) {
    std::filesystem::path p(in.string(value["dem"], field + ".dem"));
    if (p.is_relative()) p = std::filesystem::path(sceneFile).parent_path() / p;
    t.demPath = p.lexically_normal().string();
    if (!std::filesystem::is_regular_file(t.demPath)) in.fail(field + ".dem", "no such file: " + t.demPath);
    if (value.contains("size")) in.fail(field + ".size", "only for a synthetic terrain (\"seed\")");
  } else {
    t.seed = static_cast<std::uint64_t>(in.integer(value["seed"], field + ".seed", 0, 2147483647));
    if (value.contains("size")) t.size = in.integer(value["size"], field + ".size", 2, 4096);
  }
  if (value.contains("spacing")) t.spacingM = in.positiveLength(value["spacing"], field + ".spacing", 1e-3,
                                                                 "a length from 1 mm to 1e12 m");
  t.latDeg = in.number(value["latDeg"], field + ".latDeg", -90.0, 90.0, "a latitude in [-90, 90] degrees");
  t.lonDeg = in.number(value["lonDeg"], field + ".lonDeg", -360.0, 360.0, "a longitude in [-360, 360] degrees");
  return t;
}

/// What a body's "albedoMap" or "normalMap" names: the file ("" for "none") and whether it
/// is a reflectance map (NamedAlbedoMap::reflectance; a file of one's own is not).
struct MapChoice {
  std::string path;
  bool reflectance = false;
};

/// A body's "albedoMap" or "normalMap": a named map (`find`), "none", or an image file
/// (relative to the scene). A named map that is not installed is an error naming its package.
MapChoice parseMap(const Reader& in, const json& value, const std::string& field, const std::string& sceneFile,
                     std::optional<NamedAlbedoMap> (*find)(std::string_view), const std::string& namedList,
                     const char* noneMeans) {
  const std::string text = in.string(value, field);
  if (text == "none") return {};
  if (const auto named = find(text)) {
    if (!std::filesystem::is_regular_file(named->file))
      in.fail(field, "the '" + named->name + "' map is not installed (" + named->file + "): install the Debian package " +
                         named->package + ", or give \"none\" for " + noneMeans);
    return {named->file, named->reflectance};
  }
  std::filesystem::path p(text);
  if (p.is_relative()) p = std::filesystem::path(sceneFile).parent_path() / p;
  const std::string path = p.lexically_normal().string();
  if (!std::filesystem::is_regular_file(path))
    in.fail(field, "no such file: " + path + " (or a named map: " + namedList + ", or \"none\")");
  return {path, false};
}

/// A preset's named map when it is installed; when not, a note and "".
std::string presetMap(const std::optional<NamedAlbedoMap>& named, const std::string& body, const char* without,
                      std::vector<std::string>& notes) {
  if (!named) return "";
  if (std::filesystem::is_regular_file(named->file)) return named->file;
  notes.push_back(body + ": " + without + " (the " + named->name + " map is not installed: Debian package " +
                  named->package + ")");
  return "";
}

/// "stars": true (the packaged catalogue to V 6.5), false, or an object with "catalogue"
/// (a file relative to the scene) and "limitingMagnitude". The packaged catalogue not
/// installed is a note, not an error (xplanet's Yale catalogue instead when it is there,
/// else no stars); a named file that is not there is an error.
std::optional<StarSky> parseStars(const Reader& in, const json& value, const std::string& sceneFile,
                                  std::vector<std::string>& notes) {
  if (value.is_boolean() && !value.get<bool>()) return std::nullopt;
  StarSky stars;
  stars.cataloguePath = sky::kKStarsCatalogue;
  bool named = false;
  if (!value.is_boolean()) {
    if (!value.is_object()) in.fail("stars", "expected true, false or an object, " + got(value));
    in.object(value, "stars", {"catalogue", "limitingMagnitude", "scintillation", "seed", "milkyWay"});
    if (value.contains("catalogue")) {
      std::filesystem::path p(in.string(value["catalogue"], "stars.catalogue"));
      if (p.is_relative()) p = std::filesystem::path(sceneFile).parent_path() / p;
      stars.cataloguePath = p.lexically_normal().string();
      named = true;
    }
    if (value.contains("limitingMagnitude"))
      stars.limitingMagnitude = in.number(value["limitingMagnitude"], "stars.limitingMagnitude", -30.0, 30.0,
                                          "a V magnitude in [-30, 30]");
    if (value.contains("scintillation"))
      stars.scintillation = in.number(value["scintillation"], "stars.scintillation", 0.0, 1.0,
                                      "the spread of the log of a star's light at the zenith, in [0, 1]");
    if (value.contains("seed")) stars.seed = static_cast<std::uint64_t>(in.integer(value["seed"], "stars.seed", 0, 2147483647));
  }
  if (!value.is_boolean() && value.contains("milkyWay"))
    stars.milkyWayPath = parseMap(in, value["milkyWay"], "stars.milkyWay", sceneFile, findNamedMilkyWayMap,
                                  namedNormalMapList(), "no Milky Way").path;
  else
    stars.milkyWayPath = presetMap(findNamedMilkyWayMap("stellarium"), "stars", "no Milky Way", notes);
  if (!std::filesystem::is_regular_file(stars.cataloguePath)) {
    if (named) in.fail("stars.catalogue", "no such file: " + stars.cataloguePath);
    if (std::filesystem::is_regular_file(sky::kXplanetCatalogue)) {
      notes.push_back(std::string("the star catalogue ") + sky::kKStarsCatalogue +
                      " is not installed (Debian package kstars-data): the Yale Bright Star Catalogue " +
                      sky::kXplanetCatalogue + " instead (to V 8, without colours)");
      stars.cataloguePath = sky::kXplanetCatalogue;
      return stars;
    }
    notes.push_back("no stars: the star catalogue " + stars.cataloguePath +
                    " is not installed (Debian package kstars-data)");
    return std::nullopt;
  }
  return stars;
}

/// A body's "clouds": a list of layers (or one), each {"altitude": LENGTH, "coverage": 0..1,
/// "opticalDepth": N, "seed": N, "featureSize": LENGTH, "wind": [east, north] m/s}.
std::vector<sky::CloudLayer> parseClouds(const Reader& in, const json& value, const std::string& field) {
  const json list = value.is_array() ? value : json::array({value});
  if (list.size() > static_cast<std::size_t>(sky::kMaxCloudLayers))
    in.fail(field, "at most " + std::to_string(sky::kMaxCloudLayers) + " layers, got " + std::to_string(list.size()));
  std::vector<sky::CloudLayer> layers;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string f = value.is_array() ? index(field, i) : field;
    const json& v = list[i];
    if (!v.is_object()) in.fail(f, "expected a layer {\"altitude\", \"coverage\", \"opticalDepth\", ...}, " + got(v));
    in.object(v, f, {"altitude", "coverage", "opticalDepth", "seed", "featureSize", "wind"});
    sky::CloudLayer l;
    if (v.contains("altitude")) {
      l.altitudeM = in.length(v["altitude"], f + ".altitude", "a length from 0 m to 1e6 m");
      if (!(l.altitudeM >= 0.0 && l.altitudeM <= 1.0e6)) in.fail(f + ".altitude", "expected a length from 0 m to 1e6 m, " + got(v["altitude"]));
    }
    if (v.contains("coverage")) l.coverage = in.number(v["coverage"], f + ".coverage", 0.0, 1.0, "a fraction in [0, 1]");
    if (v.contains("opticalDepth"))
      l.opticalDepth = in.number(v["opticalDepth"], f + ".opticalDepth", 0.0, 1.0e4, "an optical depth in [0, 1e4]");
    if (v.contains("seed")) l.seed = static_cast<std::uint32_t>(in.integer(v["seed"], f + ".seed", 0, 2147483647));
    if (v.contains("featureSize"))
      l.featureSizeM = in.positiveLength(v["featureSize"], f + ".featureSize", sky::kMinCloudFeatureSizeM,
                                         "a length from 1 km to 1e12 m");
    if (v.contains("wind")) {
      const json& w = v["wind"];
      if (!w.is_array() || w.size() != 2 || !w[0].is_number() || !w[1].is_number())
        in.fail(f + ".wind", "expected [east, north] in m/s, " + got(w));
      l.windEastMs = in.number(w[0], f + ".wind[0]", -1000.0, 1000.0, "a speed in [-1000, 1000] m/s");
      l.windNorthMs = in.number(w[1], f + ".wind[1]", -1000.0, 1000.0, "a speed in [-1000, 1000] m/s");
    }
    layers.push_back(l);
  }
  return layers;
}

Body parseBody(const Reader& in, const json& value, const std::string& field, const std::string& sceneFile,
               std::vector<std::string>& notes) {
  in.object(value, field,
            {"preset", "name", "radius", "equatorialRadius", "polarRadius", "position",
             "atmosphere", "albedo", "color", "photometry", "albedoMap", "normalMap", "relief", "terrain",
              "clouds"});
  Body body;
  const BodyPreset* preset = nullptr;
  if (value.contains("preset")) {
    const std::string name = in.string(value["preset"], field + ".preset");
    preset = findPreset(name);
    if (preset == nullptr)
      in.fail(field + ".preset",
              "unknown body '" + name + "' (known: " + presetNameList() + ")");
    body.preset = preset->name;
    body.name = preset->name;
    body.radiusM = preset->meanRadiusM;
    body.equatorialRadiusM = preset->equatorialRadiusM;
    body.polarRadiusM = preset->polarRadiusM;
    body.hasAtmosphere = preset->hasAtmosphere;
    body.albedo = preset->geometricAlbedo;
    body.color = glm::dvec3(preset->color[0], preset->color[1], preset->color[2]);
    body.photometry = preset->photometry;
  } else {
    for (const char* key : {"name", "radius", "position"})
      if (!value.contains(key))
        in.fail(field + "." + key, "required for a body without a preset");
  }

  if (value.contains("name")) body.name = in.string(value["name"], field + ".name");
  const bool hasEquatorial = value.contains("equatorialRadius");
  const bool hasPolar = value.contains("polarRadius");
  if (value.contains("radius")) {
    body.radiusM = in.positiveLength(value["radius"], field + ".radius");
    body.equatorialRadiusM = body.polarRadiusM = body.radiusM;
  }
  if (hasEquatorial)
    body.equatorialRadiusM = in.positiveLength(value["equatorialRadius"], field + ".equatorialRadius");
  if (hasPolar) body.polarRadiusM = in.positiveLength(value["polarRadius"], field + ".polarRadius");
  if ((hasEquatorial || hasPolar) && !value.contains("radius"))
    body.radiusM = (2.0 * body.equatorialRadiusM + body.polarRadiusM) / 3.0;

  if (!value.contains("position") || value["position"] == "ephemeris") {
    if (preset == nullptr)
      in.fail(field + ".position", "no ephemeris for a body without a preset: give its "
                                   "position explicitly in metres");
    if (!hasEphemeris(preset->name))
      in.fail(field + ".position", "no ephemeris for '" + preset->name +
                                       "': give its position explicitly in metres");
    body.positionFromEphemeris = true;
  } else if (value["position"].is_array()) {
    body.positionM = in.vector(value["position"], field + ".position");
  } else {
    in.fail(field + ".position",
            "expected [x, y, z] in metres or \"ephemeris\", " + got(value["position"]));
  }

  if (value.contains("atmosphere")) {
    body.atmosphere = parseAtmosphereModel(in, value["atmosphere"], field + ".atmosphere",
                                                 body.preset.empty() ? body.name : body.preset, sceneFile);
    body.hasAtmosphere = body.atmosphere != nullptr;
  }
  if (value.contains("albedo"))
    body.albedo = in.number(value["albedo"], field + ".albedo", 0.0, 1.0, "a number in [0, 1]");
  if (value.contains("color")) body.color = in.color(value["color"], field + ".color");
  if (value.contains("photometry")) {
    const std::string law = in.string(value["photometry"], field + ".photometry");
    if (law == "lambert") body.photometry = {};
    else if (law == "hapke") body.photometry = {sky::Photometry::Law::Hapke, sky::moonParameters()};
    else in.fail(field + ".photometry", "expected \"lambert\" or \"hapke\", got \"" + law + "\"");
  }
  if (value.contains("albedoMap")) {
    const MapChoice map = parseMap(in, value["albedoMap"], field + ".albedoMap", sceneFile, findNamedAlbedoMap,
                                   namedAlbedoMapList(), "a uniform albedo");
    body.albedoMapPath = map.path;
    body.albedoMapReflectance = map.reflectance;
  } else if (preset != nullptr && !preset->albedoMap.empty())
    body.albedoMapPath = presetMap(findNamedAlbedoMap(preset->albedoMap), body.name, "uniform albedo", notes);
  if (value.contains("normalMap"))
    body.normalMapPath = parseMap(in, value["normalMap"], field + ".normalMap", sceneFile, findNamedNormalMap,
                                  namedNormalMapList(), "the sphere's normals").path;
  else if (preset != nullptr && !preset->normalMap.empty())
    body.normalMapPath = presetMap(findNamedNormalMap(preset->normalMap), body.name, "no relief", notes);
  if (value.contains("relief"))
    body.reliefStrength = in.number(value["relief"], field + ".relief", 0.0, 4.0, "a number in [0, 4]");
  if (value.contains("terrain")) {
    if (preset == nullptr || !hasRotationModel(preset->name))
      in.fail(field + ".terrain", "needs a body with a rotation model (a preset: Earth, Moon, Mars)");
    body.terrain = parseTerrain(in, value["terrain"], field + ".terrain", sceneFile);
  }
  if (value.contains("clouds")) {
    if (!body.atmosphere)
      in.fail(field + ".clouds", "clouds are drawn in an atmosphere: give the body \"atmosphere\" too");
    body.clouds = parseClouds(in, value["clouds"], field + ".clouds");
  }
  return body;
}

void parseBodies(const Reader& in, const json& root, Scene& scene) {
  if (!root.contains("bodies")) in.fail("bodies", "required (a list of bodies with one Sun)");
  const json& list = root["bodies"];
  if (!list.is_array() || list.empty())
    in.fail("bodies", "expected a non-empty list of bodies, " + got(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = index("bodies", i);
    Body body = parseBody(in, list[i], field, scene.path, scene.notes);
    for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
      if (scene.bodies[j].name == body.name)
        in.fail(field + ".name", "duplicate name '" + body.name + "' (also " +
                                     index("bodies", j) + ")");
      if (scene.bodies[j].isSun() && body.isSun())
        in.fail(field + ".preset", "a second Sun (" + index("bodies", j) +
                                       " is the Sun); a scene has exactly one");
    }
    scene.bodies.push_back(body);
  }
  const bool hasSun = std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                  [](const Body& b) { return b.isSun(); });
  if (!hasSun) in.fail("bodies", "no Sun: add {\"preset\": \"Sun\"}");
}

std::string bodyNameList(const Scene& scene) {
  std::string list;
  for (const Body& body : scene.bodies) list += (list.empty() ? "" : ", ") + body.name;
  return list;
}

const Body& sceneBody(const Reader& in, const Scene& scene, const json& value,
                      const std::string& field) {
  const std::string name = in.string(value, field);
  const Body* body = scene.find(name);
  if (body == nullptr)
    in.fail(field, "unknown body '" + name + "' (scene bodies: " + bodyNameList(scene) + ")");
  return *body;
}

Observer parseObserver(const Reader& in, const json& value, const Scene& scene) {
  const std::string field = "camera.observer";
  in.object(value, field, {"body", "latDeg", "lonDeg", "altM"});
  for (const char* key : {"body", "latDeg", "lonDeg"})
    if (!value.contains(key)) in.fail(field + "." + key, "required");
  Observer observer;
  const Body& body = sceneBody(in, scene, value["body"], field + ".body");
  if (!hasRotationModel(body.preset))
    in.fail(field + ".body", "no rotation model for '" + body.name +
                                 "' (observers can stand on Sun, Earth, Moon, Mars)");
  observer.body = body.name;
  observer.latDeg =
      in.number(value["latDeg"], field + ".latDeg", -90.0, 90.0, "a latitude in [-90, 90] degrees");
  observer.lonDeg = in.number(value["lonDeg"], field + ".lonDeg", -360.0, 360.0,
                              "a longitude in [-360, 360] degrees");
  if (value.contains("altM"))
    observer.altM = in.number(value["altM"], field + ".altM", -1e4, 1e12,
                              "an altitude from -10000 m to 1e12 m");
  return observer;
}

void parseCamera(const Reader& in, const json& root, Scene& scene) {
  if (!root.contains("camera"))
    in.fail("camera", "required (an object with position or observer, and target)");
  const json& value = root["camera"];
  in.object(value, "camera", {"position", "observer", "target", "up", "fovDeg"});
  Camera& camera = scene.camera;

  const bool hasPosition = value.contains("position");
  if (hasPosition == value.contains("observer"))
    in.fail("camera", "expected either 'position' [x, y, z] or 'observer' "
                      "{body, latDeg, lonDeg, altM}");
  if (hasPosition) camera.positionM = in.vector(value["position"], "camera.position");
  else camera.observer = parseObserver(in, value["observer"], scene);

  if (!value.contains("target"))
    in.fail("camera.target", "required (a body name, [x, y, z] in metres, or {azimuthDeg, elevationDeg})");
  const json& target = value["target"];
  if (target.is_array()) {
    camera.targetM = in.vector(target, "camera.target");
  } else if (target.is_string()) {
    camera.targetBody = sceneBody(in, scene, target, "camera.target").name;
  } else if (target.is_object()) {
    in.object(target, "camera.target", {"azimuthDeg", "elevationDeg"});
    if (!camera.observer)
      in.fail("camera.target", "an azimuth and elevation need a camera observer (they are in its horizon)");
    for (const char* key : {"azimuthDeg", "elevationDeg"})
      if (!target.contains(key)) in.fail(std::string("camera.target.") + key, "required");
    HorizontalDirection d;
    d.azimuthDeg = in.number(target["azimuthDeg"], "camera.target.azimuthDeg", -360.0, 360.0,
                             "an azimuth in [-360, 360] degrees from north through east");
    d.elevationDeg = in.number(target["elevationDeg"], "camera.target.elevationDeg", -90.0, 90.0,
                               "an elevation in [-90, 90] degrees");
    camera.targetDirection = d;
  } else {
    in.fail("camera.target", "expected a body name, [x, y, z] in metres or {azimuthDeg, elevationDeg}, " + got(target));
  }

  if (value.contains("up") && value["up"] == "zenith") {
    if (!value.contains("observer")) in.fail("camera.up", "\"zenith\" needs a camera observer");
    camera.upIsZenith = true;
  } else if (value.contains("up")) {
    const glm::dvec3 up = in.vector(value["up"], "camera.up");
    if (!(glm::length(up) > 0.0)) in.fail("camera.up", "expected a non-zero vector");
    camera.requestedUp = up;
  }
  if (value.contains("fovDeg")) {
    camera.fovDeg = in.number(value["fovDeg"], "camera.fovDeg", 0.0, 180.0,
                              "a vertical field of view in (0, 180) degrees");
    if (camera.fovDeg <= 0.0 || camera.fovDeg >= 180.0)
      in.fail("camera.fovDeg",
              "expected a vertical field of view in (0, 180) degrees, " + got(value["fovDeg"]));
  }
}

/// The scene needs a time when a position depends on it.
void checkTime(const Reader& in, const Scene& scene) {
  if (scene.hasTime) return;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (scene.bodies[i].positionFromEphemeris && !scene.bodies[i].isSun()) // Sun: origin
      in.fail("time", "required: " + index("bodies", i) + " ('" + scene.bodies[i].name +
                          "') takes its position from the ephemeris");
  if (scene.camera.observer)
    in.fail("time", "required: the camera observer stands on a rotating body");
}

} // namespace

Scene parseScene(const std::string& jsonText, const std::string& pathForMessages) {
  const Reader in(pathForMessages);
  const json root = parseJson(jsonText, pathForMessages);
  if (!root.is_object()) in.fail("", "expected a JSON object at the top level, " + got(root));
  in.object(root, "", {"name", "time", "bodies", "camera", "exposure", "image", "shadow", "stars"});

  Scene scene;
  scene.path = pathForMessages;
  scene.name = root.contains("name") ? in.string(root["name"], "name")
                                     : std::filesystem::path(pathForMessages).stem().string();
  if (root.contains("time")) {
    const json& time = root["time"];
    try {
      if (time.is_object()) {
        // {"eclipse": "2015-09-28", "at": "U2+10min"}: UT1, which UTC follows to 0.9 s.
        in.object(time, "time", {"eclipse", "at"});
        if (!time.contains("eclipse") || !time.contains("at"))
          in.fail("time", "an eclipse's instant needs both \"eclipse\" (its date) and \"at\" (greatest, P1, U2+10min...)");
        const double ut1 = eclipseInstantUt(in.string(time["eclipse"], "time.eclipse"), in.string(time["at"], "time.at"));
        scene.time.jd1 = std::floor(ut1);
        scene.time.jd2 = ut1 - scene.time.jd1;
      } else {
        scene.time = parseUtc(in.string(time, "time"));
      }
    } catch (const std::invalid_argument& e) {
      in.fail("time", e.what());
    }
    scene.hasTime = true;
    scene.fileTime = scene.time;
  }
  parseBodies(in, root, scene);
  parseCamera(in, root, scene);
  checkTime(in, scene);

  if (root.contains("exposure"))
    scene.exposureEv =
        in.number(root["exposure"], "exposure", -60.0, 60.0, "an exposure in [-60, 60] EV");
  if (root.contains("image")) {
    const json& image = root["image"];
    in.object(image, "image", {"width", "height"});
    if (image.contains("width")) scene.width = in.integer(image["width"], "image.width", 16, 16384);
    if (image.contains("height"))
      scene.height = in.integer(image["height"], "image.height", 16, 16384);
  }
  if (root.contains("shadow")) {
    const json& shadow = root["shadow"];
    in.object(shadow, "shadow", {"lutSize"});
    if (shadow.contains("lutSize"))
      scene.shadowLutSize = in.integer(shadow["lutSize"], "shadow.lutSize", 8, 4096);
  }

  // Stars by default in a scene with a time (their places are for a date).
  if (root.contains("stars")) {
    if (!scene.hasTime && !(root["stars"].is_boolean() && !root["stars"].get<bool>()))
      in.fail("time", "required: the stars' places are for a date");
    scene.stars = parseStars(in, root["stars"], pathForMessages, scene.notes);
  } else if (scene.hasTime) {
    scene.stars = parseStars(in, json(true), pathForMessages, scene.notes);
  }

  detail::resolve(scene);
  return scene;
}

} // namespace umbra::scene
