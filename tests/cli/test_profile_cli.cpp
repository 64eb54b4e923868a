// `umbra profile shadow` against the geometry of the shadow cones, and its CSV format.
#include "CliRunner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace umbra::test;

namespace {
constexpr double kAu = 149597870700.0, kSunR = 696342e3, kEarthR = 6371.0084e3;

// First offset [km] where the luminance crosses `level` going outwards (linear interpolation).
double crossing(const Csv& c, double level) {
  for (std::size_t i = 1; i < c.rows.size(); ++i) {
    const double a = c.rows[i - 1][4], b = c.rows[i][4];
    if (a <= level && b > level) {
      const double t = (level - a) / (b - a);
      return c.rows[i - 1][0] + t * (c.rows[i][0] - c.rows[i - 1][0]);
    }
  }
  return NAN;
}

// The cone radii from the tangent lines of Sun and Earth, written out here independently:
// the umbra's tip lies R d / (R_sun - R) behind the occluder, the penumbra's apex
// R d / (R_sun + R) in front of it.
double umbraRadiusKm(double x) {
  const double tip = kEarthR * kAu / (kSunR - kEarthR);
  const double half = std::asin((kSunR - kEarthR) / kAu);
  return (tip - x) * std::tan(half) / 1e3;
}
double penumbraRadiusKm(double x) {
  const double apex = kEarthR * kAu / (kSunR + kEarthR);
  const double half = std::asin((kSunR + kEarthR) / kAu);
  return (apex + x) * std::tan(half) / 1e3;
}

class ProfileRadii : public ::testing::TestWithParam<double> {};

} // namespace

