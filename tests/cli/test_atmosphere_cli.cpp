// `umbra atmosphere refraction`: CSV format, the horizontal deviation, and the standard
// astronomical refraction curve.
#include "CliRunner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace umbra::test;

namespace {
std::vector<std::vector<double>> readRows(const std::string& path, std::string& header) {
  std::ifstream f(path);
  std::getline(f, header);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(f, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}
} // namespace

TEST(AtmosphereCli, RefractionFollowsTheAstronomicalRefractionCurve) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"atmosphere", "refraction", "--preset", "earth", "--altitude", "0",
                                      "--zenith-deg", "0:90:1", "--csv", dir / "r.csv"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::string header;
  const auto rows = readRows(dir / "r.csv", header);
  EXPECT_EQ(header, "zenith_deg,deviation_deg,contact_altitude_m,transmittance_r,transmittance_g,transmittance_b");
  ASSERT_EQ(rows.size(), 91u);
  // horizontal ray at sea level: ~0.6 degrees (the eclipse paper's figure)
  EXPECT_GT(rows[90][1], 0.55);
  EXPECT_LT(rows[90][1], 0.65);
  // Bennett (1982): R = cot(h + 7.31 / (h + 4.4)) arcmin for apparent elevation h in
  // degrees; compared above 5 degrees, where it holds for standard conditions.
  for (int z = 0; z <= 85; ++z) {
    const double h = 90.0 - z;
    const double bennettDeg = 1.0 / std::tan((h + 7.31 / (h + 4.4)) * M_PI / 180.0) / 60.0;
    EXPECT_NEAR(rows[z][1], bennettDeg, 0.1 * std::abs(bennettDeg) + 1e-4) << "zenith " << z;  // Bennett dips below 0 at the zenith
    EXPECT_GT(rows[z][3], rows[z][5]);  // red gets through better than blue
  }
}

TEST(AtmosphereCli, MarsBendsLessThanOnePercentOfEarth) {
  TempDir dir;
  ASSERT_EQ(run(UMBRA_EXE, {"atmosphere", "refraction", "--preset", "earth", "--zenith-deg", "90:90:1", "--csv", dir / "e.csv"}).exitCode, 0);
  ASSERT_EQ(run(UMBRA_EXE, {"atmosphere", "refraction", "--preset", "mars", "--zenith-deg", "90:90:1", "--csv", dir / "m.csv"}).exitCode, 0);
  std::string header;
  const double earth = readRows(dir / "e.csv", header).at(0).at(1);
  const double mars = readRows(dir / "m.csv", header).at(0).at(1);
  EXPECT_GT(mars, 0.0);
  EXPECT_LT(mars, 0.01 * earth);
}

// ---- umbra atmosphere sky ----------------------------------------------------------------

namespace {
// Small and quick: 3 wavelengths, 2 orders, coarse grid.
std::vector<std::string> skyArgs(const std::string& csv, double sunZenithDeg = 45.0) {
  return {"atmosphere", "sky", "--preset", "earth", "--sun-zenith-deg", std::to_string(sunZenithDeg), "--orders", "2",
          "--wavelengths", "3", "--zenith-step", "10", "--azimuth-step", "30", "--csv", csv};
}

void expectOneLineError(const RunResult& r) {
  EXPECT_NE(r.exitCode, 0);
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}
} // namespace

TEST(AtmosphereSkyCli, CsvGridAndPlot) {
  TempDir dir;
  std::vector<std::string> args = skyArgs(dir / "sky.csv");
  args.insert(args.end(), {"--plot", dir / "sky.png", "--plot-size", "64"});
  const RunResult r = run(UMBRA_EXE, args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::string header;
  const auto rows = readRows(dir / "sky.csv", header);
  EXPECT_EQ(header, "view_zenith_deg,view_azimuth_deg,luminance,r,g,b");
  ASSERT_EQ(rows.size(), 10u * 7u);  // zenith 0..90 step 10, azimuth 0..180 step 30
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 6u);
    for (double v : row) {
      EXPECT_TRUE(std::isfinite(v));
      EXPECT_GE(v, 0.0);
    }
  }
  EXPECT_EQ(rows.front()[0], 0.0);
  EXPECT_EQ(rows.back()[0], 90.0);
  EXPECT_EQ(rows.back()[1], 180.0);
  EXPECT_GT(rows.front()[2], 1000.0);  // a daylit zenith, cd/m^2
  const std::string png = readAll(dir / "sky.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(dir.fileCount(), 2);
}

