// Bad input to the umbra CLI: a clear one-line message, a non-zero exit, no output file
// (not even a temporary one). One test per case.
#include "CliRunner.hpp"

#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace umbra::test;

namespace {

// Runs umbra expecting failure; checks the message and that `dir` gained no file.
void expectFailure(const TempDir& dir, const std::vector<std::string>& args, const std::string& message) {
  const int filesBefore = dir.fileCount();
  const RunResult r = run(UMBRA_EXE, args, {"UMBRA_CACHE_DIR=" + dir.path.string() + "/cache"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find(message), std::string::npos) << "stderr: " << r.err;
  EXPECT_EQ(r.err.find("umbra: error:"), 0u) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line expected: " << r.err;
  EXPECT_EQ(dir.fileCount(), filesBefore) << "an output or temporary file was left";
}

std::vector<std::string> profileArgs(const TempDir& dir, std::vector<std::string> extra) {
  std::vector<std::string> a{"profile", "shadow", "--no-atmosphere", "--distance", "384400km", "--csv", dir / "p.csv"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

void writeLut(const TempDir& dir, const std::string& name) {
  ASSERT_EQ(run(UMBRA_EXE, {"precompute", "shadow", "--occluder", "Earth", "--size", "32", "--no-cache", "--output",
                            dir / name}).exitCode, 0);
}

} // namespace

TEST(BadInput, UnknownBody) {
  TempDir dir;
  expectFailure(dir, profileArgs(dir, {"--occluder", "Pluto"}), "unknown body 'Pluto' (known: Sun, Earth, Moon");
}

TEST(BadInput, SunAsOccluder) {
  TempDir dir;
  expectFailure(dir, {"precompute", "shadow", "--occluder", "sun", "--output", dir / "x.exr"}, "the Sun cannot occlude");
}

TEST(BadInput, NegativeRadius) {
  TempDir dir;
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--occluder-radius", "-5km"}),
                "--occluder-radius: expected a positive length, got -5km");
}

TEST(BadInput, BadLengthUnit) {
  TempDir dir;
  expectFailure(dir, {"profile", "shadow", "--occluder", "Earth", "--distance", "3 parsec", "--csv", dir / "p.csv"},
                "--distance: invalid length '3 parsec'");
}

TEST(BadInput, MissingOption) {
  TempDir dir;
  expectFailure(dir, {"profile", "shadow", "--occluder", "Earth", "--csv", dir / "p.csv"}, "give --occluder and --distance, or --scene");
}

TEST(BadInput, MissingTableFile) {
  TempDir dir;
  expectFailure(dir, {"inspect", dir / "missing.exr"}, "missing.exr: cannot open: No such file or directory");
}

TEST(BadInput, UnwritableOutputDirectory) {
  TempDir dir;
  expectFailure(dir, {"precompute", "shadow", "--occluder", "Earth", "--output", dir / "no/such/dir/lut.exr"},
                "does not exist");
}

TEST(BadInput, OutputIsADirectory) {
  TempDir dir;
  std::filesystem::create_directory(dir.path / "taken.csv");
  expectFailure(dir, {"profile", "shadow", "--occluder", "Earth", "--distance", "1e9", "--csv", dir / "taken.csv"},
                "taken.csv: is a directory");
}

TEST(BadInput, WrongOutputType) {
  TempDir dir;
  expectFailure(dir, {"precompute", "shadow", "--occluder", "Earth", "--output", dir / "lut.png"},
                "lut.png: unsupported file type (expected .exr)");
}

TEST(BadInput, TruncatedLut) {
  TempDir dir;
  writeLut(dir, "lut.exr");
  std::filesystem::resize_file(dir.path / "lut.exr", std::filesystem::file_size(dir.path / "lut.exr") / 2);
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--lut", dir / "lut.exr"}), "lut.exr: ");
  expectFailure(dir, {"inspect", dir / "lut.exr"}, "lut.exr: ");
}

TEST(BadInput, LutWithWrongChannels) {
  TempDir dir;
  umbra::tables::Table t;
  t.width = t.height = 4;
  t.channels = {"Y"};
  t.data.assign(16, 0.5f);
  t.parameters = {{"kind", "eclipse-shadow-airless"}};
  umbra::tables::writeExr(dir / "y.exr", t);
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--lut", dir / "y.exr"}), "missing channels 'R', 'G', 'B' (has: Y)");
}

TEST(BadInput, RgbExrThatIsNotAShadowLut) {
  TempDir dir;
  umbra::tables::Table t;
  t.width = t.height = 4;
  t.channels = {"R", "G", "B"};
  t.data.assign(48, 0.5f);
  umbra::tables::writeExr(dir / "photo.exr", t);
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--lut", dir / "photo.exr"}), "photo.exr: not a shadow LuT");
}

namespace {
std::string writeScene(const TempDir& dir, const std::string& name, const std::string& json) {
  std::ofstream(dir.path / name) << json;
  return dir / name;
}
const char* kSceneHead = R"({"name": "t", "time": "2015-09-28T01:45:00Z", "bodies": [{"preset": "Sun"}, )";
const char* kSceneTail = R"(], "camera": {"position": [1.5e11, 0, 0], "target": [0, 0, 0], "fovDeg": 1}})";
} // namespace

TEST(BadInput, MalformedSceneJson) {
  TempDir dir;
  const std::string scene = writeScene(dir, "bad.json", "{\"bodies\": [\n  {\"preset\": \"Sun\"},\n  oops\n]}");
  expectFailure(dir, {"render", scene, "--output", dir / "x.png"}, "bad.json: invalid JSON at line 3, column");
}

TEST(BadInput, UnknownBodyInScene) {
  TempDir dir;
  const std::string scene = writeScene(dir, "pluto.json", std::string(kSceneHead) + R"({"preset": "Pluto"})" + kSceneTail);
  expectFailure(dir, {"render", scene, "--output", dir / "x.png"}, "pluto.json: bodies[1].preset: unknown body 'Pluto'");
}

TEST(BadInput, NegativeRadiusInScene) {
  TempDir dir;
  const std::string scene = writeScene(dir, "neg.json", std::string(kSceneHead) +
      R"({"name": "Rock", "radius": -5, "position": [1.5e11, 1e9, 0]})" + kSceneTail);
  expectFailure(dir, {"render", scene, "--output", dir / "x.png"}, "neg.json: bodies[1].radius: expected a length from 1 m to 1e12 m");
}

TEST(BadInput, MissingSceneFile) {
  TempDir dir;
  expectFailure(dir, {"render", dir / "nowhere.json", "--output", dir / "x.png"},
                "nowhere.json: cannot open file: No such file or directory");
}

TEST(BadInput, UnwritableRenderOutput) {
  TempDir dir;
  expectFailure(dir, {"render", UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json", "--output",
                      dir / "missing-dir/x.png"}, "does not exist");
}

TEST(BadInput, BadRenderSizeAndTime) {
  TempDir dir;
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json";
  expectFailure(dir, {"render", scene, "--size", "12x", "--output", dir / "x.png"}, "--size: expected WIDTHxHEIGHT");
  expectFailure(dir, {"render", scene, "--time", "yesterday", "--output", dir / "x.png"}, "--time: ");
}

TEST(BadInput, ProfileNeedsABodyOrAScene) {
  TempDir dir;
  expectFailure(dir, {"profile", "shadow", "--csv", dir / "p.csv"}, "give --occluder and --distance, or --scene");
  expectFailure(dir, {"profile", "shadow", "--occluder", "Earth", "--scene", UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json",
                      "--csv", dir / "p.csv"}, "excludes");
}

TEST(BadInput, UnknownAtmospherePreset) {
  TempDir dir;
  expectFailure(dir, {"atmosphere", "refraction", "--preset", "pluto", "--csv", dir / "r.csv"},
                "unknown atmosphere preset 'pluto' (known: earth, earth-2015-calbuco, earth-bruneton, earth-maritime, earth-turbid, earth-volcanic, mars)");
}

TEST(BadInput, BadZenithRange) {
  TempDir dir;
  expectFailure(dir, {"atmosphere", "refraction", "--preset", "earth", "--zenith-deg", "90:0:1", "--csv", dir / "r.csv"},
                "--zenith-deg: expected 0 <= FROM <= TO <= 180");
  expectFailure(dir, {"atmosphere", "refraction", "--preset", "earth", "--zenith-deg", "0-90", "--csv", dir / "r.csv"},
                "--zenith-deg: expected FROM:TO:STEP");
}

TEST(BadInput, MalformedAtmosphereFile) {
  TempDir dir;
  std::ofstream(dir.path / "bad.json") << "{\"name\": \"x\",\n \"bottomRadius\": }";
  expectFailure(dir, {"atmosphere", "refraction", "--config", dir / "bad.json", "--csv", dir / "r.csv"}, "bad.json: ");
}

// ---- hostile input: non-finite and absurd numbers, deep and duplicated JSON ------------

// Number options refuse NaN, infinities and empty values, naming the option (CLI11 let NaN
// through its ranges: --limb-darkening nan ended in std::terminate from a parallel loop).
TEST(BadInput, NonFiniteAndEmptyNumbers) {
  TempDir dir;
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--limb-darkening", "nan"}),
                "--limb-darkening: expected a finite number, got 'nan'");
  expectFailure(dir, {"atmosphere", "sky", "--preset", "earth", "--sun-zenith-deg", "", "--csv", dir / "s.csv"},
                "--sun-zenith-deg: expected a number, got an empty value");
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--samples", ""}), "--samples: ");  // its range says no
  expectFailure(dir, {"render", UMBRA_SOURCE_DIR "/examples/scenes/full-moon-2026-10-26.json", "--glare", "nan",
                      "--output", dir / "x.png"},
                "--glare: expected a finite number, got 'nan'");
  expectFailure(dir, {"atmosphere", "sky", "--preset", "earth", "--sun-zenith-deg", "-inf", "--csv", dir / "s.csv"},
                "--sun-zenith-deg: expected a finite number, got '-inf'");
}

// Absurd but finite lengths: a range naming the option, not a crash or a NaN profile.
TEST(BadInput, LengthsOutsideTheirPhysicalRange) {
  TempDir dir;
  expectFailure(dir, {"profile", "shadow", "--no-atmosphere", "--occluder", "Earth", "--distance", "1e-300m", "--csv",
                      dir / "p.csv"},
                "--distance: expected a length from 6.37101e+06 m to 1e+15 m, got 1e-300m");
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--sun-distance", "1e308km"}),
                "--sun-distance: expected a length from 7.02713e+08 m to 1e+15 m, got 1e308km");
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--occluder-radius", "1e308km"}),
                "--occluder-radius: expected a length from 1 m to 1e+12 m, got 1e308km");
  expectFailure(dir, profileArgs(dir, {"--occluder", "Earth", "--max-offset", "1e308km"}),
                "--max-offset: expected a length from 1 m to 1e+15 m, got 1e308km");
  expectFailure(dir, {"terrain", "shadow", "--synthetic", "1", "--size", "16", "--sun-elevation-deg", "5",
                      "--sun-azimuth-deg", "10", "--body-radius", "1e308m", "--output", dir / "t.exr"},
                "--body-radius: expected a length from 1 m to 1e+12 m, got 1e308m");
}

