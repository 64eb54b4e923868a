// `umbra terrain shadow`: the output holds the library's visible fraction (north up),
// GeoTIFF input matches the same heights given directly, --time puts the Sun where the
// lunar south pole sees it, and bad input gives one-line errors and no file.
// `umbra terrain lighting`: a flat plain follows the Sun's elevation; the extremes.
#include "CliRunner.hpp"
#include "GeoTiffSupport.hpp"

#include "CraterField.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"
#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

using namespace umbra::test;
using namespace umbra;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

terrain::HeightField field(int size, int seed) {
  terrain::CraterFieldOptions o;
  o.size = size;
  o.seed = seed;
  return terrain::makeCraterField(o);
}

double printed(const std::string& out, const std::string& what) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(out, m, std::regex(what + " ([-0-9.]+)"))) << out;
  return m.empty() ? NAN : std::stod(m[1]);
}

} // namespace

TEST(TerrainCli, ExrHoldsTheLibrarysFractionNorthUp) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"terrain", "shadow", "--synthetic", "4", "--size", "48", "--sun-elevation-deg",
                                      "2", "--sun-azimuth-deg", "300", "--output", dir / "s.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const tables::Table t = tables::readExr(dir / "s.exr");
  ASSERT_EQ(t.width, 48);
  ASSERT_EQ(t.height, 48);
  EXPECT_EQ(t.parameters.at("method"), "dp");
  const terrain::HeightField f = field(48, 4);
  const terrain::MaximumMipmap mip(f);
  terrain::SunDisc sun;
  sun.direction = terrain::sunDirectionFromElevationAzimuth(2.0 * kDeg, 300.0 * kDeg);
  sun.angularRadiusRad = std::stod(t.parameters.at("sunAngularRadiusRad"));  // the Moon's mean distance
  EXPECT_NEAR(sun.angularRadiusRad, 0.2666 * kDeg, 0.001 * kDeg);
  double sum = 0.0;
  for (int j = 0; j < 48; j += 5)
    for (int i = 0; i < 48; i += 3) {
      const double v = terrain::visibleFraction(f, mip, i, j, sun, {});
      EXPECT_NEAR(t.at(i, 47 - j, 0), v, 1e-6) << i << "," << j;
      sum += v;
    }
  EXPECT_GT(sum, 1.0);
}

