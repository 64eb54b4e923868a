// `umbra precompute eclipse` and `umbra profile shadow --atmosphere`: the files and their
// layout, the colour of Earth's umbra and of Mars' at Phobos, the Figure 12 plot, and
// one-line errors without output for bad input. Small tables (--draft-tables).
#include "CliRunner.hpp"

#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>

using namespace umbra::test;

namespace {

std::vector<std::array<double, 5>> readRows(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line, "offset_km,r,g,b,luminance");
  std::vector<std::array<double, 5>> rows;
  while (std::getline(f, line)) {
    std::array<double, 5> row{};
    std::stringstream s(line);
    char comma;
    s >> row[0] >> comma >> row[1] >> comma >> row[2] >> comma >> row[3] >> comma >> row[4];
    rows.push_back(row);
  }
  return rows;
}

const std::vector<std::string> kSmall = {"--draft-tables", "--orders", "2", "--limb-size", "32", "--scattering-cells", "8"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

} // namespace

TEST(EclipseCli, PrecomputeWritesTheShadowAndLimbLuminanceTables) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE,
                          with({"precompute", "eclipse", "--occluder", "earth", "--atmosphere", "earth", "--size", "16",
                                "--limb-lut-size", "8", "--layers", "2", "--output", dir / "out"},
                               kSmall),
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const umbra::tables::Table shadow = umbra::tables::readExr(dir / "out/eclipse-shadow-atmosphere.exr", {"R", "G", "B"});
  EXPECT_EQ(shadow.width, 16);
  EXPECT_EQ(shadow.height, 16);
  EXPECT_EQ(shadow.parameters.at("atmosphere"), "earth");
  for (float x : shadow.data) {
    ASSERT_TRUE(std::isfinite(x));
    ASSERT_GE(x, 0.0f);
    ASSERT_LE(x, 1.0f + 1e-5f);
  }
  // Bottom row (v near 0), u beyond the umbra's tip's half: umbra or antumbra, red first.
  const int i = 6;  // u = 0.41: about 10^6 km
  EXPECT_GT(shadow.at(i, 0, 0), shadow.at(i, 0, 2));
  const umbra::tables::Table limb = umbra::tables::readExr(dir / "out/eclipse-limb-luminance.exr", {"R", "G", "B"});
  EXPECT_EQ(limb.width, 8);
  EXPECT_EQ(limb.height, 8 * 8 * 2);  // v x (columns x layers), slices stacked
  EXPECT_EQ(limb.parameters.at("size"), "8x8x8x2");
  for (float x : limb.data) ASSERT_TRUE(std::isfinite(x) && x >= 0.0f);
}

// --distance-range: both tables over the same u and v ranges (Phobos' distances from Mars:
// u ~ 0.008, v split at the umbra's edge), recorded in their headers.
TEST(EclipseCli, PrecomputeDistanceRangeRangesBothTables) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE,
                          with({"precompute", "eclipse", "--occluder", "mars", "--atmosphere", "mars", "--size", "8",
                                "--limb-lut-size", "4", "--distance-range", "9365km:9387km", "--output", dir / "out"},
                               kSmall),
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const umbra::tables::Table shadow = umbra::tables::readExr(dir / "out/eclipse-shadow-atmosphere.exr", {"R", "G", "B"});
  const umbra::tables::Table limb = umbra::tables::readExr(dir / "out/eclipse-limb-luminance.exr", {"R", "G", "B"});
  for (const char* key : {"uMin", "uMax", "vMin", "vMax", "vLowFraction"}) {
    ASSERT_TRUE(limb.parameters.count(key)) << key;
    EXPECT_EQ(limb.parameters.at(key), shadow.parameters.at(key)) << key;
  }
  EXPECT_NEAR(std::stod(limb.parameters.at("uMin")), 0.0083, 0.0002);
  EXPECT_LT(std::stod(limb.parameters.at("uMax")) - std::stod(limb.parameters.at("uMin")), 1e-4);
  EXPECT_EQ(limb.parameters.at("vLowFraction"), "0.25");
  for (float x : limb.data) ASSERT_TRUE(std::isfinite(x) && x >= 0.0f);
}

TEST(EclipseCli, EarthProfileAtTheMoonIsRedWithAFigure12Plot) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE,
                          with({"profile", "shadow", "--occluder", "earth", "--atmosphere", "earth", "--size", "48",
                                "--distance", "384400km", "--samples", "21", "--csv", dir / "p.csv", "--plot",
                                dir / "p.svg"},
                               kSmall),
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = readRows(dir / "p.csv");
  ASSERT_EQ(rows.size(), 21u);
  const auto& centre = rows[0];
  EXPECT_GT(centre[1], centre[2]);
  EXPECT_GT(centre[2], centre[3]);
  EXPECT_GT(centre[1], 1e-6);
  EXPECT_LT(centre[1], 1e-2);
  EXPECT_GT(rows.back()[4], 0.99);  // 1.25 x the penumbra's radius: sunlit
  const std::string svg = readAll(dir / "p.svg");
  EXPECT_NE(svg.find(">umbra<"), std::string::npos);
  EXPECT_NE(svg.find(">penumbra<"), std::string::npos);
  EXPECT_NE(svg.find(">1e-05<"), std::string::npos);  // log axis down to the blue umbra
}