struct TwilightSky {
  double arch = 0.0, zenith = -1.0, opposite = 0.0;  // cd/m^2
};
TwilightSky readTwilightSky(const std::string& csv) {
  std::string header;
  TwilightSky t;
  for (const auto& row : readRows(csv, header)) {
    if (row[0] == 0.0) t.zenith = row[2];
    if (row[0] >= 80.0 && row[1] == 0.0) t.arch = std::max(t.arch, row[2]);
    if (row[1] == 180.0) t.opposite = std::max(t.opposite, row[2]);
  }
  return t;
}

// Twilight, the Sun 16 degrees below the horizon (past the tables' usual lowest, 12
// degrees): the brightest sky is low towards the Sun's azimuth (the twilight arch), where
// views reach sunlit air. The zenith and the sky opposite the Sun see only the light
// scattered into the shadowed air (second-order twilight), which the tables carry when
// they hold the Sun below 102 degrees (by default 20 below the Sun asked for): dimmer than
// the arch, and black with --lowest-sun-zenith-deg 102, which leaves the arch its light
// scattered once (in the default haze a tenth of it: 1.9e-4 of 1.7e-3 cd/m^2; with
// Bruneton's thin haze nearly all).
TEST(AtmosphereSkyCli, TwilightSkyBelowTheTablesLowestSun) {
  TempDir dir;
  ASSERT_EQ(run(UMBRA_EXE, skyArgs(dir / "t.csv", 106.0)).exitCode, 0);
  std::vector<std::string> usual = skyArgs(dir / "u.csv", 106.0);
  usual.insert(usual.end(), {"--lowest-sun-zenith-deg", "102"});
  ASSERT_EQ(run(UMBRA_EXE, usual).exitCode, 0);
  const TwilightSky t = readTwilightSky(dir / "t.csv"), u = readTwilightSky(dir / "u.csv");
  std::printf("  Sun 16 deg down: twilight arch %.3g cd/m^2, zenith %.3g, opposite %.3g (tables down to 102 deg: "
              "%.3g, %.3g, %.3g)\n", t.arch, t.zenith, t.opposite, u.arch, u.zenith, u.opposite);
  EXPECT_GT(t.arch, 1e-3);
  EXPECT_GT(t.zenith, 1e-3 * t.arch);
  EXPECT_LT(t.zenith, 0.1 * t.arch);
  EXPECT_GT(t.opposite, 0.0);
  EXPECT_LT(t.opposite, 0.1 * t.arch);
  EXPECT_GT(u.arch, 0.05 * t.arch);
  EXPECT_LT(u.arch, t.arch);
  EXPECT_EQ(u.zenith, 0.0);
  EXPECT_EQ(u.opposite, 0.0);
  // With the Sun 40 degrees down only the second-order light remains, 1e-6 of the arch's.
  ASSERT_EQ(run(UMBRA_EXE, skyArgs(dir / "n.csv", 130.0)).exitCode, 0);
  const TwilightSky n = readTwilightSky(dir / "n.csv");
  std::printf("  Sun 40 deg down: brightest %.3g cd/m^2\n", n.arch);
  EXPECT_LT(n.arch, 1e-6 * t.arch);
  EXPECT_LT(n.zenith, 1e-6 * t.arch);
}

