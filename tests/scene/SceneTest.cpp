#include "scene/Eclipses.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Scene.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

using namespace umbra::scene;

namespace {

const char* const kFile = "examples/x.json";

/// The SceneError message for this JSON text (fails the test when it parses).
std::string errorFor(const std::string& text) {
  try {
    parseScene(text, kFile);
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for: " << text;
  return "";
}

/// A scene that needs no time: a Sun, a rock, a camera at a fixed point.
std::string fixedScene(const std::string& bodies, const std::string& extra = "") {
  return R"({"bodies": [)" + bodies +
         R"(], "camera": {"position": [1e11, 0, 1e6], "target": [1e11, 0, 0]})" + extra + "}";
}

const std::string kSunAndRock =
    R"({"preset": "Sun"}, {"name": "Rock", "radius": "10km", "position": [1e11, 0, 0]})";

} // namespace

// ---- one test per error case ------------------------------------------------------------

TEST(SceneErrors, MalformedJson) {
  const std::string message = errorFor("{\n  \"bodies\": [\n    {\"preset\" \"Sun\"}\n  ]\n}\n");
  EXPECT_EQ(message.rfind("examples/x.json: invalid JSON at line 3, column 19: ", 0), 0u)
      << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
}

TEST(SceneValidation, JsonErrorPositionsMatchNlohmann) {
  EXPECT_EQ(errorFor(""), "examples/x.json: invalid JSON at line 1, column 1: syntax error "
                          "while parsing value - unexpected end of input; expected '[', '{', "
                          "or a literal");
  EXPECT_EQ(errorFor("{\"a\":1,\n}"),
            "examples/x.json: invalid JSON at line 2, column 1: syntax error while parsing "
            "object key - unexpected '}'; expected string literal");
  EXPECT_EQ(errorFor("{\"a\":1}\n\n x").rfind("examples/x.json: invalid JSON at line 3, "
                                              "column 2: syntax error", 0),
            0u);
}

TEST(SceneErrors, UnknownPreset) {
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Pluto"})")),
            "examples/x.json: bodies[1].preset: unknown body 'Pluto' "
            "(known: Sun, Earth, Moon, Mars, Phobos, Deimos)");
}

// Lengths beyond the physical limits are named, not passed on to overflow later (a
// position of 1e308 m made the camera's up vector "parallel to the view direction").
TEST(SceneErrors, LengthsBeyondPhysicalLimits) {
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"name": "Rock", "radius": "1e13", "position": [0, 0, 1]})")),
            "examples/x.json: bodies[1].radius: expected a length from 1 m to 1e12 m, got \"1e13\"");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"name": "Rock", "radius": 0.5, "position": [0, 0, 1]})")),
            "examples/x.json: bodies[1].radius: expected a length from 1 m to 1e12 m, got 0.5");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"name": "Rock", "radius": 5, "position": [0, -1e308, 1]})")),
            "examples/x.json: bodies[1].position[1]: expected a length within 1e15 m of the Sun, got -1e+308");
}

TEST(SceneErrors, NegativeRadius) {
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"name": "Moonlet", "radius": "1km",
                                   "position": [0, 0, 1]},
                                   {"name": "Rock", "radius": -5, "position": [0, 0, 1]})")),
            "examples/x.json: bodies[2].radius: expected a length from 1 m to 1e12 m, got -5");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"},
                                   {"name": "Rock", "radius": "-5 km", "position": [0, 0, 1]})")),
            "examples/x.json: bodies[1].radius: expected a length from 1 m to 1e12 m, got \"-5 km\"");
}

TEST(SceneErrors, MissingFile) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "umbra-no-such-scene.json").string();
  try {
    loadScene(path);
    FAIL() << "no exception";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open file: No such file or directory");
  }
}

TEST(SceneErrors, UnknownTopLevelKey) {
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, R"(, "exposre": -5)")),
            "examples/x.json: exposre: unknown key (expected one of: name, time, bodies, "
            "camera, exposure, image, shadow, stars)");
}

TEST(SceneErrors, TwoSuns) {
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "sun", "name": "Sun2"})")),
            "examples/x.json: bodies[1].preset: a second Sun (bodies[0] is the Sun); "
            "a scene has exactly one");
}

TEST(SceneErrors, ObserverLatitudeOutOfRange) {
  const std::string text = R"({"time": "2015-09-28T01:45Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": 91, "lonDeg": 0}, "target": "Moon"}})";
  EXPECT_EQ(errorFor(text), "examples/x.json: camera.observer.latDeg: expected a latitude in "
                            "[-90, 90] degrees, got 91");
}

// ---- more validation --------------------------------------------------------------------