TEST(TerrainCli, GeoTiffInputMatchesTheSameHeightsAndHandlesNoData) {
  TempDir dir;
  const terrain::HeightField f = field(40, 8);
  writeGeoTiff(dir / "dem.tif", f, 100e3);
  const std::vector<std::string> sunArgs = {"--sun-elevation-deg", "1.2", "--sun-azimuth-deg", "75"};
  auto args = [&](std::vector<std::string> a) {
    a.insert(a.begin(), {"terrain", "shadow"});
    a.insert(a.end(), sunArgs.begin(), sunArgs.end());
    return a;
  };
  RunResult r = run(UMBRA_EXE, args({"--dem", dir / "dem.tif", "--output", dir / "dem.exr"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // The raster's centre, 100 km from the pole along x: stereographic rho = 2 R tan(colatitude / 2).
  EXPECT_NEAR(printed(r.out, "\\(lat"), -90.0 + 2.0 * std::atan(100.0 / (2.0 * 1737.4)) / kDeg, 1e-6) << r.out;
  EXPECT_NEAR(printed(r.out, "lon"), 90.0, 1e-6) << r.out;
  r = run(UMBRA_EXE, args({"--synthetic", "8", "--size", "40", "--output", dir / "syn.exr"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const tables::Table a = tables::readExr(dir / "dem.exr"), b = tables::readExr(dir / "syn.exr");
  ASSERT_EQ(a.data.size(), b.data.size());
  for (std::size_t k = 0; k < a.data.size(); ++k) ASSERT_NEAR(a.data[k], b.data[k], 1e-6) << k;

  // No-data cells (GDAL's no-data value): finite output everywhere.
  writeGeoTiff(dir / "holes.tif", f, 0.0, {0, 41, 42, 43, 500, 1599});
  r = run(UMBRA_EXE, args({"--dem", dir / "holes.tif", "--method", "uniform", "--output", dir / "holes.exr"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (float v : tables::readExr(dir / "holes.exr").data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
}

// GDAL (a hundred-odd libraries, ~33 MiB resident) is loaded by the commands that read a
// DEM only, from its module beside `umbra` (app/cli/DemModule.hpp); the loader's trace
// (LD_DEBUG=files) names each library loaded.
TEST(TerrainCli, GdalIsLoadedOnlyToReadADem) {
  TempDir dir;
  writeGeoTiff(dir / "dem.tif", field(16, 3), 0.0);
  const std::vector<std::string> sun = {"--sun-elevation-deg", "3", "--sun-azimuth-deg", "10"};
  auto shadow = [&](std::vector<std::string> a) {
    a.insert(a.begin(), {"terrain", "shadow"});
    a.insert(a.end(), sun.begin(), sun.end());
    return run(UMBRA_EXE, a, {"LD_DEBUG=files"});
  };
  RunResult r = shadow({"--synthetic", "3", "--size", "16", "--output", dir / "syn.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("file=libvtkCommonCore"), std::string::npos) << "no loader trace";
  EXPECT_EQ(r.err.find("libgdal"), std::string::npos);
  r = shadow({"--dem", dir / "dem.tif", "--output", dir / "dem.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("umbra-dem-gdal.so"), std::string::npos);
  EXPECT_NE(r.err.find("file=libgdal"), std::string::npos);
}

TEST(TerrainCli, TimeGivesTheSunTheLunarSouthPoleSees) {
  // The Moon's axis is tilted 1.54 deg to the ecliptic: from the pole the Sun stays within
  // ~1.6 deg of the horizon and goes once around it in a synodic month (29.53 days).
  TempDir dir;
  double previousAzimuth = NAN;
  for (const char* time : {"2024-01-01T00:00:00Z", "2024-01-08T09:10:00Z", "2024-01-15T18:20:00Z"}) {
    const RunResult r = run(UMBRA_EXE, {"terrain", "shadow", "--synthetic", "1", "--size", "16", "--time", time,
                                        "--output", dir / "t.png"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const double elevation = printed(r.out, "sun elevation"), azimuth = printed(r.out, "azimuth");
    EXPECT_LT(std::abs(elevation), 1.6) << time;
    if (!std::isnan(previousAzimuth)) {
      const double turned = std::fmod(std::abs(azimuth - previousAzimuth) + 360.0, 360.0);
      EXPECT_NEAR(std::min(turned, 360.0 - turned), 90.0, 10.0) << time;  // a quarter month: a quarter turn
    }
    previousAzimuth = azimuth;
  }
  // Over an eclipse year (346.6 days) the pole's Sun goes from ~1.5 deg above the horizon
  // to ~1.5 deg below (the lunar pole's precession terms of the IAU model).
  double highest = -90.0, lowest = 90.0;
  for (const char* time : {"2024-01-15T00:00:00Z", "2024-07-15T00:00:00Z"}) {
    const RunResult r = run(UMBRA_EXE, {"terrain", "shadow", "--synthetic", "1", "--size", "16", "--time", time,
                                        "--output", dir / "t.png"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    highest = std::max(highest, printed(r.out, "sun elevation"));
    lowest = std::min(lowest, printed(r.out, "sun elevation"));
  }
  EXPECT_GT(highest, 1.3);
  EXPECT_LT(lowest, -1.3);
}

TEST(TerrainCli, BadInputGivesOneLineAndNoFile) {
  TempDir dir;
  const std::string out = dir / "x.exr";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--dem", dir / "missing.tif", "--sun-elevation-deg", "1", "--sun-azimuth-deg", "0"}, "missing.tif"},
      {{"--synthetic", "1", "--sun-elevation-deg", "1"}, "--sun-azimuth-deg"},
      {{"--synthetic", "1"}, "--time"},
      {{"--synthetic", "1", "--time", "yesterday"}, "--time"},
      {{"--synthetic", "1", "--sun-elevation-deg", "1", "--sun-azimuth-deg", "0", "--method", "fast"}, "--method"},
      {{"--sun-elevation-deg", "1", "--sun-azimuth-deg", "0"}, "--synthetic"},
      {{"--synthetic", "1", "--sun-elevation-deg", "91", "--sun-azimuth-deg", "0"}, "--sun-elevation-deg"},
  };
  for (const auto& [extra, mention] : cases) {
    std::vector<std::string> args = {"terrain", "shadow", "--output", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(UMBRA_EXE, args);
    EXPECT_NE(r.exitCode, 0) << mention;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const RunResult r = run(UMBRA_EXE, {"terrain", "shadow", "--synthetic", "1", "--sun-elevation-deg", "1",
                                      "--sun-azimuth-deg", "0", "--output", dir / "x.txt"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(dir.fileCount(), 0);
}

TEST(TerrainCli, VtiHoldsHeightsAndFractionAndGeographicRastersAreRefused) {
  TempDir dir;
  RunResult r = run(UMBRA_EXE, {"terrain", "shadow", "--synthetic", "2", "--size", "24", "--sun-elevation-deg", "3",
                                "--sun-azimuth-deg", "10", "--limb-darkening", "0.6", "--output", dir / "s.vti"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string vti = readAll(dir / "s.vti");
  EXPECT_NE(vti.find("Name=\"height_m\""), std::string::npos);
  EXPECT_NE(vti.find("Name=\"visible_solar_fraction\""), std::string::npos);
  EXPECT_NE(vti.find("Spacing=\"30 30 1\""), std::string::npos);

  // A latitude/longitude raster: one line naming the file and what to do.
  writeGeoTiff(dir / "geo.tif", field(24, 2), 0.0, {}, "+proj=longlat +R=1737400 +no_defs");
  r = run(UMBRA_EXE, {"terrain", "shadow", "--dem", dir / "geo.tif", "--sun-elevation-deg", "3", "--sun-azimuth-deg",
                      "10", "--output", dir / "geo.exr"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("geo.tif: geographic"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "geo.exr"));
}

namespace {
/// A flat plain (heights 0), size x size samples, centred on the pole.
void writeFlatGeoTiff(const std::string& path, int size) {
  terrain::HeightField flat;
  flat.width = flat.height = size;
  flat.heightsM.assign(static_cast<std::size_t>(size) * size, 0.0);
  writeGeoTiff(path, flat, 0.0);
}

std::vector<std::vector<std::string>> csvRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}
} // namespace

// `umbra terrain lighting` on a flat plain 60 km from the lunar south pole (a GeoTIFF of
// zeros), March 2024 at 12-hour steps (a lunar day: the Sun sets and rises): the share of the time lit at the centre is the share of the
// steps whose Sun (the CSV's elevation column, from the ephemeris) has its disc's top above
// the horizontal, exactly; the mean visible fraction follows Eq. 7 at those elevations;
// the Earth is reported; the maps come out finite and in range; the plot has a line a point.
TEST(TerrainLightingCli, FlatPlainFollowsTheSunsElevation) {
  TempDir dir;
  writeFlatGeoTiff(dir / "flat.tif", 21);
  const RunResult r = run(UMBRA_EXE, {"terrain", "lighting", "--dem", dir / "flat.tif", "--lat-deg", "-88", "--lon-deg",
                                      "30", "--from", "2024-03-01T00:00:00Z", "--to", "2024-03-29T00:00:00Z", "--step",
                                      "12h", "--point", "10,10", "--point", "0,20", "--csv", dir / "points.csv",
                                      "--plot", dir / "points.svg", "--output", dir / "maps.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csvRows(dir / "points.csv");
  ASSERT_EQ(rows.size(), 1u + 57u * 2u);  // header, 57 steps of 2 points
  EXPECT_EQ(rows[0][0], "time_utc");
  // Each step stands for 12 hours, the first and the last for 6 (the range ends there).
  int steps = 0, nearTheEdge = 0;
  double lit = 0.0, expectedLit = 0.0, meanFraction = 0.0, weights = 0.0;
  const double sunRadiusDeg = 0.2690;  // (the Sun from 0.991 au)
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 10u) << k;
    if (rows[k][1] != "1") continue;
    const double e = std::stod(rows[k][4]), v = std::stod(rows[k][7]);
    EXPECT_EQ(rows[k][6], "1");  // no eclipse
    const double w = steps == 0 || steps == 56 ? 0.5 : 1.0;
    ++steps;
    weights += w;
    lit += w * (v > 0.0);
    expectedLit += w * (e > -sunRadiusDeg);  // the disc's top above the horizontal
    nearTheEdge += std::abs(e + sunRadiusDeg) < 0.002;
    meanFraction += w * v;
    if (std::abs(e) > 0.3) {
      EXPECT_EQ(v, e > 0.0 ? 1.0 : 0.0) << rows[k][0];
    }
    EXPECT_GE(std::stod(rows[k][9]), 0.0);  // the Earth's visible fraction
    EXPECT_TRUE(std::abs(std::stod(rows[k][8])) < 10.0) << "the Earth from near the pole: low in the sky";
  }
  ASSERT_EQ(steps, 57);
  const tables::Table t = tables::readExr(dir / "maps.exr");
  ASSERT_EQ(t.width, 21);
  EXPECT_EQ(t.parameters.at("steps"), "57");
  const int centre = 3 * (10 * 21 + 10);
  EXPECT_DOUBLE_EQ(weights, 56.0);
  EXPECT_EQ(t.parameters.at("totalS"), "2419200");  // 28 days
  EXPECT_NEAR(t.data[centre + 0], lit / weights, 1e-6);
  EXPECT_NEAR(t.data[centre + 0], expectedLit / weights, nearTheEdge / weights + 1e-6);
  EXPECT_GT(expectedLit, 0.0);
  EXPECT_LT(expectedLit, weights);
  EXPECT_NEAR(t.data[centre + 2], meanFraction / weights, 1e-5);
  for (float v : t.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  std::printf("  centre: lit %.0f of %.0f hours (%d steps near the disc's edge)\n", 12.0 * lit, 12.0 * weights, nearTheEdge);
  EXPECT_NE(r.out.find("point 1 (10, 10): lit"), std::string::npos) << r.out;
  // The plot: one line a point.
  std::ifstream svg(dir / "points.svg");
  const std::string plot((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  std::size_t lines = 0;
  for (std::size_t at = plot.find("<polyline"); at != std::string::npos; at = plot.find("<polyline", at + 1)) ++lines;
  EXPECT_EQ(lines, 2u);
  EXPECT_NE(plot.find("point 2 (0, 20)"), std::string::npos);
}

// The extremes: a range of no length and a step longer than the range give one step; a
// DEM of one sample, a point off the grid and a bad method give one line and no file.
TEST(TerrainLightingCli, ExtremesGiveOneStepOrOneLine) {
  TempDir dir;
  auto lighting = [&](std::vector<std::string> a) {
    a.insert(a.begin(), {"terrain", "lighting"});
    return run(UMBRA_EXE, a);
  };
  for (const auto& [to, step] : std::vector<std::pair<std::string, std::string>>{{"2024-03-01T00:00:00Z", "1h"},
                                                                                 {"2024-03-01T06:00:00Z", "1d"}}) {
    const RunResult r = lighting({"--synthetic", "2", "--size", "32", "--from", "2024-03-01T00:00:00Z", "--to", to,
                                  "--step", step, "--csv", dir / "one.csv", "--output", dir / "one.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(csvRows(dir / "one.csv").size(), 2u);
    const tables::Table t = tables::readExr(dir / "one.exr");
    EXPECT_EQ(t.parameters.at("steps"), "1");
    for (float v : t.data) ASSERT_TRUE(std::isfinite(v));
  }
  terrain::HeightField one;
  one.width = one.height = 1;
  one.heightsM = {0.0};
  writeGeoTiff(dir / "one.tif", one, 0.0);
  for (const std::vector<std::string>& a :
       {std::vector<std::string>{"--dem", dir / "one.tif"}, {"--synthetic", "1", "--point", "40,3"},
        {"--synthetic", "1", "--method", "fast"}}) {
    std::vector<std::string> args = a;
    args.insert(args.end(), {"--size", "32", "--from", "2024-03-01T00:00:00Z", "--to", "2024-03-02T00:00:00Z",
                             "--step", "6h", "--output", dir / "bad.exr"});
    if (a[0] == "--dem") args.erase(args.begin() + 2, args.begin() + 4);  // (no --size with a DEM)
    const RunResult r = lighting(args);
    EXPECT_NE(r.exitCode, 0) << a[0];
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr"));
  }
}

// The lunar eclipse of 2015-09-28 seen from a flat plain at the centre of the Moon's near
// side (the Sun near the zenith, behind the Earth): the Sun's visible fraction is what the
// Earth's disc leaves of it (the CSV's eclipse column, from eclipse/SolarDisc's geometry),
// to 1e-4; none of the Sun while the whole Moon is in the umbra (NASA: U2 02:11:11, U3
// 03:23:05 UT), all of it before the penumbra's first contact (P1 00:11:47).
TEST(TerrainLightingCli, LunarEclipseDarkensAFlatSiteAsTheEarthCoversTheSun) {
  TempDir dir;
  writeFlatGeoTiff(dir / "flat.tif", 9);
  const RunResult r = run(UMBRA_EXE, {"terrain", "lighting", "--dem", dir / "flat.tif", "--lat-deg", "0", "--lon-deg", "0",
                                      "--from", "2015-09-28T00:00:00Z", "--to", "2015-09-28T06:00:00Z", "--step", "15min",
                                      "--csv", dir / "e.csv", "--output", dir / "e.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csvRows(dir / "e.csv");
  ASSERT_EQ(rows.size(), 26u);
  int total = 0, partial = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const std::string& time = rows[k][0];
    const double e = std::stod(rows[k][4]), eclipse = std::stod(rows[k][6]), v = std::stod(rows[k][7]);
    EXPECT_GT(e, 60.0) << time;
    EXPECT_NEAR(v, eclipse, 1e-4) << time;
    if (time >= "2015-09-28T02:15:00Z" && time <= "2015-09-28T03:15:00Z") {
      EXPECT_EQ(eclipse, 0.0) << time;
      ++total;
    }
    if (time == "2015-09-28T00:00:00Z") {
      EXPECT_EQ(eclipse, 1.0);
    }
    partial += eclipse > 0.0 && eclipse < 1.0;
  }
  EXPECT_EQ(total, 5);
  EXPECT_GT(partial, 4);
  EXPECT_NE(r.out.find("longest shadow"), std::string::npos);
}
