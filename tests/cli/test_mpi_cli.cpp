// umbra across MPI ranks (mpirun -n 2, oversubscribed on a 2-core machine): the frames of
// an animation split over the ranks are the frames of one process; a failing or killed
// rank leaves no frames; the eclipse LuTs whose texels the ranks share are the LuTs of one
// process, to the byte; a sweep's CSV is the same over ranks, in one process and case by case;
// terrain lighting's time steps shared by the ranks give the maps and the CSV of one process.
#include "CliRunner.hpp"
#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace umbra::test;

namespace {

const std::string kScene = UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json";

/// `mpirun -n ranks umbra args...` (as root too, more ranks than cores allowed).
std::vector<std::string> mpirunArgs(int ranks, const std::vector<std::string>& args) {
  std::vector<std::string> a = {"-n", std::to_string(ranks), "--oversubscribe", "--allow-run-as-root", UMBRA_EXE};
  a.insert(a.end(), args.begin(), args.end());
  return a;
}

std::vector<std::string> animation(const std::string& output) {
  return {"render", kScene, "--size", "64x48", "--from", "2015-09-28T01:00:00Z", "--to", "2015-09-28T03:00:00Z",
          "--step", "30min", "--output", output};
}

/// The names in `dir`, sorted (hidden ones too).
std::vector<std::string> namesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

const std::vector<std::string> kFrames = {"f-00.png", "f-01.png", "f-02.png", "f-03.png", "f-04.png"};

}  // namespace

TEST(RenderMpi, FramesOverTwoRanksAreTheFramesOfOneProcess) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  std::filesystem::create_directory(dir / "one");
  std::filesystem::create_directory(dir / "two");
  const RunResult one = run(UMBRA_EXE, animation(dir / "one/f-%02d.png"), env);
  ASSERT_EQ(one.exitCode, 0) << one.err;
  // An empty cache for the ranks: one of them makes the shadow LuT, the other reads it.
  const RunResult two = run(UMBRA_MPIEXEC, mpirunArgs(2, animation(dir / "two/f-%02d.png")),
                            {"UMBRA_CACHE_DIR=" + dir / "cache-two"});
  ASSERT_EQ(two.exitCode, 0) << two.err;
  EXPECT_EQ(namesIn(dir / "two"), kFrames);  // no part file left
  for (const std::string& f : kFrames) EXPECT_EQ(readAll(dir / ("one/" + f)), readAll(dir / ("two/" + f))) << f;
  // One report, rank 0's, naming the ranks.
  EXPECT_EQ(std::count(two.out.begin(), two.out.end(), '\n'), 1) << two.out;
  EXPECT_NE(two.out.find("wrote 5 frames"), std::string::npos) << two.out;
  EXPECT_NE(two.out.find("on 2 ranks"), std::string::npos) << two.out;
  // The LuT made once (its lock gone), and the same as one process makes.
  std::vector<std::string> luts;
  for (const std::string& name : namesIn(dir / "cache-two")) {
    EXPECT_EQ(name.find(".lock"), std::string::npos) << name;
    if (name.rfind("eclipse-shadow-airless-", 0) == 0) luts.push_back(name);
  }
  ASSERT_EQ(luts.size(), 1u);
  EXPECT_EQ(readAll(dir / ("cache/" + luts[0])), readAll(dir / ("cache-two/" + luts[0])));
}