TEST_P(ProfileRadii, UmbraAndPenumbraWithinOnePercentOfGeometry) {
  const double distanceKm = GetParam();
  TempDir dir;
  for (bool exact : {false, true}) {
    SCOPED_TRACE(exact ? "exact" : "LuT 256");
    std::vector<std::string> args{"profile", "shadow", "--occluder", "Earth", "--no-atmosphere",
                                  "--distance", std::to_string(distanceKm) + "km", "--sun-distance", "1au",
                                  "--samples", "4001", "--csv", dir / "p.csv"};
    if (exact) args.push_back("--exact");
    const RunResult r = run(UMBRA_EXE, args, {"UMBRA_CACHE_DIR=" + dir / "cache"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Csv csv = readCsv(dir / "p.csv");
    EXPECT_EQ(csv.header, "offset_km,r,g,b,luminance");
    ASSERT_EQ(csv.rows.size(), 4001u);
    const double umbra = crossing(csv, 1e-4), penumbra = crossing(csv, 1.0 - 1e-4);
    const double tolerance = exact ? 0.002 : 0.01;
    EXPECT_NEAR(umbra, umbraRadiusKm(distanceKm * 1e3), tolerance * umbraRadiusKm(distanceKm * 1e3));
    EXPECT_NEAR(penumbra, penumbraRadiusKm(distanceKm * 1e3), tolerance * penumbraRadiusKm(distanceKm * 1e3));
    // Airless: all channels equal; values are fractions.
    for (const auto& row : csv.rows) {
      EXPECT_EQ(row[1], row[2]);
      EXPECT_EQ(row[1], row[3]);
      EXPECT_GE(row[4], 0.0);
      EXPECT_LE(row[4], 1.0 + 1e-9);
    }
  }
}

// Lunar perigee, mean distance and apogee.
INSTANTIATE_TEST_SUITE_P(MoonDistances, ProfileRadii, ::testing::Values(356500.0, 384400.0, 406700.0));

TEST(ProfileCli, AcceptsUnitsAndWritesAnSvgPlot) {
  TempDir dir;
  const RunResult km = run(UMBRA_EXE, {"profile", "shadow", "--occluder", "Earth", "--no-atmosphere", "--distance",
                                       "384400km", "--samples", "50", "--exact", "--csv", dir / "km.csv", "--plot",
                                       dir / "plot.svg"});
  ASSERT_EQ(km.exitCode, 0) << km.err;
  const RunResult m = run(UMBRA_EXE, {"profile", "shadow", "--occluder", "Earth", "--no-atmosphere", "--distance",
                                      "384400000m", "--samples", "50", "--exact", "--csv", dir / "m.csv"});
  ASSERT_EQ(m.exitCode, 0) << m.err;
  EXPECT_EQ(readAll(dir / "km.csv"), readAll(dir / "m.csv"));
  const std::string svg = readAll(dir / "plot.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
}

TEST(ProfileCli, LutFromPrecomputeGivesTheSameProfileAsTheCache) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  ASSERT_EQ(run(UMBRA_EXE, {"precompute", "shadow", "--occluder", "Earth", "--size", "64", "--output", dir / "lut.exr"}, env).exitCode, 0);
  const std::vector<std::string> common{"profile", "shadow", "--occluder", "Earth", "--no-atmosphere", "--distance",
                                        "384400km", "--size", "64", "--samples", "200"};
  auto a = common, b = common;
  a.insert(a.end(), {"--csv", dir / "a.csv"});
  b.insert(b.end(), {"--lut", dir / "lut.exr", "--csv", dir / "b.csv"});
  const RunResult ra = run(UMBRA_EXE, a, env);
  const RunResult rb = run(UMBRA_EXE, b, env);
  ASSERT_EQ(ra.exitCode, 0) << ra.err;
  ASSERT_EQ(rb.exitCode, 0) << rb.err;
  EXPECT_NE(ra.err.find("cache hit"), std::string::npos) << ra.err;  // precompute filled the cache
  EXPECT_EQ(readAll(dir / "a.csv"), readAll(dir / "b.csv"));
}

TEST(ProfileCli, SceneGivesTheOccluderAndTheReceiversDistance) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"profile", "shadow", "--scene",
                                      UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json",
                                      "--no-atmosphere", "--samples", "4001", "--csv", dir / "p.csv"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // The 2015-09-28 eclipse happened at perigee: the Moon ~356 850 km behind Earth, during
  // the partial phase its centre inside the umbra.
  EXPECT_NE(r.out.find("Moon is 3568"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("km behind Earth"), std::string::npos) << r.out;
  const std::size_t at = r.out.find("umbra ");
  ASSERT_NE(at, std::string::npos);
  const double umbraKm = std::stod(r.out.substr(at + 6));
  EXPECT_NEAR(crossing(readCsv(dir / "p.csv"), 1e-4), umbraKm, 0.01 * umbraKm);
  // After the eclipse the scene's Moon is outside the shadow, and --time moves it there.
  const RunResult later = run(UMBRA_EXE, {"profile", "shadow", "--scene",
                                          UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json",
                                          "--time", "2015-09-28T05:30:00Z", "--no-atmosphere", "--csv", dir / "q.csv"},
                              {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(later.exitCode, 0) << later.err;
  const std::size_t from = later.out.find(" and ");
  ASSERT_NE(from, std::string::npos);
  EXPECT_GT(std::stod(later.out.substr(from + 5)), 9000.0) << later.out;  // km from the axis
}

// Near the occluder (Mars' shadow at Phobos) the profile command builds a LuT over the
// cross-section's distances only, and `precompute shadow --distance-range` makes one: both
// agree with --exact at 64^2 where a whole 64^2 LuT is off by ~0.5 (docs/accuracy-vs-speed/eclipse-luts.md).
TEST(ProfileCli, RangedLutsAtPhobosAgreeWithExact) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  const std::vector<std::string> common{"profile", "shadow", "--occluder", "Mars", "--no-atmosphere", "--distance",
                                        "9376km", "--size", "64", "--samples", "300"};
  auto ranged = common, exact = common, fromFile = common;
  ranged.insert(ranged.end(), {"--csv", dir / "r.csv"});
  exact.insert(exact.end(), {"--exact", "--csv", dir / "e.csv"});
  fromFile.insert(fromFile.end(), {"--lut", dir / "lut.exr", "--csv", dir / "f.csv"});
  ASSERT_EQ(run(UMBRA_EXE, {"precompute", "shadow", "--occluder", "Mars", "--size", "64", "--distance-range",
                            "9376km:10300km", "--output", dir / "lut.exr"}, env).exitCode, 0);
  const RunResult rr = run(UMBRA_EXE, ranged, env);
  ASSERT_EQ(rr.exitCode, 0) << rr.err;
  EXPECT_NE(rr.err.find("over this cross-section's distances"), std::string::npos) << rr.err;
  ASSERT_EQ(run(UMBRA_EXE, exact, env).exitCode, 0);
  const RunResult rf = run(UMBRA_EXE, fromFile, env);
  ASSERT_EQ(rf.exitCode, 0) << rf.err;
  const Csv e = readCsv(dir / "e.csv");
  for (const char* name : {"r.csv", "f.csv"}) {
    const Csv c = readCsv(dir / name);
    ASSERT_EQ(c.rows.size(), e.rows.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < c.rows.size(); ++i) worst = std::max(worst, std::abs(c.rows[i][4] - e.rows[i][4]));
    EXPECT_LT(worst, 1e-3) << name;
  }
  const RunResult bad = run(UMBRA_EXE, {"precompute", "shadow", "--occluder", "Mars", "--distance-range",
                                        "9800km:9000km", "--output", dir / "bad.exr"}, env);
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--distance-range:"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr"));
}