TEST(SceneValidation, MoreMessagesNameTheField) {
  EXPECT_EQ(errorFor("[1, 2]"),
            "examples/x.json: expected a JSON object at the top level, got [1,2]");
  EXPECT_EQ(errorFor(R"({"camera": {}})"),
            "examples/x.json: bodies: required (a list of bodies with one Sun)");
  EXPECT_EQ(errorFor(fixedScene(R"({"name": "Rock", "radius": 1, "position": [0, 0, 1]})")),
            "examples/x.json: bodies: no Sun: add {\"preset\": \"Sun\"}");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"name": "Rock", "radius": 1})")),
            "examples/x.json: bodies[1].position: required for a body without a preset");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun", "position": [0, 0, 0]}, {"preset": "Phobos"})")),
            "examples/x.json: bodies[1].position: no ephemeris for 'Phobos': give its "
            "position explicitly in metres");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock + R"(, {"name": "Rock", "radius": 1, "position": [0, 0, 1]})")),
            "examples/x.json: bodies[2].name: duplicate name 'Rock' (also bodies[1])");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"},
                                   {"name": "Rock", "radius": "12 parsec", "position": [0, 0, 1]})")),
            "examples/x.json: bodies[1].radius: invalid length '12 parsec': expected a number "
            "with unit m, km or au");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"},
                                   {"name": "Rock", "radius": 1, "position": [0, "x", 1]})")),
            "examples/x.json: bodies[1].position[1]: invalid length 'x': expected a number "
            "with unit m, km or au");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Moon", "albdo": 0.1})")),
            "examples/x.json: bodies[1].albdo: unknown key (expected one of: preset, name, "
            "radius, equatorialRadius, polarRadius, position, atmosphere, albedo, color, photometry, albedoMap, normalMap, "
            "relief, terrain, clouds)");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, R"(, "image": {"width": 8})")),
            "examples/x.json: image.width: expected an integer in [16, 16384], got 8");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, R"(, "shadow": {"lutSize": 256.5})")),
            "examples/x.json: shadow.lutSize: expected an integer in [8, 4096], got 256.5");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Earth"})")),
            "examples/x.json: time: required: bodies[1] ('Earth') takes its position from the "
            "ephemeris");
  EXPECT_EQ(errorFor(R"({"time": "2015-09-28T25:00Z", "bodies": [{"preset": "Sun"}]})"),
            "examples/x.json: time: invalid UTC time '2015-09-28T25:00Z': hour out of range");
}

// "terrain": a synthetic crater field or a DEM file relative to the scene, on a body
// with a rotation model.
TEST(SceneValidation, TerrainMessages) {
  const auto moon = [](const std::string& terrain) {
    return fixedScene(R"({"preset": "Sun", "position": [0, 0, 0]}, {"preset": "Moon", "position": [1e11, 0, 0], "terrain": )" +
                      terrain + "}");
  };
  const Scene ok = parseScene(moon(R"({"seed": 3, "size": 64, "spacing": "20m", "latDeg": -89.5, "lonDeg": 10})"), kFile);
  ASSERT_TRUE(ok.bodies[1].terrain.has_value());
  EXPECT_EQ(ok.bodies[1].terrain->seed, 3u);
  EXPECT_EQ(ok.bodies[1].terrain->size, 64);
  EXPECT_DOUBLE_EQ(ok.bodies[1].terrain->spacingM, 20.0);
  EXPECT_DOUBLE_EQ(ok.bodies[1].terrain->latDeg, -89.5);
  EXPECT_TRUE(ok.bodies[1].terrain->demPath.empty());
  EXPECT_EQ(errorFor(moon(R"({"latDeg": 0, "lonDeg": 0})")),
            "examples/x.json: bodies[1].terrain: expected either \"dem\" (a GeoTIFF file) or \"seed\" (a synthetic "
            "crater field)");
  EXPECT_EQ(errorFor(moon(R"({"seed": 1, "lonDeg": 0})")),
            "examples/x.json: bodies[1].terrain.latDeg: required (the centre of the terrain)");
  EXPECT_EQ(errorFor(moon(R"({"seed": 1, "size": 1, "latDeg": 0, "lonDeg": 0})")),
            "examples/x.json: bodies[1].terrain.size: expected an integer in [2, 4096], got 1");
  EXPECT_EQ(errorFor(moon(R"({"dem": "nothere.tif", "latDeg": 0, "lonDeg": 0})")),
            "examples/x.json: bodies[1].terrain.dem: no such file: examples/nothere.tif");
  EXPECT_EQ(errorFor(moon(R"({"seed": 1, "latDeg": 0, "lonDeg": 0, "hieght": 2})")).substr(0, 58),
            "examples/x.json: bodies[1].terrain.hieght: unknown key (ex");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock.substr(0, kSunAndRock.size() - 1) + R"(, "terrain": {"seed": 1, "latDeg": 0, "lonDeg": 0}})")),
            "examples/x.json: bodies[1].terrain: needs a body with a rotation model (a preset: Earth, Moon, Mars)");
}

// "atmosphere": true (the preset named after the body), false, a preset, a file relative
// to the scene; a preset's own flag (Earth: true) does not ask for rendering.
TEST(Scene, AtmosphereChoices) {
  auto model = [](const std::string& body) {
    const auto m = parseScene(fixedScene(R"({"preset": "Sun"}, )" + body), kFile).bodies[1].atmosphere;
    return m ? m->name() : std::string();
  };
  EXPECT_EQ(model(R"({"preset": "Earth", "position": [1e11, 0, 0], "atmosphere": true})"), "earth");
  EXPECT_EQ(model(R"({"preset": "Earth", "name": "Terra", "position": [1e11, 0, 0], "atmosphere": true})"), "earth");
  EXPECT_EQ(model(R"({"name": "Mars", "radius": "3389.5 km", "position": [1e11, 0, 0], "atmosphere": true})"), "mars");
  EXPECT_EQ(model(R"({"preset": "Earth", "position": [1e11, 0, 0]})"), "");
  EXPECT_EQ(model(R"({"preset": "Earth", "position": [1e11, 0, 0], "atmosphere": false})"), "");
  EXPECT_EQ(model(R"({"preset": "Earth", "position": [1e11, 0, 0], "atmosphere": "earth-2015-calbuco"})"),
            "earth-2015-calbuco");
  const auto dir = std::filesystem::temp_directory_path() / "umbra-scene-atmosphere-test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "thin.json") << R"({"extends": "earth", "name": "thin"})";
  }
  const Scene scene = parseScene(
      fixedScene(R"({"preset": "Sun"}, {"preset": "Earth", "position": [1e11, 0, 0], "atmosphere": "thin.json"})"),
      (dir / "scene.json").string());
  ASSERT_TRUE(scene.bodies[1].atmosphere);
  EXPECT_EQ(scene.bodies[1].atmosphere->name(), (dir / "thin.json").string());
  EXPECT_EQ(scene.bodies[1].atmosphere->rgb().name, "thin");
  std::filesystem::remove_all(dir);
}