// The atmosphere tables come through vtkAtmosphereTablesSource's cache: a second run with
// another LuT size computes a new LuT but stores no atmosphere table again (a store writes
// a temporary file and renames it: a new inode; a load only touches the time, which the
// cache's LRU cap reads as a use).
TEST(EclipseCli, PrecomputeEclipseTakesTheAtmosphereTablesFromTheirCache) {
  TempDir dir;
  auto atmosphereTables = [&] {
    std::map<std::string, ino_t> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir / "cache"))
      if (e.is_regular_file() && e.path().filename().string().rfind("atmosphere-", 0) == 0) {
        struct stat st {};
        EXPECT_EQ(::stat(e.path().c_str(), &st), 0) << e.path();
        files[e.path().string()] = st.st_ino;
      }
    return files;
  };
  std::map<std::string, ino_t> first;
  for (const std::string size : {"8", "12"}) {
    const RunResult r = run(UMBRA_EXE,
                            with({"precompute", "eclipse", "--occluder", "earth", "--atmosphere", "earth", "--size", size,
                                  "--limb-lut-size", "8", "--layers", "2", "--output", dir / ("out" + size)},
                                 kSmall),
                            {"UMBRA_CACHE_DIR=" + dir / "cache"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    if (first.empty()) {
      first = atmosphereTables();
      auto has = [&](const std::string& kind) {
        return std::any_of(first.begin(), first.end(),
                           [&](const auto& f) { return f.first.find("atmosphere-" + kind) != std::string::npos; });
      };
      EXPECT_TRUE(has("multiple-scattering") && has("transmittance"));
      // Of the refraction table the LuTs read two rows, traced with the limb profile: the
      // whole table is neither made nor cached.
      EXPECT_FALSE(has("refraction"));
    } else {
      EXPECT_EQ(atmosphereTables(), first);  // none rewritten
    }
  }
  const auto shadow = umbra::tables::readExr(dir / "out12/eclipse-shadow-atmosphere.exr", {"R", "G", "B"});
  EXPECT_EQ(shadow.width, 12);
  EXPECT_NE(shadow.parameters.at("atmosphereTables").find("input:"), std::string::npos);
}

// Phobos lies in the first texels of the LuT's u axis, so its profile is computed directly
// (--exact): red over blue in the umbra, as from the LuT at the axis. The umbra's centre at
// Phobos sees only sunlit air high on the far side of Mars' limb through the limb: ~1e-9
// of I_sun (Precompute.MarsLimbFromPhobosAndDeimosInTheUmbraMatchesBruteForce checks those
// rays against brute force). 32 nu cells are the eclipse commands' default for Mars (the
// dust's forward peak; docs/eclipse-shadows.md): this runs without --scattering-nu.
TEST(EclipseCli, MarsProfileAtPhobosIsRedderThanBlue) {
  TempDir dir;
  for (const std::string mode : {"--exact", "--log"}) {
    const RunResult r = run(UMBRA_EXE,
                            with({"profile", "shadow", "--occluder", "mars", "--atmosphere", "mars", "--size", "32",
                                  "--distance", "9376km", "--samples", "5", "--csv",
                                  dir / "p.csv", mode},
                                 kSmall),
                            {"UMBRA_CACHE_DIR=" + dir / "cache"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = readRows(dir / "p.csv");
    ASSERT_EQ(rows.size(), 5u);
    EXPECT_GT(rows[0][1], 1.05 * rows[0][3]) << mode;
    EXPECT_GT(rows[0][1], rows[0][2]) << mode;
    EXPECT_GT(rows[0][2], rows[0][3]) << mode;
    EXPECT_LT(rows[0][1], 1e-2) << mode;
    EXPECT_GT(rows[0][1], 1e-10) << mode;
  }
}

TEST(EclipseCli, BadInputIsOneLineAndWritesNothing) {
  TempDir dir;
  const std::vector<std::vector<std::string>> cases = {
      {"precompute", "eclipse", "--occluder", "earth", "--atmosphere", "nosuch", "--output", dir / "a"},
      {"precompute", "eclipse", "--occluder", "earth", "--output", dir / "b"},
      {"precompute", "eclipse", "--occluder", "earth", "--atmosphere", "earth", "--limb-size", "4", "--layers", "8",
       "--output", dir / "c"},
      {"precompute", "eclipse", "--occluder", "earth", "--atmosphere", "earth", "--output", dir / "no/such/dir"},
      {"profile", "shadow", "--occluder", "earth", "--atmosphere", "nosuch", "--distance", "384400km", "--csv",
       dir / "d.csv"},
      {"profile", "shadow", "--occluder", "earth", "--atmosphere", "earth", "--no-atmosphere", "--distance",
       "384400km", "--csv", dir / "e.csv"},
  };
  for (const auto& args : cases) {
    const RunResult r = run(UMBRA_EXE, args, {"UMBRA_CACHE_DIR=" + dir / "cache"});
    EXPECT_NE(r.exitCode, 0) << args[5];
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(dir.fileCount(), 0);
}