TEST(RenderMpi, ARankThatFailsLeavesNoFrames) {
  TempDir dir;
  std::filesystem::create_directory(dir / "frames");
  // The last frame (rank 1's) cannot be written: its part file's name is taken by a directory.
  std::filesystem::create_directory(dir / "frames/.f-04.part.png");
  const RunResult r = run(UMBRA_MPIEXEC, mpirunArgs(2, animation(dir / "frames/f-%02d.png")),
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_NE(r.exitCode, 0);
  // One error, from rank 0, naming the rank, the frame and why (mpirun adds its own lines).
  EXPECT_NE(r.err.find("umbra: error: rank 1: frame 4 (2015-09-28T03:00:00Z, " + dir / "frames/f-04.png" + "): "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("Is a directory"), std::string::npos) << r.err;
  std::size_t errors = 0;
  for (std::size_t at = r.err.find("umbra: error"); at != std::string::npos; at = r.err.find("umbra: error", at + 1))
    ++errors;
  EXPECT_EQ(errors, 1u) << r.err;
  EXPECT_EQ(namesIn(dir / "frames"), std::vector<std::string>{".f-04.part.png"});  // rank 0's frames gone too
}

TEST(RenderMpi, AKilledRankLeavesNoFramesAndAValidCache) {
  TempDir dir;
  std::filesystem::create_directory(dir / "frames");
  // 25 frames; once the first part file is there, the newest rank is killed.
  std::string command = quote(UMBRA_MPIEXEC);
  for (const std::string& a :
       mpirunArgs(2, {"render", kScene, "--size", "64x48", "--from", "2015-09-28T00:00:00Z", "--to",
                      "2015-09-28T04:00:00Z", "--step", "10min", "--output", dir / "frames/f-%02d.png"}))
    command += " " + quote(a);
  const std::string script = "UMBRA_CACHE_DIR=" + quote(dir / "cache") + " " + command + " >" + quote(dir / "out") +
                             " 2>" + quote(dir / "err") + " & m=$!; for i in $(seq 300); do ls " +
                             quote(dir / "frames") + "/.f-*.part.png >/dev/null 2>&1 && break; sleep 0.1; done; " +
                             "pkill -9 -n -P $m; wait $m; echo $? >" + quote(dir / "rc");
  ASSERT_EQ(std::system(("sh -c " + quote(script)).c_str()), 0);
  EXPECT_NE(std::stoi(readAll(dir / "rc")), 0);
  EXPECT_NE(readAll(dir / "err").find("signal 9"), std::string::npos) << readAll(dir / "err");
  for (const std::string& name : namesIn(dir / "frames")) EXPECT_EQ(name.rfind(".f-", 0), 0u) << name;  // parts only
  // The cache: complete tables only (no temporary, no lock), which a new run reads.
  for (const std::string& name : namesIn(dir / "cache")) {
    EXPECT_EQ(name.find(".lock"), std::string::npos) << name;
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
  }
  const RunResult again = run(UMBRA_EXE, animation(dir / "frames/g-%02d.png"), {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_EQ(again.exitCode, 0) << again.err;
}

TEST(PrecomputeMpi, LutsOverTwoRanksAreTheLutsOfOneProcessToTheByte) {
  TempDir dir;
  const std::vector<std::string> eclipse = {"precompute", "eclipse", "--occluder", "earth", "--atmosphere", "earth",
                                            "--size", "24", "--limb-lut-size", "8", "--layers", "2", "--draft-tables",
                                            "--orders", "2", "--limb-size", "32", "--scattering-cells", "8"};
  auto to = [&](const std::string& out) {
    std::vector<std::string> a = eclipse;
    a.insert(a.end(), {"--output", out});
    return a;
  };
  const RunResult one = run(UMBRA_EXE, to(dir / "one"), {"UMBRA_CACHE_DIR=" + dir / "cache-one"});
  ASSERT_EQ(one.exitCode, 0) << one.err;
  const RunResult two = run(UMBRA_MPIEXEC, mpirunArgs(2, to(dir / "two")), {"UMBRA_CACHE_DIR=" + dir / "cache-two"});
  ASSERT_EQ(two.exitCode, 0) << two.err;
  EXPECT_EQ(std::count(two.out.begin(), two.out.end(), '\n'), 3) << two.out;  // rank 0's report alone
  for (const std::string f : {"eclipse-shadow-atmosphere.exr", "eclipse-limb-luminance.exr"}) {
    EXPECT_EQ(readAll(dir / ("one/" + f)), readAll(dir / ("two/" + f))) << f;
  }
  // The cache holds what one process stores, and a second run over the ranks reads it.
  for (const std::string& name : namesIn(dir / "cache-one"))
    if (name.rfind("eclipse-", 0) == 0) { EXPECT_EQ(readAll(dir / ("cache-one/" + name)), readAll(dir / ("cache-two/" + name))); }
  const RunResult again = run(UMBRA_MPIEXEC, mpirunArgs(2, to(dir / "again")), {"UMBRA_CACHE_DIR=" + dir / "cache-two"});
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_NE(again.err.find("cache hit: "), std::string::npos) << again.err;
  EXPECT_EQ(readAll(dir / "one/eclipse-shadow-atmosphere.exr"), readAll(dir / "again/eclipse-shadow-atmosphere.exr"));

  // The airless LuT (precompute shadow), without the cache.
  const RunResult a1 = run(UMBRA_EXE, {"precompute", "shadow", "--occluder", "moon", "--size", "40", "--no-cache",
                                       "--output", dir / "airless-one.exr"});
  const RunResult a2 = run(UMBRA_MPIEXEC, mpirunArgs(2, {"precompute", "shadow", "--occluder", "moon", "--size", "40",
                                                         "--no-cache", "--output", dir / "airless-two.exr"}));
  ASSERT_EQ(a1.exitCode, 0) << a1.err;
  ASSERT_EQ(a2.exitCode, 0) << a2.err;
  EXPECT_EQ(readAll(dir / "airless-one.exr"), readAll(dir / "airless-two.exr"));
}

TEST(Mpi, ACommandOfOneRankRunsOnRankZeroAlone) {
  // Two ranks asked for one CSV: rank 0 writes it, the other exits.
  TempDir dir;
  const RunResult r = run(UMBRA_MPIEXEC, mpirunArgs(2, {"atmosphere", "refraction", "--preset", "earth", "--zenith-deg",
                                                        "80:90:5", "--csv", dir / "r.csv"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("this command runs on one rank"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(namesIn(dir.path.string()), std::vector<std::string>{"r.csv"});
}

TEST(PrecomputeMpi, AtmosphereTablesOverTwoRanksAreTheTablesOfOneProcessToTheByte) {
  // 5 wavelengths: batches of 3 and 2 (ceil(5 / 2)), one per rank; and batches of 1, three
  // for rank 0, two for rank 1.
  TempDir dir;
  std::vector<std::string> args = {"atmosphere", "precompute", "--preset", "earth", "--wavelengths", "5",
                                   "--transmittance-size", "16x8", "--scattering-size", "4,8,4,2",
                                   "--irradiance-size", "8x4", "--orders", "2", "--no-cache"};
  auto to = [&](const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> a = args;
    a.insert(a.end(), extra.begin(), extra.end());
    a.insert(a.end(), {"--output", out});
    return a;
  };
  const RunResult one = run(UMBRA_EXE, to(dir / "one", {}));
  ASSERT_EQ(one.exitCode, 0) << one.err;
  for (const auto& [name, extra] :
       std::vector<std::pair<std::string, std::vector<std::string>>>{{"two", {}}, {"ones", {"--wavelength-batch", "1"}}}) {
    const RunResult two = run(UMBRA_MPIEXEC, mpirunArgs(2, to(dir / name, extra)));
    ASSERT_EQ(two.exitCode, 0) << two.err;
    EXPECT_EQ(namesIn(dir / name), namesIn(dir / "one"));
    for (const std::string& f : namesIn(dir / "one"))
      EXPECT_EQ(readAll(dir / ("one/" + f)), readAll(dir / (name + "/" + f))) << name << " " << f;
  }
  // Through the cache: rank 0 stores them, a second run reads them on both ranks.
  args.pop_back();
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  ASSERT_EQ(run(UMBRA_MPIEXEC, mpirunArgs(2, to(dir / "cached", {})), env).exitCode, 0);
  const RunResult again = run(UMBRA_MPIEXEC, mpirunArgs(2, to(dir / "again", {})), env);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  for (const std::string& f : namesIn(dir / "one"))
    EXPECT_EQ(readAll(dir / ("one/" + f)), readAll(dir / ("again/" + f))) << f;
}

namespace {

/// A small sweep (draft tables, small limb views) over the stratospheric aerosol load.
std::string smallSweep(const std::string& grid) {
  return R"({"description": "test", "occluder": "earth", "atmosphere": "earth", "distance": "384400km",
            "offsetsKm": [2000], "tables": "draft", "orders": 2, "limbSize": 16, "scatteringCells": 4,
            "grid": {"/components/stratosphere/densityScale": )" +
         grid + "}}";
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// The CSV's rows without their first column (the case's number).
std::vector<std::string> rowsWithoutCase(const std::string& csv) {
  std::vector<std::string> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) rows.push_back(line.substr(line.find(',')));
  return rows;
}

}  // namespace

TEST(SweepMpi, TheCsvOverTwoRanksIsTheCsvOfOneProcessAndOfEachCaseAlone) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  writeText(dir / "sweep.json", smallSweep("[1, 10, 100]"));
  const RunResult one = run(UMBRA_EXE, {"sweep", dir / "sweep.json", "--csv", dir / "one.csv"}, env);
  ASSERT_EQ(one.exitCode, 0) << one.err;
  const RunResult two =
      run(UMBRA_MPIEXEC, mpirunArgs(2, {"sweep", dir / "sweep.json", "--csv", dir / "two.csv", "--plot",
                                        dir / "two.svg"}),
          {"UMBRA_CACHE_DIR=" + dir / "cache-two"});
  ASSERT_EQ(two.exitCode, 0) << two.err;
  const std::string csv = readAll(dir / "one.csv");
  EXPECT_EQ(csv, readAll(dir / "two.csv"));
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "case,/components/stratosphere/densityScale,centre_r,centre_g,centre_b,centre_luminance,"
            "centre_delta_v_mag,umbra_radius_km,penumbra_radius_km,luminance_at_2000km");
  EXPECT_NE(readAll(dir / "two.svg").find("Danjon scale"), std::string::npos);
  // Each case as a sweep of its own gives its row.
  const std::vector<std::string> rows = rowsWithoutCase(csv);
  ASSERT_EQ(rows.size(), 3u);
  const char* values[] = {"[1]", "[10]", "[100]"};
  for (int k = 0; k < 3; ++k) {
    writeText(dir / "alone.json", smallSweep(values[k]));
    ASSERT_EQ(run(UMBRA_EXE, {"sweep", dir / "alone.json", "--csv", dir / "alone.csv"}, env).exitCode, 0);
    EXPECT_EQ(rowsWithoutCase(readAll(dir / "alone.csv")), std::vector<std::string>{rows[k]}) << k;
  }
  // More aerosols, a darker umbra (the Moon's magnitude drop grows).
  std::vector<double> dropMag;
  for (const std::string& row : rows) {
    std::vector<std::string> cells;
    std::istringstream in(row.substr(1));
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    dropMag.push_back(std::stod(cells.at(5)));
  }
  EXPECT_LT(dropMag[0], dropMag[1]);
  EXPECT_LT(dropMag[1], dropMag[2]);
}

TEST(SweepMpi, TheFiguresAreTheExactProfilesAtTheSameOffsets) {
  // One case, the atmosphere as the preset has it: the centre and 2000 km of `umbra profile
  // shadow --exact` (two samples, 0 and 2000 km) with the same tables and limb views.
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  writeText(dir / "sweep.json", R"({"occluder": "earth", "atmosphere": "earth", "distance": "384400km",
      "offsetsKm": [2000], "tables": "draft", "orders": 2, "limbSize": 16, "scatteringCells": 4,
      "cases": [{"groundAlbedo": 0.1}]})");
  ASSERT_EQ(run(UMBRA_EXE, {"sweep", dir / "sweep.json", "--csv", dir / "s.csv"}, env).exitCode, 0);
  const RunResult p = run(UMBRA_EXE, {"profile", "shadow", "--occluder", "earth", "--atmosphere", "earth", "--exact",
                                      "--distance", "384400km", "--max-offset", "2000km", "--samples", "2",
                                      "--draft-tables", "--orders", "2", "--limb-size", "16", "--scattering-cells",
                                      "4", "--csv", dir / "p.csv"},
                          env);
  ASSERT_EQ(p.exitCode, 0) << p.err;
  const Csv profile = readCsv(dir / "p.csv");
  ASSERT_EQ(profile.rows.size(), 2u);
  const std::string row = rowsWithoutCase(readAll(dir / "s.csv")).at(0);
  std::vector<double> cells;
  std::istringstream in(row.substr(1));
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(std::stod(cell));
  // groundAlbedo, r, g, b, luminance, delta V, umbra, penumbra, luminance at 2000 km
  ASSERT_EQ(cells.size(), 9u);
  // (The sweep reads the atmosphere tables through their cache, in float; the profile
  // computes them in double: 1e-6 apart.)
  for (int q = 0; q < 4; ++q) EXPECT_NEAR(cells[1 + q], profile.rows[0][1 + q], 1e-6 * profile.rows[0][1 + q]) << q;
  EXPECT_NEAR(cells[8], profile.rows[1][4], 1e-6 * profile.rows[1][4]);
  EXPECT_NEAR(cells[5], -2.5 * std::log10(cells[4]), 1e-7);  // (both printed to 10 digits)
  // The geometric radii at the Moon: umbra ~4600 km, penumbra ~8200 km (from the profile's note).
  EXPECT_NE(p.out.find("umbra " + std::to_string(static_cast<int>(cells[6])).substr(0, 3)), std::string::npos) << p.out;
}

TEST(SweepMpi, ABadCaseOnOneRankLeavesNoCsvAndNamesTheCase) {
  TempDir dir;
  writeText(dir / "sweep.json", smallSweep("[1, 10, -1]"));  // the last case is rank 1's
  const RunResult r = run(UMBRA_MPIEXEC, mpirunArgs(2, {"sweep", dir / "sweep.json", "--csv", dir / "out.csv"}),
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("umbra: error: rank 1: " + dir / "sweep.json" + ": case 2 (/components/stratosphere/densityScale -1): "),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  for (const std::string& name : namesIn(dir.path.string())) EXPECT_EQ(name.find("out.csv"), std::string::npos) << name;
}

TEST(SweepCli, BadFilesNameTheFileAndTheField) {
  TempDir dir;
  struct Bad {
    std::string json, message;
  };
  for (const Bad& b : {Bad{"{", "not JSON"},
                       Bad{R"({"grid": {"groundAlbedo": [0.1]}, "cases": [{"groundAlbedo": 0.1}]})",
                           "give either \"grid\" or \"cases\""},
                       Bad{R"({"grid": {"groundAlbedo": [0.1]}, "colour": 1})", "colour: unknown key"},
                       Bad{R"({"grid": {"/components/nosuch/densityScale": [1]}})",
                           "/components/nosuch/densityScale: no such object in the atmosphere earth"},
                       Bad{R"({"grid": {"groundAlbedo": []}})", "grid.groundAlbedo: expected a non-empty list"},
                       Bad{R"({"cases": [{"groundAlbedo": 0.1}, {"distance": "1km"}]})", "cases[1]: no \"groundAlbedo\""},
                       Bad{R"({"grid": {"distance": [384400]}})", "distance: expected a length with its unit"},
                       Bad{R"({"tables": "huge", "grid": {"groundAlbedo": [0.1]}})", "tables: expected"}}) {
    writeText(dir / "bad.json", b.json);
    const RunResult r = run(UMBRA_EXE, {"sweep", dir / "bad.json", "--csv", dir / "out.csv"});
    EXPECT_EQ(r.exitCode, 1) << b.json;
    EXPECT_NE(r.err.find(dir / "bad.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(b.message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  }
}

// 13 steps over 3 ranks (5, 4 and 4): the CSV is the one process's to the byte; the maps
// agree to the rounding of their sums (a crater floor's shadow runs across both joins).
TEST(TerrainLightingMpi, StepsOverThreeRanksGiveTheMapsOfOneProcess) {
  TempDir dir;
  auto args = [&](const std::string& name) {
    return std::vector<std::string>{"terrain", "lighting", "--synthetic", "7", "--size", "96", "--from",
                                    "2024-03-01T00:00:00Z", "--to", "2024-03-02T00:00:00Z", "--step", "2h", "--point",
                                    "48,48", "--point", "10,80", "--csv", dir / (name + ".csv"), "--output",
                                    dir / (name + ".exr")};
  };
  const RunResult one = run(UMBRA_EXE, args("one"));
  ASSERT_EQ(one.exitCode, 0) << one.err;
  const RunResult three = run(UMBRA_MPIEXEC, mpirunArgs(3, args("three")));
  ASSERT_EQ(three.exitCode, 0) << three.err;
  EXPECT_NE(three.out.find("on 3 ranks"), std::string::npos) << three.out;
  EXPECT_EQ(readAll(dir / "one.csv"), readAll(dir / "three.csv"));
  const umbra::tables::Table a = umbra::tables::readExr(dir / "one.exr"), b = umbra::tables::readExr(dir / "three.exr");
  ASSERT_EQ(a.data.size(), b.data.size());
  double longest = 0.0;
  for (std::size_t k = 0; k < a.data.size(); ++k) {
    ASSERT_NEAR(a.data[k], b.data[k], k % 3 == 1 ? 1e-3 : 1e-6) << k;  // (channel 1: seconds)
    if (k % 3 == 1) longest = std::max<double>(longest, a.data[k]);
  }
  EXPECT_EQ(longest, 86400.0);  // dark all day somewhere: across both joins
}
