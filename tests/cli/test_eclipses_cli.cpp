// umbra eclipses: the catalogue as a user runs it (CSV against NASA's figures, a thousand
// years without a hang, bad input as one line and no file); an unknown command named.
#include "CliRunner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace umbra::test;

namespace {

/// The CSV's rows as maps from the header's names to the cells.
std::vector<std::map<std::string, std::string>> csvRows(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  std::string line;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    EXPECT_EQ(cells.size(), header.size()) << line;
    rows.push_back(row);
  }
  return rows;
}

// 2017: NASA's total eclipse of 08-21 (gamma 0.4367, magnitude 1.0306, 2 m 40 s, 114.7 km;
// Saros 145) and its partial lunar eclipse of 08-07 (umbral magnitude 0.2464, Saros 119),
// with NASA's Delta T of 70.3 s.
TEST(EclipsesCli, A2017CatalogueAgainstNasa) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"eclipses", "--from", "2017-08-01", "--to", "2017-08-31", "--delta-t", "70.3",
                                      "--csv", dir / "e.csv"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csvRows(dir / "e.csv");
  ASSERT_EQ(rows.size(), 2u);
  const auto& lunar = rows[0];
  EXPECT_EQ(lunar.at("kind"), "lunar");
  EXPECT_EQ(lunar.at("type"), "partial");
  EXPECT_NEAR(std::stod(lunar.at("magnitude")), 0.2464, 0.002);
  EXPECT_EQ(lunar.at("saros"), "119");
  const auto& solar = rows[1];
  EXPECT_EQ(solar.at("kind"), "solar");
  EXPECT_EQ(solar.at("type"), "total");
  EXPECT_EQ(solar.at("greatest_ut").substr(0, 19), "2017-08-21T18:25:29");
  EXPECT_EQ(solar.at("greatest_tt").substr(0, 16), "2017-08-21T18:26");
  EXPECT_EQ(solar.at("delta_t_s"), "70.3");
  EXPECT_NEAR(std::stod(solar.at("gamma")), 0.4367, 0.0005);
  EXPECT_NEAR(std::stod(solar.at("magnitude")), 1.0306, 0.0005);
  EXPECT_NEAR(std::stod(solar.at("central_duration_s")), 160.0, 1.0);
  EXPECT_NEAR(std::stod(solar.at("path_width_km")), 114.7, 1.2);
  EXPECT_EQ(solar.at("saros"), "145");
  EXPECT_EQ(solar.at("p2_ut"), "");  // no interior contact of the penumbra
  EXPECT_EQ(solar.at("p1_ut").substr(0, 13), "2017-08-21T15");
  EXPECT_NE(r.out.find("2 eclipses"), std::string::npos) << r.out;
  EXPECT_EQ(dir.fileCount(), 1);
}

// A thousand years (1000-1999): no hang, no NaN, and about as many eclipses as NASA's
// canons give a millennium (2.38 solar and 2.41 lunar a year over -1999..+3000); the note
// on Delta T's uncertainty before 1600.
TEST(EclipsesCli, AThousandYears) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"eclipses", "--from", "1000-01-01", "--to", "1999-12-31", "--csv", dir / "e.csv"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("Delta T is uncertain"), std::string::npos) << r.err;
  int solar = 0, lunar = 0;
  for (const auto& row : csvRows(dir / "e.csv")) {
    (row.at("kind") == "solar" ? solar : lunar) += 1;
    for (const char* c : {"gamma", "magnitude", "delta_t_s"}) EXPECT_TRUE(std::isfinite(std::stod(row.at(c))));
  }
  EXPECT_NEAR(solar, 2380, 60);
  EXPECT_NEAR(lunar, 2410, 60);
}

/// The quantity column of `eclipse brightness --csv`.
double quantity(const std::string& csv, const std::string& name) {
  std::ifstream f(csv);
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(name + ",", 0) == 0) return std::stod(line.substr(name.size() + 1));
  ADD_FAILURE() << name << " not in " << csv;
  return std::nan("");
}

