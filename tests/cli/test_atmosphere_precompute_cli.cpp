// `umbra atmosphere precompute`: one EXR per table in the output directory, readable, with
// the right channels and no non-finite value; the cache; bad input leaves nothing behind.
#include "CliRunner.hpp"
#include "Precompute.hpp"
#include "TableSizes.hpp"

#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

using namespace umbra::test;
namespace fs = std::filesystem;

namespace {
/// Tiny tables: the whole run takes a fraction of a second.
std::vector<std::string> tiny(std::vector<std::string> args) {
  for (const char* a : {"--transmittance-size", "16x8", "--scattering-size", "4,8,4,2", "--irradiance-size", "8x4",
                        "--orders", "2"})
    args.push_back(a);
  return args;
}

std::vector<std::string> filesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}
} // namespace

TEST(AtmospherePrecomputeCli, WritesOneExrPerTable) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, tiny({"atmosphere", "precompute", "--preset", "earth", "--output", dir / "tables",
                                           "--cache-dir", dir / "cache"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto files = filesIn(dir / "tables");
  for (const char* f : {"atmosphere-transmittance.exr", "atmosphere-single-scattering-molecules.exr",
                        "atmosphere-multiple-scattering.exr", "atmosphere-direct-irradiance.exr",
                        "atmosphere-irradiance.exr"}) {
    EXPECT_NE(std::find(files.begin(), files.end(), f), files.end()) << f;
    EXPECT_NE(r.out.find(f), std::string::npos) << r.out;
  }
  EXPECT_EQ(std::find(files.begin(), files.end(), "atmosphere-refraction.exr"), files.end());
  for (const std::string& f : files) {
    const umbra::tables::Table t = umbra::tables::readExr(dir / ("tables/" + f));
    EXPECT_EQ(t.channels, (std::vector<std::string>{"L680nm", "L550nm", "L440nm"})) << f;
    EXPECT_EQ(t.parameters.at("kind") + ".exr", f);
    if (f.find("scattering") != std::string::npos) {
      EXPECT_EQ(t.width, 8) << f;
      EXPECT_EQ(t.height, 32) << f;
      EXPECT_EQ(t.parameters.at("depth"), "4");
    }
  }
  const RunResult inspect = run(UMBRA_EXE, {"inspect", dir / "tables/atmosphere-multiple-scattering.exr"});
  ASSERT_EQ(inspect.exitCode, 0) << inspect.err;
  EXPECT_NE(inspect.out.find("non-finite 0"), std::string::npos) << inspect.out;
  EXPECT_EQ(inspect.out.find("non-finite 1"), std::string::npos) << inspect.out;

  // The same again: every table from the cache.
  const RunResult again = run(UMBRA_EXE, tiny({"atmosphere", "precompute", "--preset", "earth", "--output",
                                               dir / "again", "--cache-dir", dir / "cache"}));
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_NE(again.err.find("cache hit"), std::string::npos) << again.err;
  EXPECT_EQ(filesIn(dir / "again"), files);
}

// The Lorenz-Mie optics of the default sky's aerosols (OPAC's three continental components
// and the stratospheric sulphate, at each wavelength) go into the table cache beside the
// tables; a run with other table sizes reads them and writes none; --no-cache leaves the
// cache alone.
TEST(AtmospherePrecomputeCli, TheLorenzMieOpticsAreCachedBesideTheTables) {
  TempDir dir;
  auto mieFiles = [&] {
    std::vector<std::string> names;
    if (fs::exists(dir / "cache"))
      for (const std::string& f : filesIn(dir / "cache"))
        if (f.rfind("mie-optics-", 0) == 0 && f.size() > 5 && f.substr(f.size() - 5) == ".json") names.push_back(f);
    return names;
  };
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  const RunResult first = run(UMBRA_EXE, tiny({"atmosphere", "precompute", "--preset", "earth", "--output", dir / "a"}), env);
  ASSERT_EQ(first.exitCode, 0) << first.err;
  const std::vector<std::string> written = mieFiles();
  EXPECT_EQ(written.size(), 4u * 3u);  // 4 populations, 3 wavelengths
  auto inode = [&](const std::string& name) {
    struct stat st {};
    return ::stat((dir / ("cache/" + name)).c_str(), &st) == 0 ? st.st_ino : 0;
  };
  const auto before = inode(written.front());

  std::vector<std::string> other = tiny({"atmosphere", "precompute", "--preset", "earth", "--output", dir / "b"});
  other[other.size() - 1] = "3";  // --orders 3: every table misses
  const RunResult second = run(UMBRA_EXE, other, env);
  ASSERT_EQ(second.exitCode, 0) << second.err;
  EXPECT_EQ(mieFiles(), written);
  EXPECT_EQ(inode(written.front()), before);  // read, not written again
  EXPECT_EQ(umbra::tables::readExr(dir / "b/atmosphere-transmittance.exr").data,
            umbra::tables::readExr(dir / "a/atmosphere-transmittance.exr").data);

  const std::vector<std::string> elsewhere{"UMBRA_CACHE_DIR=" + dir / "untouched"};
  const RunResult off = run(UMBRA_EXE, tiny({"atmosphere", "precompute", "--preset", "earth", "--output", dir / "c",
                                             "--no-cache"}), elsewhere);
  ASSERT_EQ(off.exitCode, 0) << off.err;
  EXPECT_FALSE(fs::exists(dir / "untouched"));
}

TEST(AtmospherePrecomputeCli, RefractionAndWavelengths) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, tiny({"atmosphere", "precompute", "--preset", "mars", "--refraction",
                                           "--refraction-size", "32x16", "--wavelengths", "5", "--output", dir / "t", "--no-cache"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "t/atmosphere-refraction.exr"));
  const umbra::tables::Table t = umbra::tables::readExr(dir / "t/atmosphere-transmittance.exr");
  EXPECT_EQ(t.channels.size(), 5u);
  EXPECT_EQ(t.channels[0], "L407nm");  // 360 + 0.5 * 470 / 5
  EXPECT_EQ(t.parameters.at("refractedPaths"), "1");
}