// Scene and atmosphere files nested 100 000 deep (a stack overflow before), a key given
// twice, an atmosphere 1e308 m high (a hang in the refraction before): one line each.
TEST(BadInput, HostileFiles) {
  TempDir dir;
  {
    std::ofstream(dir / "deep.json") << "{\"bodies\": " << std::string(100000, '[') << std::string(100000, ']') << "}";
  }
  expectFailure(dir, {"render", dir / "deep.json", "--output", dir / "x.png"}, "nested more than 64 levels deep");
  {
    std::ofstream(dir / "twice.json") << R"({"time": "2015-09-28T02:00:00Z", "bodies": [{"preset": "Sun"},
      {"preset": "Moon", "albedo": 0.1, "albedo": 0.2}], "camera": {"position": [0, 0, 0], "target": "Moon"}})";
  }
  expectFailure(dir, {"render", dir / "twice.json", "--output", dir / "x.png"}, "bodies[1].albedo: duplicate key");
  {
    std::ofstream(dir / "tall.json") << R"({"extends": "earth", "name": "tall", "topRadiusM": 1e308})";
  }
  expectFailure(dir, {"atmosphere", "refraction", "--config", dir / "tall.json", "--csv", dir / "r.csv"},
                "topRadiusM: expected a radius from 1 m to 1e12 m, got 1e+308");
}