// How dark: the deep central eclipse of 2018-07-27 (gamma 0.117) through the clear `earth`
// atmosphere within the V that photometry measured at the total eclipses of 2000-2025
// (-2.8, 2008-02-21, to -0.35, 2011-06-15: docs/eclipse-predictions.md), and 0.2-0.6
// magnitudes dimmer through Calbuco's sulphate (Keen: the 2015 Moon 0.4 mag dimmer than a
// clean stratosphere gives).
TEST(EclipsesCli, HowDarkTheMoonIs) {
  TempDir dir;
  double v[2] = {0.0, 0.0};
  const char* atmospheres[2] = {"earth", "earth-2015-calbuco"};
  for (int i = 0; i < 2; ++i) {
    const std::string csv = dir / (std::string(atmospheres[i]) + ".csv");
    const RunResult r = run(UMBRA_EXE, {"eclipse", "brightness", "--date", "2018-07-27", "--atmosphere", atmospheres[i],
                                        "--samples", "401", "--csv", csv});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("Danjon L"), std::string::npos) << r.out;
    v[i] = quantity(csv, "v");
    const double full = quantity(csv, "v_outside_shadow");
    EXPECT_NEAR(full, -12.8, 0.3);  // the full Moon near perigee
    EXPECT_GT(quantity(csv, "danjon_l"), 0.0);
    EXPECT_LE(quantity(csv, "danjon_l"), 4.0);
    for (const char* where : {"surface_brightness_centre", "surface_brightness_near_limb", "surface_brightness_far_limb"})
      EXPECT_GT(quantity(csv, where), 3.4 + 8.0) << where;  // more than 8 magnitudes below the full Moon's 3.4
  }
  EXPECT_GT(v[0], -2.8);
  EXPECT_LT(v[0], -0.35);
  EXPECT_GT(v[1] - v[0], 0.2);
  EXPECT_LT(v[1] - v[0], 0.6);
  // Clouds to 10 km on half the limb stop half the low rays: dimmer, by less than the
  // 0.75 magnitudes that would halve all the light.
  const std::string cloudy = dir / "cloudy.csv";
  const RunResult c = run(UMBRA_EXE, {"eclipse", "brightness", "--date", "2018-07-27", "--atmosphere", "earth",
                                      "--samples", "401", "--cloud-cover", "0.5", "--cloud-top", "10km", "--csv", cloudy});
  ASSERT_EQ(c.exitCode, 0) << c.err;
  EXPECT_NE(c.out.find("clouds to 10.0 km over 50 % of the limb"), std::string::npos) << c.out;
  EXPECT_GT(quantity(cloudy, "v") - v[0], 0.1);
  EXPECT_LT(quantity(cloudy, "v") - v[0], 0.76);
  const RunResult bad = run(UMBRA_EXE, {"eclipse", "brightness", "--date", "2017-08-21", "--atmosphere", "earth"});
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--date: no lunar eclipse on 2017-08-21; the next is the total eclipse of 2018-01-31"),
            std::string::npos)
      << bad.err;
}

// The three shadow rules at 2018-07-27: the physical edge through `earth` (the umbra's
// edge where its shadow profile is steepest) enlarges the Earth by 60-110 km, between
// Danjon's 1/85 (75 km) and Chauvenet's 1/50 of the shadow (92 km); its magnitude lies
// within 0.006 of both.
TEST(EclipsesCli, ThePhysicalEdgeOfTheShadow) {
  TempDir dir;
  std::map<std::string, double> magnitude;
  for (const char* rule : {"danjon", "chauvenet", "physical"}) {
    const std::string csv = dir / (std::string(rule) + ".csv");
    const RunResult r = run(UMBRA_EXE, {"eclipses", "--from", "2018-07-27", "--to", "2018-07-27T23:59", "--kind", "lunar",
                                        "--lunar-shadow", rule, "--csv", csv});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = csvRows(csv);
    ASSERT_EQ(rows.size(), 1u);
    magnitude[rule] = std::stod(rows[0].at("magnitude"));
    if (std::string(rule) == "physical") {
      const std::smatch m = [&] {
        std::smatch match;
        std::regex_search(r.err, match, std::regex(R"(enlarged by ([0-9.]+) km)"));
        return match;
      }();
      ASSERT_EQ(m.size(), 2u) << r.err;
      EXPECT_GT(std::stod(m[1]), 60.0);
      EXPECT_LT(std::stod(m[1]), 110.0);
    }
  }
  EXPECT_NEAR(magnitude["danjon"], 1.6087, 0.002);
  EXPECT_NEAR(magnitude["chauvenet"] - magnitude["danjon"], 0.005, 0.003);
  EXPECT_NEAR(magnitude["physical"], magnitude["danjon"], 0.006);
  EXPECT_NEAR(magnitude["physical"], magnitude["chauvenet"], 0.006);
}