TEST(SceneValidation, AtmosphereMessages) {
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Moon", "position": [1, 0, 0], "atmosphere": true})")),
            "examples/x.json: bodies[1].atmosphere: no atmosphere preset named after 'Moon': give a preset "
            "name or a file");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Moon", "position": [1, 0, 0], "atmosphere": 3})")),
            "examples/x.json: bodies[1].atmosphere: expected true, false, an atmosphere preset name or a "
            "file, got 3");
  const std::string unknown =
      errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Moon", "position": [1, 0, 0], "atmosphere": "venus"})"));
  EXPECT_EQ(unknown.rfind("examples/x.json: bodies[1].atmosphere: ", 0), 0u) << unknown;
  EXPECT_NE(unknown.find("venus"), std::string::npos) << unknown;
  const std::string missing =
      errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Moon", "position": [1, 0, 0], "atmosphere": "no/such.json"})"));
  EXPECT_EQ(missing.rfind("examples/x.json: bodies[1].atmosphere: ", 0), 0u) << missing;
}

TEST(SceneValidation, CameraMessages) {
  const std::string head = R"({"time": "2015-09-28T01:45Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"}, {"preset": "Moon"},
               {"preset": "Phobos", "position": [2e11, 0, 0]}], "camera": )";
  EXPECT_EQ(errorFor(head + R"({"target": "Moon"}})"),
            "examples/x.json: camera: expected either 'position' [x, y, z] or 'observer' "
            "{body, latDeg, lonDeg, altM}");
  EXPECT_EQ(errorFor(head + R"({"position": [0, 0, 0], "target": "Pluto"}})"),
            "examples/x.json: camera.target: unknown body 'Pluto' (scene bodies: Sun, Earth, "
            "Moon, Phobos)");
  EXPECT_EQ(errorFor(head + R"({"position": [1, 0, 0], "target": [1, 0, 0]}})"),
            "examples/x.json: camera.target: the target is at the camera position");
  EXPECT_EQ(errorFor(head + R"({"position": [1, 0, 0], "target": "Moon", "fovDeg": 180}})"),
            "examples/x.json: camera.fovDeg: expected a vertical field of view in (0, 180) "
            "degrees, got 180");
  EXPECT_EQ(errorFor(head + R"({"observer": {"body": "Phobos", "latDeg": 0, "lonDeg": 0},
                                "target": "Moon"}})"),
            "examples/x.json: camera.observer.body: no rotation model for 'Phobos' (observers "
            "can stand on Sun, Earth, Moon, Mars)");
  EXPECT_EQ(errorFor(head + R"({"observer": {"body": "Earth", "latDeg": 0, "lonDeg": 0,
                                "altM": -20000}, "target": "Moon"}})"),
            "examples/x.json: camera.observer.altM: expected an altitude from -10000 m to 1e12 m, "
            "got -20000");
  EXPECT_EQ(errorFor(head + R"({"observer": {"body": "Earth", "latDeg": 0, "lonDeg": 0},
                                "target": "Moon", "zoom": 2}})"),
            "examples/x.json: camera.zoom: unknown key (expected one of: position, observer, "
            "target, up, fovDeg)");
  // An azimuth and elevation: in an observer's horizon.
  EXPECT_EQ(errorFor(head + R"({"position": [1, 0, 0], "target": {"azimuthDeg": 90, "elevationDeg": 10}}})"),
            "examples/x.json: camera.target: an azimuth and elevation need a camera observer (they are in its "
            "horizon)");
  const std::string observer = R"({"observer": {"body": "Earth", "latDeg": 0, "lonDeg": 0}, "target": )";
  EXPECT_EQ(errorFor(head + observer + R"({"azimuthDeg": 90}}})"),
            "examples/x.json: camera.target.elevationDeg: required");
  EXPECT_EQ(errorFor(head + observer + R"({"azimuthDeg": 90, "elevationDeg": 95}}})"),
            "examples/x.json: camera.target.elevationDeg: expected an elevation in [-90, 90] degrees, got 95");
  EXPECT_EQ(errorFor(head + observer + R"({"azimuthDeg": 90, "altitudeDeg": 5}}})"),
            "examples/x.json: camera.target.altitudeDeg: unknown key (expected one of: azimuthDeg, elevationDeg)");
  EXPECT_EQ(errorFor(head + observer + R"(7}})"),
            "examples/x.json: camera.target: expected a body name, [x, y, z] in metres or {azimuthDeg, "
            "elevationDeg}, got 7");
}

// ---- valid scenes -----------------------------------------------------------------------