// --density-directions: the default (12 by day) and 16 x 32 give the same day sky within a
// few per cent (docs/accuracy-vs-speed/atmosphere-tables.md, "Density directions": <= 2 % between 12 and
// 48), the count in the summary line. Mars' dust asks for 48: its default (one order here,
// to be quick: the count is chosen all the same), and a note naming the flag when fewer
// are asked for.
TEST(AtmosphereSkyCli, DensityDirections) {
  TempDir dir;
  const RunResult a = run(UMBRA_EXE, skyArgs(dir / "a.csv"));
  std::vector<std::string> more = skyArgs(dir / "b.csv");
  more.insert(more.end(), {"--density-directions", "16"});
  const RunResult b = run(UMBRA_EXE, more);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  EXPECT_NE(a.out.find("12 x 24 density directions"), std::string::npos) << a.out;
  EXPECT_NE(b.out.find("16 x 32 density directions"), std::string::npos) << b.out;
  EXPECT_EQ(a.err.find("note:"), std::string::npos) << a.err;
  std::string header;
  const auto ra = readRows(dir / "a.csv", header), rb = readRows(dir / "b.csv", header);
  ASSERT_EQ(ra.size(), rb.size());
  int differ = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    EXPECT_NEAR(rb[i][2], ra[i][2], 0.03 * ra[i][2]) << "row " << i;
    differ += rb[i][2] != ra[i][2];
  }
  EXPECT_GT(differ, 0);
  std::vector<std::string> mars = skyArgs(dir / "m.csv");
  mars[3] = "mars";
  std::vector<std::string> marsDefault = mars;
  marsDefault[7] = "1";  // --orders
  const RunResult d = run(UMBRA_EXE, marsDefault);
  ASSERT_EQ(d.exitCode, 0) << d.err;
  EXPECT_NE(d.out.find("48 x 96 density directions"), std::string::npos) << d.out;
  EXPECT_EQ(d.err.find("note:"), std::string::npos) << d.err;
  mars.insert(mars.end(), {"--density-directions", "12"});
  const RunResult m = run(UMBRA_EXE, mars);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  EXPECT_NE(m.err.find("phase functions ask for 48 density directions, 12 used"), std::string::npos) << m.err;
  EXPECT_NE(m.err.find("--density-directions 48"), std::string::npos) << m.err;
}

TEST(AtmosphereSkyCli, BadInputIsOneLineAndLeavesNoFile) {
  TempDir dir;
  std::vector<std::string> unknown = skyArgs(dir / "a.csv");
  unknown[3] = "no-such-planet";
  expectOneLineError(run(UMBRA_EXE, unknown));
  expectOneLineError(run(UMBRA_EXE, skyArgs(dir / "b.csv", 200.0)));
  expectOneLineError(run(UMBRA_EXE, skyArgs(dir / "missing-dir/c.csv")));
  std::vector<std::string> badPlot = skyArgs(dir / "d.csv");
  badPlot.insert(badPlot.end(), {"--plot", dir / "missing-dir/d.png"});
  expectOneLineError(run(UMBRA_EXE, badPlot));
  for (const char* lowest : {"90", "171", "x", "110deg"}) {
    std::vector<std::string> badLowest = skyArgs(dir / "e.csv", 106.0);
    badLowest.insert(badLowest.end(), {"--lowest-sun-zenith-deg", lowest});
    expectOneLineError(run(UMBRA_EXE, badLowest));
  }
  for (const char* directions : {"2", "65", "x"}) {
    std::vector<std::string> badDirections = skyArgs(dir / "f.csv");
    badDirections.insert(badDirections.end(), {"--density-directions", directions});
    expectOneLineError(run(UMBRA_EXE, badDirections));
  }
  EXPECT_EQ(dir.fileCount(), 0);
}

// ---- umbra atmosphere eclipse-sky --------------------------------------------------------

namespace {
// NASA's greatest eclipse of 2017-08-21 (18:25:30 UT, 36 58.0' N, 87 40.3' W); few paths.
std::vector<std::string> eclipseSkyArgs(const std::string& csv) {
  return {"atmosphere", "eclipse-sky", "--preset", "earth-bruneton", "--time", "2017-08-21T18:25:30Z",
          "--observer", "36.9667,-87.6717", "--paths", "4000", "--step-deg", "10", "--csv", csv};
}
}  // namespace