// --wavelength-batch: 5 wavelengths 2 at a time give the same tables, to the bit, as all at
// once; a batch outside 0..256 is refused naming the option.
TEST(AtmospherePrecomputeCli, WavelengthBatchesGiveTheSameTables) {
  TempDir dir;
  auto args = [&](const std::string& out, const std::string& batch) {
    return tiny({"atmosphere", "precompute", "--preset", "earth", "--wavelengths", "5", "--wavelength-batch", batch,
                 "--output", dir / out, "--no-cache"});
  };
  const RunResult all = run(UMBRA_EXE, args("all", "0"));
  ASSERT_EQ(all.exitCode, 0) << all.err;
  const RunResult batched = run(UMBRA_EXE, args("batched", "2"));
  ASSERT_EQ(batched.exitCode, 0) << batched.err;
  const auto files = filesIn(dir / "all");
  ASSERT_EQ(filesIn(dir / "batched"), files);
  for (const std::string& f : files) {
    const umbra::tables::Table a = umbra::tables::readExr(dir / ("all/" + f)), b = umbra::tables::readExr(dir / ("batched/" + f));
    EXPECT_EQ(a.channels.size(), 5u) << f;
    EXPECT_EQ(a.data, b.data) << f;
  }
  const RunResult bad = run(UMBRA_EXE, args("bad", "-1"));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--wavelength-batch"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

// --spill always: the tables but J_k through a temporary file in $TMPDIR give the same
// tables, to the bit, as all in memory (tables of 2 MiB a wavelength batch: the least that
// spills); with $TMPDIR missing the run fails naming it and writes nothing, and --spill never
// does not need it. A --spill that is none of the three is refused naming the option.
TEST(AtmospherePrecomputeCli, SpilledTablesAreTheSame) {
  TempDir dir;
  auto args = [&](const std::string& out, const std::string& spill) {
    return std::vector<std::string>{"atmosphere", "precompute", "--preset", "earth", "--wavelengths", "4",
                                    "--transmittance-size", "16x8", "--scattering-size", "16,32,16,16",
                                    "--irradiance-size", "8x4", "--orders", "3", "--spill", spill,
                                    "--output", dir / out, "--no-cache"};
  };
  const std::string tmp = "TMPDIR=" + (dir / "tmp");
  fs::create_directory(dir / "tmp");
  const RunResult memory = run(UMBRA_EXE, args("memory", "never"));
  ASSERT_EQ(memory.exitCode, 0) << memory.err;
  const RunResult spilled = run(UMBRA_EXE, args("spilled", "always"), {tmp});
  ASSERT_EQ(spilled.exitCode, 0) << spilled.err;
  const auto files = filesIn(dir / "memory");
  ASSERT_EQ(filesIn(dir / "spilled"), files);
  for (const std::string& f : files) {
    const umbra::tables::Table a = umbra::tables::readExr(dir / ("memory/" + f));
    const umbra::tables::Table b = umbra::tables::readExr(dir / ("spilled/" + f));
    EXPECT_EQ(a.data, b.data) << f;
  }
  EXPECT_TRUE(fs::is_empty(dir / "tmp"));  // the file was never named, or unlinked at once

  const std::string missing = "TMPDIR=" + (dir / "no-such-dir");
  const RunResult failed = run(UMBRA_EXE, args("failed", "always"), {missing});
  EXPECT_NE(failed.exitCode, 0);
  EXPECT_NE(failed.err.find("no-such-dir"), std::string::npos) << failed.err;
  EXPECT_FALSE(fs::exists(dir / "failed"));
  EXPECT_EQ(run(UMBRA_EXE, args("never", "never"), {missing}).exitCode, 0);

  const RunResult bad = run(UMBRA_EXE, args("bad", "sometimes"));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--spill"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

TEST(AtmospherePrecomputeCli, BadInputWritesNothing) {
  TempDir dir;
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"--preset", "pluto", "--output", dir / "t"}, "pluto"},
      {{"--preset", "earth", "--orders", "0", "--output", dir / "t"}, "--orders"},
      {{"--preset", "earth", "--output", dir / "missing/t"}, "does not exist"},
      {{"--preset", "earth", "--scattering-size", "4,7,4,2", "--output", dir / "t"}, "--scattering-size"},
      {{"--preset", "earth", "--transmittance-size", "16", "--output", dir / "t"}, "--transmittance-size"},
      {{"--output", dir / "t"}, "--preset"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"atmosphere", "precompute", "--cache-dir", dir / "cache"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    if (c.message != "--orders") args.insert(args.end(), {"--orders", "2"});
    const RunResult r = run(UMBRA_EXE, args);
    EXPECT_NE(r.exitCode, 0) << c.message;
    EXPECT_NE(r.err.find("umbra: error:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(dir.fileCount(), 0) << c.message;
  }
}

// Killed while it computes (kill -9): no DIR, only its hidden staging directory, which the
// next run removes (its process is gone) before it writes DIR whole.
TEST(AtmospherePrecomputeCli, AKilledRunLeavesNoHalfFilledDirectory) {
  TempDir dir;
  const std::string out = dir / "tables";
  // The default sizes take seconds: killed after half a second, mid-way.
  const std::string cmd = std::string("(") + UMBRA_EXE + " atmosphere precompute --preset earth --no-cache --output " +
                          quote(out) + " >/dev/null 2>&1 & pid=$!; sleep 0.5; kill -9 $pid; wait $pid) 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()) == -1, false);
  EXPECT_FALSE(fs::exists(out));
  // A staging directory a killed run left while it wrote (no process 999999999).
  fs::create_directories(dir / ".tables.tmp-999999999");
  std::ofstream(dir / ".tables.tmp-999999999/atmosphere-transmittance.exr") << "half";
  const RunResult r = run(UMBRA_EXE, tiny({"atmosphere", "precompute", "--preset", "earth", "--output", out,
                                           "--no-cache"}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(filesIn(out).size(), 7u);  // transmittance, 3 single scattering, multiple, 2 irradiance
  EXPECT_EQ(filesIn(dir.path.string()), std::vector<std::string>{"tables"});  // no staging left
}

// The command's bounds and defaults are the library's (atmosphere/TableSizes.hpp): the
// largest sizes pass PrecomputeOptions::validate and one more fails there and on the
// command line, whose message names the bound; the help shows the default sizes.
TEST(AtmospherePrecomputeCli, SizesAndBoundsAreTheLibrarys) {
  using namespace umbra::atmosphere;
  PrecomputeOptions po;
  EXPECT_EQ(po.scatteringMu, kDefaultTableSizes.scattering[1]);
  EXPECT_EQ(po.transmittanceWidth, kDefaultTableSizes.transmittance[0]);
  po.scatteringNu = kMaxScatteringCells;
  po.orders = kMaxOrders;
  po.transmittanceWidth = kMaxTableSide;
  EXPECT_EQ(po.validate(), "");
  po.scatteringNu = kMaxScatteringCells + 1;
  EXPECT_NE(po.validate().find(std::to_string(kMaxScatteringCells)), std::string::npos) << po.validate();
  EXPECT_EQ(PrecomputeOptions().withSizes(kSmallTableSizes).irradianceWidth, kSmallTableSizes.irradiance[0]);

  TempDir dir;
  const std::string tooMany = "8,32,8," + std::to_string(kMaxScatteringCells + 1);
  const RunResult bad = run(UMBRA_EXE, {"atmosphere", "precompute", "--preset", "earth", "--scattering-size", tooMany,
                                        "--output", dir / "bad"});
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--scattering-size: expected R, MU_S, NU in 2.." + std::to_string(kMaxScatteringCells)),
            std::string::npos)
      << bad.err;
  const RunResult orders = run(UMBRA_EXE, {"atmosphere", "precompute", "--preset", "earth", "--orders",
                                           std::to_string(kMaxOrders + 1), "--output", dir / "bad"});
  EXPECT_NE(orders.err.find("--orders: expected 1 to " + std::to_string(kMaxOrders)), std::string::npos) << orders.err;
  EXPECT_FALSE(fs::exists(dir / "bad"));
  const RunResult help = run(UMBRA_EXE, {"atmosphere", "precompute", "--help"});
  EXPECT_NE(help.out.find(sizeText(kDefaultTableSizes.scattering)), std::string::npos) << help.out;
}