TEST(Scene, DefaultsAndOverrides) {
  const Scene scene = parseScene(
      fixedScene(R"({"preset": "Sun"},
                    {"preset": "Moon", "name": "Luna", "radius": "1000 km", "albedo": 0.2,
                     "position": ["1 au", 0, "-2km"], "atmosphere": "mars", "color": [1, 0, 0]},
                    {"name": "Rock", "radius": 10, "position": [1e11, 0, 0]})"),
      "scenes/my-scene.json");
  EXPECT_EQ(scene.name, "my-scene");
  EXPECT_FALSE(scene.hasTime);
  EXPECT_EQ(scene.sun().name, "Sun");
  EXPECT_EQ(scene.sun().positionM, glm::dvec3(0.0));
  const Body* luna = scene.find("Luna");
  ASSERT_NE(luna, nullptr);
  EXPECT_EQ(luna->preset, "Moon");
  EXPECT_EQ(luna->radiusM, 1e6);
  EXPECT_EQ(luna->equatorialRadiusM, 1e6);
  EXPECT_EQ(luna->polarRadiusM, 1e6);
  EXPECT_EQ(luna->albedo, 0.2);
  EXPECT_TRUE(luna->hasAtmosphere);
  ASSERT_TRUE(luna->atmosphere);
  EXPECT_EQ(luna->atmosphere->name(), "mars");
  EXPECT_FALSE(luna->positionFromEphemeris);
  EXPECT_EQ(luna->positionM, glm::dvec3(149597870700.0, 0.0, -2000.0));
  EXPECT_EQ(luna->color, glm::dvec3(1, 0, 0));
  EXPECT_EQ(scene.find("Moon"), nullptr);
  const Body* rock = scene.find("Rock");
  ASSERT_NE(rock, nullptr);
  EXPECT_EQ(rock->preset, "");
  EXPECT_FALSE(rock->isSun());
  EXPECT_EQ(scene.exposureEv, 0.0);
  EXPECT_EQ(scene.width, 960);
  EXPECT_EQ(scene.height, 720);
  EXPECT_EQ(scene.shadowLutSize, 256);
  EXPECT_EQ(scene.camera.fovDeg, 45.0);
  EXPECT_FALSE(scene.camera.observer);
  // The camera looks along -z, so the default up (+z) falls back to +x.
  EXPECT_NEAR(glm::length(scene.camera.up - glm::dvec3(1, 0, 0)), 0.0, 1e-12);
}

TEST(Scene, UpIsOrthogonalizedAgainstTheViewDirection) {
  const Scene scene = parseScene(
      R"({"bodies": [{"preset": "Sun"}],
          "camera": {"position": [1e11, 0, 0], "target": "Sun", "up": [1, 0, 1]}})",
      kFile);
  EXPECT_NEAR(glm::length(scene.camera.up - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

// A target given as an azimuth (from north through east) and an elevation: the view
// direction against the observer's horizon computed independently, from GeographicLib's
// ellipsoid by finite differences (north: +latitude, east: +longitude, up: +altitude),
// body-fixed and turned to ICRS; the target follows the horizon as the body turns.
TEST(Scene, TargetAzimuthAndElevationAreInTheObserversHorizon) {
  const double latDeg = 40.0, lonDeg = -30.0;
  auto scene = [&](double az, double el) {
    return parseScene(R"({"time": "2024-03-20T18:00:00Z", "bodies": [{"preset": "Sun"}, {"preset": "Earth"}],
        "camera": {"observer": {"body": "Earth", "latDeg": 40, "lonDeg": -30, "altM": 2},
                   "target": {"azimuthDeg": )" + std::to_string(az) + R"(, "elevationDeg": )" + std::to_string(el) +
                          "}}}",
                      kFile);
  };
  auto axes = [&](UtcTime t) {
    const Body earth = *parseScene(R"({"time": "2024-03-20T18:00:00Z", "bodies": [{"preset": "Sun"}, {"preset": "Earth"}],
        "camera": {"position": [1, 0, 0], "target": "Sun"}})", kFile).find("Earth");
    const GeographicLib::Geocentric ellipsoid(earth.equatorialRadiusM,
                                              (earth.equatorialRadiusM - earth.polarRadiusM) / earth.equatorialRadiusM);
    auto at = [&](double lat, double lon, double alt) {
      glm::dvec3 p;
      ellipsoid.Forward(lat, lon, alt, p.x, p.y, p.z);
      return p;
    };
    const glm::dvec3 o = at(latDeg, lonDeg, 2.0);
    const glm::dmat3 r = bodyFixedToInertial("Earth", t);
    return std::array<glm::dvec3, 3>{r * glm::normalize(at(latDeg + 1e-5, lonDeg, 2.0) - o),
                                     r * glm::normalize(at(latDeg, lonDeg + 1e-5, 2.0) - o),
                                     r * glm::normalize(at(latDeg, lonDeg, 1002.0) - o)};
  };
  const auto [north, east, up] = axes(parseUtc("2024-03-20T18:00:00Z"));
  const double d = std::acos(-1.0) / 180.0;
  const std::vector<std::array<double, 2>> cases = {{0, 0}, {90, 0}, {180, 30}, {270, -10}, {-45, 60}, {10, 90}};
  for (const auto& [az, el] : cases) {
    const Scene s = scene(az, el);
    const glm::dvec3 view = glm::normalize(s.camera.targetM - s.camera.positionM);
    const glm::dvec3 expected =
        std::cos(el * d) * (std::cos(az * d) * north + std::sin(az * d) * east) + std::sin(el * d) * up;
    EXPECT_LT(glm::length(view - expected), 1e-6) << "azimuth " << az << ", elevation " << el;
  }
  // Three hours later the Earth has turned 45 degrees: the same horizon direction.
  Scene s = scene(90, 20);
  setTime(s, parseUtc("2024-03-20T21:00:00Z"));
  const auto later = axes(parseUtc("2024-03-20T21:00:00Z"));
  const glm::dvec3 view = glm::normalize(s.camera.targetM - s.camera.positionM);
  EXPECT_LT(glm::length(view - (std::cos(20 * d) * later[1] + std::sin(20 * d) * later[2])), 1e-6);
  EXPECT_GT(glm::length(later[2] - up), 0.5);  // it did turn
}

// The Sun's elevation from the north pole is its declination: 0 at the March equinox of
// 2024 (03:06 UTC), the obliquity of the ecliptic (23.44 deg) at the June solstice
// (2024-06-20 20:51 UTC); without an observer, none.
TEST(Scene, SunElevationFromThePoleIsTheSunsDeclination) {
  auto at = [](const std::string& time) {
    return parseScene(R"({"time": ")" + time + R"(", "bodies": [{"preset": "Sun"}, {"preset": "Earth"}],
        "camera": {"observer": {"body": "Earth", "latDeg": 90, "lonDeg": 0}, "target": "Sun"}})",
                      kFile);
  };
  EXPECT_NEAR(*sunElevationDeg(at("2024-03-20T03:06:00Z")), 0.0, 0.02);
  EXPECT_NEAR(*sunElevationDeg(at("2024-06-20T20:51:00Z")), 23.44, 0.02);
  EXPECT_FALSE(sunElevationDeg(parseScene(fixedScene(kSunAndRock), kFile)).has_value());
}

