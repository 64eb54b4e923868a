// The table cache as the command line uses it: a damaged table is rebuilt and the run says
// so, naming the file; two processes building the same table at once agree and leave one
// table and no temporary behind.
#include "CliRunner.hpp"

#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace umbra::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> precomputeArgs(const TempDir& dir, const std::string& output) {
  return {"precompute", "shadow", "--occluder", "Earth", "--size", "32", "--output", dir / output};
}

std::vector<fs::path> cacheFiles(const fs::path& cache) {
  std::vector<fs::path> files;
  if (fs::exists(cache))
    for (const auto& e : fs::directory_iterator(cache)) files.push_back(e.path());
  return files;
}

bool allFinite(const umbra::tables::Table& t) {
  for (float v : t.data)
    if (!std::isfinite(v)) return false;
  return !t.data.empty();
}

} // namespace

// The cached LuT's values turned to NaN under its own header: the next run warns, naming
// the file, computes the LuT again (a finite one) and caches it; the run after that hits.
TEST(CacheCli, ADamagedTableIsRebuiltAndTheRunSaysSo) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  ASSERT_EQ(run(UMBRA_EXE, precomputeArgs(dir, "a.exr"), env).exitCode, 0);
  const auto files = cacheFiles(dir.path / "cache");
  ASSERT_EQ(files.size(), 1u);
  const std::string cached = files.front().string();

  umbra::tables::Table damaged = umbra::tables::readExr(cached);
  for (std::size_t i = 0; i < damaged.data.size(); i += 7) damaged.data[i] = std::nanf("");
  umbra::tables::writeExr(cached, damaged);

  const RunResult rebuilt = run(UMBRA_EXE, precomputeArgs(dir, "b.exr"), env);
  ASSERT_EQ(rebuilt.exitCode, 0) << rebuilt.err;
  EXPECT_NE(rebuilt.err.find("umbra: cache: " + cached), std::string::npos) << rebuilt.err;
  EXPECT_NE(rebuilt.err.find("computing it again"), std::string::npos) << rebuilt.err;
  EXPECT_NE(rebuilt.err.find("cached: " + cached), std::string::npos) << rebuilt.err;
  EXPECT_TRUE(allFinite(umbra::tables::readExr(dir / "b.exr")));
  EXPECT_EQ(umbra::tables::readExr(dir / "b.exr").data, umbra::tables::readExr(dir / "a.exr").data);

  const RunResult hit = run(UMBRA_EXE, precomputeArgs(dir, "c.exr"), env);
  ASSERT_EQ(hit.exitCode, 0) << hit.err;
  EXPECT_NE(hit.err.find("cache hit: " + cached), std::string::npos) << hit.err;
  EXPECT_EQ(hit.err.find("umbra: cache:"), std::string::npos) << hit.err;
}

// Two processes build the same LuT into one cache at the same moment: both succeed with
// the same table, the cache holds it once and no temporary is left.
TEST(CacheCli, TwoWritersAtOnceAgree) {
  TempDir dir;
  std::string command = "export UMBRA_CACHE_DIR=" + quote(dir / "cache") + "; ";
  for (const char* name : {"a", "b"}) {
    command += quote(UMBRA_EXE);
    for (const std::string& a : precomputeArgs(dir, std::string(name) + ".exr")) command += " " + quote(a);
    command += " 2>" + quote(dir / (std::string(name) + ".log")) + " & " + name + "=$!; ";
  }
  command += "wait $a; x=$?; wait $b; y=$?; exit $((x + y))";
  const RunResult both = run("bash", {"-c", command});
  EXPECT_EQ(both.exitCode, 0) << readAll(dir / "a.log") << readAll(dir / "b.log");
  const auto files = cacheFiles(dir.path / "cache");
  ASSERT_EQ(files.size(), 1u) << "one table, no temporary";
  EXPECT_EQ(files.front().extension(), ".exr");
  const auto a = umbra::tables::readExr(dir / "a.exr"), b = umbra::tables::readExr(dir / "b.exr");
  EXPECT_TRUE(allFinite(a));
  EXPECT_EQ(a.data, b.data);
  EXPECT_EQ(a.data, umbra::tables::readExr(files.front().string()).data);
}