// eclipse path: a central eclipse gets its central line, limits and the outline of the
// partial eclipse; a partial one the outline alone.
TEST(EclipsesCli, PathsOnTheMap) {
  TempDir dir;
  const auto text = [](const std::string& path) { return readAll(path); };
  const RunResult total = run(UMBRA_EXE, {"eclipse", "path", "--date", "2017-08-21", "--step", "600", "--geojson", dir / "t.geojson"});
  ASSERT_EQ(total.exitCode, 0) << total.err;
  for (const char* name : {"\"central line\"", "\"northern limit\"", "\"southern limit\"", "\"outline of the partial eclipse\""})
    EXPECT_NE(text(dir / "t.geojson").find(name), std::string::npos) << name;
  const RunResult partial = run(UMBRA_EXE, {"eclipse", "path", "--date", "2025-03-29", "--geojson", dir / "p.geojson"});
  ASSERT_EQ(partial.exitCode, 0) << partial.err;
  EXPECT_NE(partial.out.find("no central line"), std::string::npos) << partial.out;
  EXPECT_NE(text(dir / "p.geojson").find("\"outline of the partial eclipse\""), std::string::npos);
  EXPECT_EQ(text(dir / "p.geojson").find("\"central line\""), std::string::npos);
  EXPECT_EQ(dir.fileCount(), 2);
}

TEST(EclipsesCli, BadInputIsOneLineAndNoFile) {
  TempDir dir;
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"eclipses", "--from", "2017-13-01", "--to", "2018-01-01", "--csv", dir / "a.csv"}, "--from/--to: invalid date '2017-13-01'"},
           {{"eclipses", "--from", "2018-01-01", "--to", "2017-01-01", "--csv", dir / "a.csv"}, "--to (2017-01-01) is before --from"},
           {{"eclipses", "--from", "-4000-01-01", "--to", "2017-01-01", "--csv", dir / "a.csv"}, "-3000..+5000"},
           {{"eclipses", "--from", "2017-01-01", "--to", "2018-01-01", "--kind", "stellar"}, "--kind"},
           {{"eclipses", "--from", "2017-01-01", "--to", "2018-01-01", "--csv", dir / "missing/a.csv"}, "missing"}}) {
    const RunResult bad = run(UMBRA_EXE, args);
    EXPECT_NE(bad.exitCode, 0) << message;
    EXPECT_NE(bad.err.find(message), std::string::npos) << "stderr: " << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
  EXPECT_EQ(dir.fileCount(), 0);
}

// An unknown command names itself and lists the commands.
TEST(EclipsesCli, AnUnknownCommandIsNamed) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"foo"}, {"--verbose", "foo", "--bar"}}) {
    const RunResult r = run(UMBRA_EXE, args);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("unknown command 'foo'"), std::string::npos) << r.err;
    for (const char* command : {"render", "eclipses", "atmosphere", "terrain"})
      EXPECT_NE(r.err.find(command), std::string::npos) << command;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const RunResult none = run(UMBRA_EXE, {});
  EXPECT_NE(none.exitCode, 0);
  EXPECT_NE(none.err.find("subcommand is required"), std::string::npos) << none.err;
}

}  // namespace