TEST(Scene, FullSceneLoadsAndSetTimeMovesTheMoon) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "umbra-scene-test-full.json").string();
  {
    std::ofstream out(path);
    out << R"({
      // comments are allowed
      "name": "Total lunar eclipse of 2015-09-28",
      "time": "2015-09-28T01:45:00Z",
      "bodies": [
        {"preset": "Sun"},
        {"preset": "Earth"},
        {"preset": "Moon", "albedo": 0.12},
        {"name": "Rock", "radius": "10km", "position": [1.0e11, 0, 0], "albedo": 0.1}
      ],
      "camera": {"observer": {"body": "Earth", "latDeg": -10.0, "lonDeg": -30.0, "altM": 0},
                 "target": "Moon", "fovDeg": 0.8},
      "exposure": -5.0,
      "image": {"width": 1280, "height": 720},
      "shadow": {"lutSize": 128}
    })";
  }
  Scene scene = loadScene(path);
  std::remove(path.c_str());

  EXPECT_EQ(scene.path, path);
  EXPECT_EQ(scene.name, "Total lunar eclipse of 2015-09-28");
  EXPECT_TRUE(scene.hasTime);
  EXPECT_EQ(formatUtc(scene.time), "2015-09-28T01:45:00Z");
  ASSERT_EQ(scene.bodies.size(), 4u);
  EXPECT_EQ(scene.exposureEv, -5.0);
  EXPECT_EQ(scene.width, 1280);
  EXPECT_EQ(scene.shadowLutSize, 128);
  EXPECT_EQ(scene.camera.fovDeg, 0.8);
  EXPECT_EQ(scene.camera.targetBody, "Moon");

  const Body& earth = *scene.find("Earth");
  const Body& moon = *scene.find("Moon");
  EXPECT_TRUE(moon.positionFromEphemeris);
  EXPECT_EQ(moon.positionM, heliocentricPositionM("Moon", scene.time));
  EXPECT_EQ(scene.camera.targetM, moon.positionM);
  const double cameraAltitudeM = glm::length(scene.camera.positionM - earth.positionM);
  EXPECT_NEAR(cameraAltitudeM, 6378e3, 25e3);
  EXPECT_NEAR(glm::dot(scene.camera.up, glm::normalize(moon.positionM - scene.camera.positionM)),
              0.0, 1e-12);

  const glm::dvec3 moonBefore = moon.positionM;
  const glm::dvec3 cameraBefore = scene.camera.positionM;
  setTime(scene, addSeconds(scene.time, 3600.0));
  EXPECT_EQ(formatUtc(scene.time), "2015-09-28T02:45:00Z");
  const Body& moonAfter = *scene.find("Moon");
  // Heliocentric speed ~30 km/s: about 1.07e8 m in an hour.
  EXPECT_NEAR(glm::length(moonAfter.positionM - moonBefore), 1.07e8, 0.05e8);
  EXPECT_EQ(scene.camera.targetM, moonAfter.positionM);
  EXPECT_NE(scene.camera.positionM, cameraBefore);
  EXPECT_EQ(scene.find("Rock")->positionM, glm::dvec3(1e11, 0, 0));
}

// ---- the Moon's photometry and albedo map -----------------------------------------------

namespace {

/// Sets UMBRA_MARBLE_DATA_DIR for the scope (the place of the Clementine map).
struct MarbleDataDir {
  explicit MarbleDataDir(const std::string& dir) { ::setenv("UMBRA_MARBLE_DATA_DIR", dir.c_str(), 1); }
  ~MarbleDataDir() { ::unsetenv("UMBRA_MARBLE_DATA_DIR"); }
};
struct StellariumDataDir {
  explicit StellariumDataDir(const std::string& dir) { ::setenv("UMBRA_STELLARIUM_DATA_DIR", dir.c_str(), 1); }
  ~StellariumDataDir() { ::unsetenv("UMBRA_STELLARIUM_DATA_DIR"); }
};

std::filesystem::path freshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("umbra-scene-test-" + std::to_string(::getpid())) / name;
  std::filesystem::create_directories(dir);
  return dir;
}

const std::string kMoonAt = R"({"preset": "Moon", "position": [1e11, 0, 0])";

}  // namespace

// The dusty airless bodies reflect by Hapke's law, the planets by Lambert's; a scene can
// ask for either.
TEST(ScenePhotometry, PresetsAndOverride) {
  const Scene s = parseScene(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + "}"), kFile);
  EXPECT_EQ(s.find("Moon")->photometry.law, umbra::sky::Photometry::Law::Hapke);
  const Scene l = parseScene(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "photometry": "lambert"})"), kFile);
  EXPECT_EQ(l.find("Moon")->photometry.law, umbra::sky::Photometry::Law::Lambert);
  const Scene h = parseScene(fixedScene(kSunAndRock.substr(0, kSunAndRock.size() - 1) + R"(, "photometry": "hapke"})"),
                             kFile);
  EXPECT_EQ(h.find("Rock")->photometry.law, umbra::sky::Photometry::Law::Hapke);
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "photometry": "phong"})")),
            "examples/x.json: bodies[1].photometry: expected \"lambert\" or \"hapke\", got \"phong\"");
}

