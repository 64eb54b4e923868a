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