TEST(AtmosphereEclipseSkyCli, TotalityAtTheGreatestEclipseOf2017) {
  TempDir dir;
  std::vector<std::string> args = eclipseSkyArgs(dir / "sky.csv");
  args.insert(args.end(), {"--plot-vertical", dir / "v.svg", "--plot-almucantar", dir / "a.svg"});
  const RunResult r = run(UMBRA_EXE, args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("Sun 63.90 deg up"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.0000 of its disc's light visible"), std::string::npos) << r.out;
  std::ifstream f(dir / "sky.csv");
  std::string header, line;
  std::getline(f, header);
  EXPECT_EQ(header,
            "curve,position_deg,view_zenith_deg,view_azimuth_deg,luminance_cd_m2,luminance_se_cd_m2,r,g,b,"
            "clear_luminance_cd_m2,radiance_680nm,se_680nm,radiance_550nm,se_550nm,radiance_440nm,se_440nm");
  int vertical = 0, almucantar = 0;
  double zenith = -1.0, zenithClear = -1.0, horizon = 0.0;
  while (std::getline(f, line)) {
    std::stringstream s(line);
    std::string curve, cell;
    std::getline(s, curve, ',');
    std::vector<double> v;
    while (std::getline(s, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 15u) << line;
    for (double x : v) EXPECT_TRUE(std::isfinite(x)) << line;
    if (curve == "vertical") {
      ++vertical;
      if (v[0] == 0.0) zenith = v[3], zenithClear = v[8];
      if (std::abs(v[0]) == 80.0) horizon = std::max(horizon, v[3]);
    } else {
      EXPECT_EQ(curve, "almucantar");
      EXPECT_NEAR(v[1], 90.0 - 63.9, 0.05);  // at the Sun's altitude
      ++almucantar;
    }
  }
  EXPECT_EQ(vertical, 19);    // -90..90 by 10
  EXPECT_EQ(almucantar, 36);  // 0..350 by 10
  // Totality: the zenith 3 to 4 orders of magnitude below the sky without the Moon, and
  // darker than the sky 10 deg above the horizon.
  EXPECT_GT(zenithClear / zenith, 1e3);
  EXPECT_LT(zenithClear / zenith, 3e4);
  EXPECT_GT(horizon, 3.0 * zenith);
  EXPECT_EQ(readAll(dir / "v.svg").substr(0, 4), "<svg");
  EXPECT_EQ(readAll(dir / "a.svg").substr(0, 4), "<svg");
  EXPECT_EQ(dir.fileCount(), 3);
}

TEST(AtmosphereEclipseSkyCli, TheQuadratureGivesTheSameTotalityWithoutStandardErrors) {
  // --method fast: the same rows, the standard-error cells empty, the zenith again 3 to 4
  // orders of magnitude below the sky without the Moon and darker than 10 deg above the
  // horizon (the quadrature against the reference: tests/eclipse_atmosphere).
  TempDir dir;
  std::vector<std::string> args = eclipseSkyArgs(dir / "sky.csv");
  args.insert(args.end(), {"--method", "fast"});
  const RunResult r = run(UMBRA_EXE, args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("quadrature"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("+-"), std::string::npos) << r.out;
  std::ifstream f(dir / "sky.csv");
  std::string line;
  std::getline(f, line);
  int rows = 0;
  double zenith = -1.0, zenithClear = -1.0, horizon = 0.0;
  while (std::getline(f, line)) {
    ++rows;
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (line.back() == ',') cells.emplace_back();
    ASSERT_EQ(cells.size(), 16u) << line;
    for (std::size_t i : {5u, 11u, 13u, 15u}) EXPECT_EQ(cells[i], "") << line;
    for (std::size_t i : {1u, 2u, 3u, 4u, 6u, 7u, 8u, 9u, 10u, 12u, 14u}) EXPECT_TRUE(std::isfinite(std::stod(cells[i]))) << line;
    if (cells[0] == "vertical" && std::stod(cells[1]) == 0.0) zenith = std::stod(cells[4]), zenithClear = std::stod(cells[9]);
    if (cells[0] == "vertical" && std::abs(std::stod(cells[1])) == 80.0) horizon = std::max(horizon, std::stod(cells[4]));
  }
  EXPECT_EQ(rows, 19 + 36);
  EXPECT_GT(zenithClear / zenith, 1e3);
  EXPECT_LT(zenithClear / zenith, 3e4);
  EXPECT_GT(horizon, 3.0 * zenith);
}

TEST(AtmosphereEclipseSkyCli, BadInputIsOneLineAndLeavesNoFile) {
  TempDir dir;
  const auto with = [&](int index, const std::string& value) {
    std::vector<std::string> a = eclipseSkyArgs(dir / "a.csv");
    a[static_cast<std::size_t>(index)] = value;
    return a;
  };
  expectOneLineError(run(UMBRA_EXE, with(5, "2017-13-21T18:25:30Z")));   // the time
  expectOneLineError(run(UMBRA_EXE, with(7, "95,0")));                   // the latitude
  expectOneLineError(run(UMBRA_EXE, with(7, "36.9,-87.6,70km")));        // above half the atmosphere
  expectOneLineError(run(UMBRA_EXE, with(9, "0")));                      // --paths
  expectOneLineError(run(UMBRA_EXE, with(11, "45")));                    // --step-deg
  expectOneLineError(run(UMBRA_EXE, with(13, dir / "missing-dir/a.csv")));
  std::vector<std::string> badPlot = eclipseSkyArgs(dir / "b.csv");
  badPlot.insert(badPlot.end(), {"--plot-vertical", dir / "b.pdf"});
  expectOneLineError(run(UMBRA_EXE, badPlot));
  std::vector<std::string> badMethod = eclipseSkyArgs(dir / "c.csv");
  badMethod.insert(badMethod.end(), {"--method", "exact"});
  expectOneLineError(run(UMBRA_EXE, badMethod));
  EXPECT_EQ(dir.fileCount(), 0);
}

// The extremes: the annular eclipse of 2023-10-14 at its greatest (11 22' N, 83 06' W: the
// ring of the Sun left, a tenth of its light), the hybrid one of 2023-04-20 at its greatest
// (9 36' S, 125 48' E: total, the umbra 49 km wide), and the North Pole during the partial
// eclipse of 2026-08-12, the South Pole in its night then: finite skies, no error.
TEST(AtmosphereEclipseSkyCli, ExtremesGiveFiniteSkies) {
  struct Case {
    const char *time, *observer;
    double visibleMin, visibleMax;
  };
  for (const Case& c : {Case{"2023-10-14T17:59:39Z", "11.37,-83.10", 0.02, 0.2},
                        Case{"2023-04-20T04:16:49Z", "-9.60,125.80", 0.0, 0.0},
                        Case{"2026-08-12T17:46:00Z", "90,0", 0.05, 0.95}, Case{"2026-08-12T17:46:00Z", "-90,0", 0.0, 1.0}}) {
    TempDir dir;
    std::vector<std::string> args = eclipseSkyArgs(dir / "sky.csv");
    args[5] = c.time;
    args[7] = c.observer;
    args[9] = "300";
    args[11] = "30";
    const RunResult r = run(UMBRA_EXE, args);
    ASSERT_EQ(r.exitCode, 0) << c.time << " " << c.observer << ": " << r.err;
    const std::size_t at = r.out.find(" of its disc's light visible");
    ASSERT_NE(at, std::string::npos) << r.out;
    const double visible = std::stod(r.out.substr(r.out.rfind(", ", at) + 2));
    EXPECT_GE(visible, c.visibleMin) << c.time << " " << c.observer;
    EXPECT_LE(visible, c.visibleMax) << c.time << " " << c.observer;
    std::ifstream f(dir / "sky.csv");
    std::string line;
    std::getline(f, line);
    int rows = 0;
    while (std::getline(f, line)) {
      ++rows;
      std::stringstream s(line.substr(line.find(',') + 1));
      std::string cell;
      while (std::getline(s, cell, ',')) EXPECT_TRUE(std::isfinite(std::stod(cell))) << line;
    }
    EXPECT_EQ(rows, 7 + 12);
  }
}