// The Moon takes the Clementine map when marble-qt-data is installed; without it a
// uniform albedo and a note naming the package, unless the scene asks for the map by name
// (then an error naming the package); "none" and a file of one's own; a missing file.
TEST(ScenePhotometry, AlbedoMapOrItsFallback) {
  const auto without = freshDir("no-marble"), with = freshDir("marble");
  const StellariumDataDir relief(freshDir("no-stellarium").string());  // its note left out below
  std::filesystem::create_directories(with / "maps/moon/clementine");
  std::ofstream(with / "maps/moon/clementine/clementine.jpg") << "x";
  const std::string moonScene = fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + "}");
  {
    const MarbleDataDir d(with.string());
    const Scene s = parseScene(moonScene, kFile);
    EXPECT_EQ(s.find("Moon")->albedoMapPath, (with / "maps/moon/clementine/clementine.jpg").string());
    ASSERT_EQ(s.notes.size(), 1u);
    EXPECT_EQ(s.notes[0].find("Moon: no relief"), 0u) << s.notes[0];
    const Scene none = parseScene(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "albedoMap": "none"})"), kFile);
    EXPECT_EQ(none.find("Moon")->albedoMapPath, "");
  }
  {
    const MarbleDataDir d(without.string());
    const Scene s = parseScene(moonScene, kFile);
    EXPECT_EQ(s.find("Moon")->albedoMapPath, "");
    ASSERT_EQ(s.notes.size(), 2u);
    EXPECT_NE(s.notes[0].find("Moon: uniform albedo"), std::string::npos) << s.notes[0];
    EXPECT_NE(s.notes[0].find("marble-qt-data"), std::string::npos) << s.notes[0];
    const std::string e =
        errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "albedoMap": "clementine"})"));
    EXPECT_EQ(e.rfind("examples/x.json: bodies[1].albedoMap: the 'clementine' map is not installed", 0), 0u) << e;
    EXPECT_NE(e.find("install the Debian package marble-qt-data"), std::string::npos) << e;
  }
  const std::string missing = errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "albedoMap": "maps/m.png"})"));
  EXPECT_EQ(missing, "examples/x.json: bodies[1].albedoMap: no such file: examples/maps/m.png (or a named map: "
                     "clementine, bluemarble, or \"none\")");
  EXPECT_NE(errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "albedoMap": 3})")).find("bodies[1].albedoMap"),
            std::string::npos);
}

// "bluemarble" names the Earth's colour map, a reflectance map (its colour taken as it is);
// the Moon's Clementine map is not one; without marble-qt-data, an error naming it.
TEST(ScenePhotometry, BlueMarbleIsAReflectanceMap) {
  const auto with = freshDir("marble-earth"), without = freshDir("no-marble-earth");
  std::filesystem::create_directories(with / "maps/earth/bluemarble");
  std::ofstream(with / "maps/earth/bluemarble/bluemarble.jpg") << "x";
  const std::string earth = fixedScene(R"({"preset": "Sun"}, {"preset": "Earth", "position": [1e11, 0, 0], )"
                                       R"("albedoMap": "bluemarble"})");
  {
    const MarbleDataDir d(with.string());
    const Scene s = parseScene(earth, kFile);
    EXPECT_EQ(s.find("Earth")->albedoMapPath, (with / "maps/earth/bluemarble/bluemarble.jpg").string());
    EXPECT_TRUE(s.find("Earth")->albedoMapReflectance);
  }
  const MarbleDataDir d(without.string());
  const std::string e = errorFor(earth);
  EXPECT_EQ(e.rfind("examples/x.json: bodies[1].albedoMap: the 'bluemarble' map is not installed", 0), 0u) << e;
  EXPECT_NE(e.find("install the Debian package marble-qt-data"), std::string::npos) << e;
  const Scene none = parseScene(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "albedoMap": "none"})"), kFile);
  EXPECT_FALSE(none.find("Moon")->albedoMapReflectance);
}

// The Moon takes stellarium-data's relief when it is installed; without it no relief and a
// note naming the package, unless the scene names the map (then an error naming the
// package); "none", a file of one's own and its strength ("relief"); bad values.
TEST(ScenePhotometry, NormalMapOrItsFallback) {
  const auto without = freshDir("no-stellarium-2"), with = freshDir("stellarium");
  std::filesystem::create_directories(with / "textures");
  std::ofstream(with / "textures/moon_normals.png") << "x";
  const MarbleDataDir albedo(freshDir("no-marble-2").string());
  const std::string moonScene = fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + "}");
  {
    const StellariumDataDir d(with.string());
    const Scene s = parseScene(moonScene, kFile);
    EXPECT_EQ(s.find("Moon")->normalMapPath, (with / "textures/moon_normals.png").string());
    EXPECT_EQ(s.find("Moon")->reliefStrength, 1.0);
    const Scene none = parseScene(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "normalMap": "none"})"), kFile);
    EXPECT_EQ(none.find("Moon")->normalMapPath, "");
    const Scene half = parseScene(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "relief": 0.5})"), kFile);
    EXPECT_EQ(half.find("Moon")->reliefStrength, 0.5);
  }
  {
    const StellariumDataDir d(without.string());
    const Scene s = parseScene(moonScene, kFile);
    EXPECT_EQ(s.find("Moon")->normalMapPath, "");
    ASSERT_EQ(s.notes.size(), 2u);  // the albedo map's and this one's
    EXPECT_EQ(s.notes[1], "Moon: no relief (the stellarium map is not installed: Debian package stellarium-data)");
    const std::string e = errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "normalMap": "stellarium"})"));
    EXPECT_EQ(e.rfind("examples/x.json: bodies[1].normalMap: the 'stellarium' map is not installed", 0), 0u) << e;
    EXPECT_NE(e.find("install the Debian package stellarium-data"), std::string::npos) << e;
  }
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "normalMap": "n.png"})")),
            "examples/x.json: bodies[1].normalMap: no such file: examples/n.png (or a named map: stellarium, or \"none\")");
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, )" + kMoonAt + R"(, "relief": 5})")),
            "examples/x.json: bodies[1].relief: expected a number in [0, 4], got 5");
}