// Raw library messages no more: a number too large for JSON, an endless file, a directory
// for a file, a sample count that would not fit in memory.
TEST(BadInput, LibraryMessagesBecomeOurs) {
  TempDir dir;
  {
    std::ofstream(dir / "big.json") << R"({"time": "2015-09-28T02:00:00Z", "bodies": [{"preset": "Sun"},
      {"preset": "Moon", "albedo": 1e999}], "camera": {"position": [0, 0, 0], "target": "Moon"}})";
  }
  expectFailure(dir, {"render", dir / "big.json", "--output", dir / "x.png"}, "big.json: number overflow parsing '1e999'");
  expectFailure(dir, {"render", "/dev/zero", "--output", dir / "x.png"},
                "/dev/zero: larger than 16 MiB: not a scene or atmosphere file");
  std::filesystem::create_directory(dir / "a-directory");
  expectFailure(dir, {"atmosphere", "refraction", "--config", dir / "a-directory", "--csv", dir / "r.csv"},
                "a-directory: is a directory, not a file");
  expectFailure(dir, {"atmosphere", "sky", "--preset", "earth", "--sun-zenith-deg", "30", "--zenith-step", "1e-9",
                      "--csv", dir / "s.csv"},
                "--zenith-step, --azimuth-step: 1710000000019 directions, more than 1000000");
}
