// umbra moon: the Moon's numbers for one time and as a table over time (CSV), against
// the library (scene::moonNumbers) and Meeus; umbra planets; bad input gets one line and
// no file.
#include "CliRunner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

using namespace umbra::test;

namespace {

std::vector<std::vector<std::string>> csvCells(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace

// Meeus's example date (1992-04-12 0h TD is 23:59:01.8 UTC the day before): the numbers of
// examples 47.a, 48.a and 53.a in the printed block; the distance ELP's with every term,
// 4.1 km short of Meeus' truncated series (Moon.PositionOfMeeus47a).
TEST(MoonCli, MeeusExampleDate) {
  const RunResult r = run(UMBRA_EXE, {"moon", "--time", "1992-04-11T23:59:02Z"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("distance              368405.6 km"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("phase angle            69.07"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("illuminated             0.678"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-1.20"), std::string::npos) << r.out;  // l'
  EXPECT_NE(r.out.find("+4.19"), std::string::npos) << r.out;  // b'
  EXPECT_EQ(r.out.find("altitude"), std::string::npos);       // geocentric: no horizon
}

// Inside 1900-2100 no note; beyond it the numbers still come, with one note that the
// ephemeris degrades there.
TEST(MoonCli, ANoteBeyondTheEphemerisYears) {
  const RunResult inside = run(UMBRA_EXE, {"moon", "--time", "2026-10-26T04:00:00Z"});
  ASSERT_EQ(inside.exitCode, 0) << inside.err;
  EXPECT_EQ(inside.err, "");
  const RunResult beyond = run(UMBRA_EXE, {"moon", "--time", "2300-01-01T00:00:00Z"});
  ASSERT_EQ(beyond.exitCode, 0) << beyond.err;
  EXPECT_EQ(beyond.err.rfind("umbra: note: 2300-01-01T00:00:00", 0), 0u) << beyond.err;
  EXPECT_NE(beyond.err.find("outside 1900-2100"), std::string::npos) << beyond.err;
  EXPECT_EQ(std::count(beyond.err.begin(), beyond.err.end(), '\n'), 1) << beyond.err;
  EXPECT_NE(beyond.out.find("distance"), std::string::npos) << beyond.out;
}

// A table over a month from an observer: one row per day, every value finite, the phase
// angle through full and new, the illuminated fraction (1 + cos i) / 2, and a V that is
// brightest at full Moon.
TEST(MoonCli, CsvOverAMonth) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"moon", "--from", "2026-10-10T00:00:00Z", "--to", "2026-11-09T00:00:00Z",
                                      "--step", "1d", "--observer", "40.42,-3.70,650", "--csv", dir / "moon.csv"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csvCells(dir / "moon.csv");
  ASSERT_EQ(rows.size(), 32u);
  ASSERT_EQ(rows[0].size(), 16u);
  EXPECT_EQ(rows[0][0], "time_utc");
  EXPECT_EQ(rows[0][7], "phase_angle_deg");
  double smallest = 180.0, largest = 0.0, brightest = 0.0, phaseOfBrightest = 0.0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 16u) << k;
    for (std::size_t c = 1; c < 16; ++c) EXPECT_TRUE(std::isfinite(std::stod(rows[k][c]))) << rows[k][c];
    const double phase = std::stod(rows[k][7]), lit = std::stod(rows[k][8]), v = std::stod(rows[k][10]);
    EXPECT_NEAR(lit, 0.5 * (1.0 + std::cos(phase * 3.14159265358979323846 / 180.0)), 1e-4);
    smallest = std::min(smallest, phase);
    largest = std::max(largest, phase);
    if (v < brightest) brightest = v, phaseOfBrightest = phase;
  }
  EXPECT_LT(smallest, 10.0);
  EXPECT_GT(largest, 170.0);
  EXPECT_EQ(phaseOfBrightest, smallest);  // brightest at full Moon
  EXPECT_NEAR(brightest, -12.7, 0.2);
}

TEST(MoonCli, BadInput) {
  TempDir dir;
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"moon", "--time", "yesterday"}, "--time: invalid UTC time 'yesterday'"},
           {{"moon", "--observer", "91,0"}, "--observer: latitude must be within -90..90 deg"},
           {{"moon", "--observer", "north"}, "--observer: expected LAT,LON[,ALT]"},
           {{"moon", "--observer", "10,20,3 parsec"}, "invalid length '3 parsec'"},
           {{"moon", "--from", "2026-01-01T00:00:00Z"}, "--from, --to and --step go together"},
           {{"moon", "--time", "2026-01-01T00:00:00Z", "--from", "2026-01-01T00:00:00Z", "--to", "2026-01-02T00:00:00Z",
             "--step", "1h"}, "--time: not with --from/--to/--step"},
           {{"moon", "--csv", dir / "moon.txt"}, ".csv"}}) {
    const RunResult r = run(UMBRA_EXE, args);
    EXPECT_NE(r.exitCode, 0) << message;
    EXPECT_NE(r.err.find(message), std::string::npos) << "stderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(dir.fileCount(), 0);
}

// ---- umbra planets ------------------------------------------------------------------------

// Totality at Luxor, 2027-08-02: the five planets in the CSV with finite numbers, their
// altitudes from the horizon frame (Venus next to the Sun, 81.7 deg up: within 10 deg of
// it), magnitudes within Mallama & Hilton's extremes; the printed table the same rows.
TEST(PlanetsCli, TheSkyOfTotalityAtLuxor) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"planets", "--time", "2027-08-02T10:06:00Z", "--observer", "25.6872,32.6396,80",
                                      "--csv", dir / "p.csv"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csvCells(dir / "p.csv");
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0][0], "planet");
  EXPECT_EQ(rows[0][10], "ring_tilt_deg");
  const std::vector<std::string> names{"Mercury", "Venus", "Mars", "Jupiter", "Saturn"};
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 11u);
    EXPECT_EQ(rows[k][10].empty(), names[k - 1] != "Saturn");  // the ring tilt Saturn's alone
    EXPECT_EQ(rows[k][0], names[k - 1]);
    for (std::size_t c = 1; c < 10; ++c) EXPECT_TRUE(std::isfinite(std::stod(rows[k][c]))) << rows[k][0] << " " << c;
    EXPECT_NE(r.out.find(names[k - 1]), std::string::npos);
  }
  // Saturn 2.4 years past the ring-plane crossing of 2025-03-23: their south face open by
  // some 27 deg x sin(360 deg x 2.4 / 29.5) ~ 13 deg, give or take the Earth's parallax.
  EXPECT_LT(std::stod(rows[5][10]), -9.0);
  EXPECT_GT(std::stod(rows[5][10]), -17.0);
  EXPECT_NEAR(std::stod(rows[2][3]), 81.7, 10.0);  // Venus, near the Sun in the sky
  EXPECT_LT(std::stod(rows[2][9]), -3.8);
  EXPECT_GT(std::stod(rows[2][9]), -4.92);
  EXPECT_EQ(dir.fileCount(), 1);
}

TEST(PlanetsCli, GeocentricWithoutAnObserverAndBadInputIsOneLine) {
  const RunResult r = run(UMBRA_EXE, {"planets", "--time", "1992-12-20T00:00:00Z"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("the Earth's centre"), std::string::npos);
  TempDir dir;
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"planets", "--time", "1992-13-20T00:00:00Z", "--csv", dir / "a.csv"}, "--time: "},
           {{"planets", "--observer", "95,0", "--csv", dir / "a.csv"}, "--observer: latitude must be within -90..90 deg"},
           {{"planets", "--csv", dir / "missing/a.csv"}, "missing"}}) {
    const RunResult bad = run(UMBRA_EXE, args);
    EXPECT_NE(bad.exitCode, 0) << message;
    EXPECT_NE(bad.err.find(message), std::string::npos) << "stderr: " << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
  EXPECT_EQ(dir.fileCount(), 0);
}