// The Milky Way behind the stars: stellarium-data's panorama by default when installed,
// a note when not; "none" for none, "stellarium" named without the package an error naming
// it, a file of one's own relative to the scene; no stars, no Milky Way.
TEST(SceneStars, MilkyWayOrItsFallback) {
  const auto without = freshDir("no-stellarium-3"), with = freshDir("stellarium-3");
  std::filesystem::create_directories(with / "textures");
  std::ofstream(with / "textures/milkyway.png") << "x";
  const std::string sky = R"({"time": "2024-01-15T21:30:00Z", "bodies": [{"preset": "Sun"}, {"preset": "Earth"}],
    "camera": {"position": [1e9, 0, 0], "target": [0, 0, 0]})";
  {
    const StellariumDataDir d(with.string());
    const Scene s = parseScene(sky + "}", kFile);
    if (s.stars) { EXPECT_EQ(s.stars->milkyWayPath, (with / "textures/milkyway.png").string()); }
    const Scene none = parseScene(sky + R"(, "stars": {"milkyWay": "none"}})", kFile);
    if (none.stars) { EXPECT_EQ(none.stars->milkyWayPath, ""); }
    EXPECT_FALSE(parseScene(sky + R"(, "stars": false})", kFile).stars.has_value());
  }
  {
    const StellariumDataDir d(without.string());
    const Scene s = parseScene(sky + "}", kFile);
    if (s.stars) {
      EXPECT_EQ(s.stars->milkyWayPath, "");
      EXPECT_NE(std::find(s.notes.begin(), s.notes.end(),
                          "stars: no Milky Way (the stellarium map is not installed: Debian package stellarium-data)"),
                s.notes.end());
    }
    const std::string e = errorFor(sky + R"(, "stars": {"milkyWay": "stellarium"}})");
    EXPECT_EQ(e.rfind("examples/x.json: stars.milkyWay: the 'stellarium' map is not installed", 0), 0u) << e;
    EXPECT_NE(e.find("install the Debian package stellarium-data"), std::string::npos) << e;
  }
  EXPECT_EQ(errorFor(sky + R"(, "stars": {"milkyWay": "mw.png"}})"),
            "examples/x.json: stars.milkyWay: no such file: examples/mw.png (or a named map: stellarium, or \"none\")");
}

// ---- hostile files: nesting and duplicate keys ----------------------------------------

// A document nested 100 000 deep is refused while it is read (it used to overflow the
// stack when the error printed it), with one line naming where.
TEST(SceneErrors, DeeplyNestedJsonIsOneLine) {
  const std::string deep = R"({"bodies": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
  const std::string message = errorFor(deep);
  EXPECT_EQ(message.rfind("examples/x.json: nested more than 64 levels deep (at bodies[0][0]", 0), 0u) << message;
  EXPECT_LT(message.size(), 160u);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

// A key given twice is an error naming it (JSON would keep the last one silently).
TEST(SceneErrors, DuplicateKeyIsNamed) {
  EXPECT_EQ(errorFor(fixedScene(R"({"preset": "Sun"}, {"preset": "Moon", "position": [1e11, 0, 0], "albedo": 0.1,
                                  "albedo": 0.2})")),
            "examples/x.json: bodies[1].albedo: duplicate key");
  EXPECT_EQ(errorFor(R"({"name": "a", "name": "b"})"), "examples/x.json: name: duplicate key");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, R"(, "image": {"width": 64, "height": 64, "width": 32})")),
            "examples/x.json: image.width: duplicate key");
}

// "stars": false draws none; an object names a catalogue (relative to the scene) and a
// limiting magnitude; a named file that is not there, a bad magnitude, an unknown key and
// a scene without a time are errors naming the field.
TEST(SceneStars, CatalogueAndLimitingMagnitude) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("umbra-scene-stars-" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(dir);
  const std::string catalogue = dir + "/few.dat";
  std::ofstream(catalogue) << "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, Sirius\n";
  const std::string timed = R"(, "time": "2024-03-20T22:00:00Z")";
  EXPECT_FALSE(parseScene(fixedScene(kSunAndRock, timed + R"(, "stars": false)"), kFile).stars);
  const Scene s = parseScene(fixedScene(kSunAndRock, timed + R"(, "stars": {"catalogue": "few.dat", "limitingMagnitude": 4.5})"),
                             dir + "/scene.json");
  ASSERT_TRUE(s.stars);
  EXPECT_EQ(s.stars->cataloguePath, catalogue);
  EXPECT_EQ(s.stars->limitingMagnitude, 4.5);

  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, timed + R"(, "stars": {"catalogue": "none.dat"})")),
            "examples/x.json: stars.catalogue: no such file: examples/none.dat");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, timed + R"(, "stars": {"limitingMagnitude": "bright"})")),
            "examples/x.json: stars.limitingMagnitude: expected a V magnitude in [-30, 30], got \"bright\"");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, timed + R"(, "stars": {"limit": 6})")).rfind(
                "examples/x.json: stars.limit: unknown key", 0),
            0u);
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, timed + R"(, "stars": {"scintillation": 2})")),
            "examples/x.json: stars.scintillation: expected the spread of the log of a star's light at the zenith, in "
            "[0, 1], got 2");
  EXPECT_EQ(parseScene(fixedScene(kSunAndRock, timed + R"(, "stars": {"catalogue": "few.dat", "scintillation": 0.2, "seed": 9})"),
                       dir + "/scene.json").stars->seed, 9u);
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, timed + R"(, "stars": 6)")),
            "examples/x.json: stars: expected true, false or an object, got 6");
  EXPECT_EQ(errorFor(fixedScene(kSunAndRock, R"(, "stars": true)")),
            "examples/x.json: time: required: the stars' places are for a date");
  std::filesystem::remove_all(dir);
}

// A body's cloud layers: a single object or a list, lengths with units, the defaults, the
// wind; the file's time kept for their drift when the scene moves; errors name the field.
TEST(SceneClouds, LayersParseAndNameTheirFields) {
  const std::string earth =
      R"({"preset": "Sun"}, {"name": "Air", "radius": "6371 km", "position": [1.5e11, 0, 0], "atmosphere": "earth", )";
  const Scene one = parseScene(fixedScene(earth + R"("clouds": {"altitude": "1.5 km", "wind": [6, -2]}})"), kFile);
  ASSERT_EQ(one.bodies[1].clouds.size(), 1u);
  const umbra::sky::CloudLayer& l = one.bodies[1].clouds[0];
  EXPECT_DOUBLE_EQ(l.altitudeM, 1500.0);
  EXPECT_DOUBLE_EQ(l.coverage, 0.5);
  EXPECT_DOUBLE_EQ(l.opticalDepth, 10.0);
  EXPECT_DOUBLE_EQ(l.featureSizeM, 20.0e3);
  EXPECT_DOUBLE_EQ(l.windEastMs, 6.0);
  EXPECT_DOUBLE_EQ(l.windNorthMs, -2.0);
  const Scene two = parseScene(
      fixedScene(earth + R"("clouds": [{"altitude": 0, "coverage": 1, "opticalDepth": 1000, "seed": 4}, {"featureSize": "1 km"}]})"),
      kFile);
  ASSERT_EQ(two.bodies[1].clouds.size(), 2u);
  EXPECT_EQ(two.bodies[1].clouds[0].seed, 4u);
  EXPECT_DOUBLE_EQ(two.bodies[1].clouds[1].featureSizeM, 1000.0);

  EXPECT_EQ(errorFor(fixedScene(earth + R"("clouds": [{"coverage": 1.5}]})")),
            "examples/x.json: bodies[1].clouds[0].coverage: expected a fraction in [0, 1], got 1.5");
  EXPECT_NE(errorFor(fixedScene(earth + R"("clouds": {"featureSize": "10 m"}})")).find("bodies[1].clouds.featureSize"),
            std::string::npos);
  EXPECT_NE(errorFor(fixedScene(earth + R"("clouds": [{"wind": 3}]})")).find("bodies[1].clouds[0].wind: expected [east, north]"),
            std::string::npos);
  EXPECT_NE(errorFor(fixedScene(earth + R"("clouds": [{"altitde": 3}]})")).find("bodies[1].clouds[0].altitde: unknown key"),
            std::string::npos);
}

// A scene's time as an eclipse's instant: the catalogue's contact plus the offset; errors
// name the field and what is missing.
TEST(Scene, TimeFromAnEclipseContact) {
  const auto sceneAt = [](const std::string& time) {
    return fixedScene(kSunAndRock, R"(, "time": )" + time);
  };
  const Scene s = parseScene(sceneAt(R"({"eclipse": "2015-09-28", "at": "U2+10min"})"), kFile);
  ASSERT_TRUE(s.hasTime);
  const double u2 = eclipseInstantUt("2015-09-28", "U2");
  EXPECT_NEAR((s.time.jd1 + s.time.jd2 - u2) * 86400.0, 600.0, 1e-3);
  EXPECT_EQ(formatUtc(s.time), "2015-09-28T02:21:11Z");  // U2 at 02:11:11 UT (NASA: 02:11:11)
  const Scene g = parseScene(sceneAt(R"({"eclipse": "2017-08-21", "at": "greatest"})"), kFile);
  EXPECT_EQ(formatUtc(g.time).substr(0, 16), "2017-08-21T18:25");
  EXPECT_NE(errorFor(sceneAt(R"({"eclipse": "2017-08-07", "at": "U2"})")).find("time: the partial lunar eclipse of 2017-08-07 has no U2"),
            std::string::npos);
  EXPECT_NE(errorFor(sceneAt(R"({"eclipse": "2017-08-08", "at": "U1"})")).find("time: no eclipse on 2017-08-08"),
            std::string::npos);
  EXPECT_NE(errorFor(sceneAt(R"({"eclipse": "2015-09-28"})")).find("time: an eclipse's instant needs both"),
            std::string::npos);
  EXPECT_NE(errorFor(sceneAt(R"({"eclipse": "2015-09-28", "at": "U5"})")).find("time: eclipse instant 'U5'"),
            std::string::npos);
  EXPECT_NE(errorFor(sceneAt(R"({"eclipse": "2015-09-28", "at": "U2", "when": 1})")).find("time.when: unknown key"),
            std::string::npos);
}
