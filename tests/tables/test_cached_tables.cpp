// cachedOrComputed: tables read from the cache when all the needed ones match, else
// computed together and stored; a store that fails is a warning.

#include "TestSupport.h"
#include "umbra/tables/CachedTables.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

namespace umbra::tables::test {
namespace {

using CachedTablesTest = TempDirTest;

std::vector<TableRequest> twoRequests(bool secondNeeded = true) {
  TableRequest a{"lut-a", {{"size", "8"}}, 8, 4, {"R", "G", "B"}, true};
  TableRequest b{"lut-b", {{"size", "8"}}, 8, 4, {"Y"}, secondNeeded};
  return {a, b};
}

std::vector<Table> twoTables(int width = 8) { return {makeTable(width, 4, {"R", "G", "B"}), makeTable(width, 4, {"Y"})}; }

TEST_F(CachedTablesTest, ComputedOnceThenRead) {
  const TableCache cache(dir_.string());
  int calls = 0;
  const auto compute = [&] {
    ++calls;
    return twoTables();
  };
  CacheOutcome first, second;
  const std::vector<Table> made = cachedOrComputed(cache, true, twoRequests(), compute, first);
  const std::vector<Table> read = cachedOrComputed(cache, true, twoRequests(), compute, second);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(first.computed, 2);
  EXPECT_EQ(first.hits, 0);
  EXPECT_EQ(second.hits, 2);
  EXPECT_EQ(second.computed, 0);
  ASSERT_EQ(read.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read[i].data, made[i].data);  // float values: the EXR's round trip is exact
    EXPECT_EQ(read[i].channels, made[i].channels);
  }
}

TEST_F(CachedTablesTest, OnlyTheNeededMustMatchAndCount) {
  const TableCache cache(dir_.string());
  CacheOutcome o;
  cachedOrComputed(cache, true, twoRequests(), [] { return twoTables(); }, o);
  std::filesystem::remove(cache.pathFor("lut-b", {{"size", "8"}}));
  int calls = 0;
  const std::vector<Table> t = cachedOrComputed(cache, true, twoRequests(false), [&] {
    ++calls;
    return twoTables();
  }, o);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(o.hits, 1);
  EXPECT_EQ(t[1].width, 0);  // not needed: left empty
  // Needed and missing: everything computed again and stored, counted for the needed only.
  cachedOrComputed(cache, true, twoRequests(), [&] {
    ++calls;
    return twoTables();
  }, o);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(o.computed, 2);
  EXPECT_TRUE(std::filesystem::exists(cache.pathFor("lut-b", {{"size", "8"}})));
}

TEST_F(CachedTablesTest, ACachedTableOfAnotherSizeIsComputedAgain) {
  const TableCache cache(dir_.string());
  CacheOutcome o;
  cachedOrComputed(cache, true, twoRequests(), [] { return twoTables(16); }, o);  // stored 16 wide
  int calls = 0;
  const std::vector<Table> t = cachedOrComputed(cache, true, twoRequests(), [&] {
    ++calls;
    return twoTables();
  }, o);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(t[0].width, 8);
}

TEST_F(CachedTablesTest, WithoutTheCacheNothingIsReadNorStored) {
  const TableCache cache(dir_.string());
  CacheOutcome o;
  cachedOrComputed(cache, true, twoRequests(), [] { return twoTables(); }, o);
  int calls = 0;
  cachedOrComputed(cache, false, twoRequests(), [&] {
    ++calls;
    return twoTables();
  }, o);
  EXPECT_EQ(calls, 1);
  const TableCache other((dir_ / "other").string());
  cachedOrComputed(other, false, twoRequests(), [] { return twoTables(); }, o);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "other"));
}

TEST_F(CachedTablesTest, FailuresAreTheComputationsOrWarnings) {
  // A computation that throws stores nothing; one that gives too few tables is a logic error.
  const TableCache cache(dir_.string());
  CacheOutcome o;
  EXPECT_THROW(cachedOrComputed(cache, true, twoRequests(), []() -> std::vector<Table> { throw std::runtime_error("x"); }, o),
               std::runtime_error);
  EXPECT_TRUE(entries(dir_).empty());
  EXPECT_THROW(cachedOrComputed(cache, true, twoRequests(), [] { return std::vector<Table>(1); }, o), std::logic_error);
  // A cache that cannot be written (its directory is a file): the tables, and a warning.
  writeBytes(file("not-a-dir"), "x");
  const TableCache blocked(file("not-a-dir") + "/cache");
  const std::vector<Table> t = cachedOrComputed(blocked, true, twoRequests(), [] { return twoTables(); }, o);
  EXPECT_EQ(t.size(), 2u);
  EXPECT_EQ(o.computed, 2);
  EXPECT_FALSE(o.warning.empty());
}

// One of the processes of ProcessesAskingAtOnceComputeOnce (this program run again, with
// the cache's directory in UMBRA_TEST_LOCK_DIR): appends "computed", "read" or "wrong" to
// the directory's log.
TEST(CachedTablesProcess, DISABLED_OneOfSeveral) {
  const char* dir = std::getenv("UMBRA_TEST_LOCK_DIR");
  ASSERT_NE(dir, nullptr);
  const TableCache cache(std::string(dir) + "/cache");
  CacheOutcome o;
  const std::vector<Table> t = cachedOrComputed(cache, true, twoRequests(), [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    return twoTables();
  }, o);
  const bool same = t.size() == 2 && t[0].data == twoTables()[0].data && t[1].data == twoTables()[1].data;
  std::ofstream(std::string(dir) + "/log", std::ios::app)
      << (!same ? "wrong" : o.hits == 2 ? "read" : o.computed == 2 ? "computed" : "wrong") << "\n";
}

TEST_F(CachedTablesTest, ProcessesAskingAtOnceComputeOnce) {
  // Three processes (the ranks of an MPI run) ask for the same missing tables at once: one
  // computes them (slowly), the others wait for its lock and read what it stored.
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string command = "UMBRA_TEST_LOCK_DIR='" + dir_.string() + "' '" + self +
                              "' --gtest_also_run_disabled_tests --gtest_filter=CachedTablesProcess.DISABLED_OneOfSeveral"
                              " >/dev/null";
  ASSERT_EQ(std::system(("sh -c \"" + command + " & " + command + " & " + command + " & wait\"").c_str()), 0);
  std::ifstream in(file("log"));
  std::vector<std::string> outcomes;
  for (std::string line; std::getline(in, line);) outcomes.push_back(line);
  std::sort(outcomes.begin(), outcomes.end());
  EXPECT_EQ(outcomes, (std::vector<std::string>{"computed", "read", "read"}));
  for (const std::string& name : entries(dir_ / "cache")) EXPECT_EQ(name.find(".lock"), std::string::npos) << name;
}

TEST_F(CachedTablesTest, AFailedComputationReleasesTheLock) {
  const TableCache cache(dir_.string());
  CacheOutcome o;
  EXPECT_THROW(cachedOrComputed(cache, true, twoRequests(), []() -> std::vector<Table> { throw std::runtime_error("x"); }, o),
               std::runtime_error);
  // Were the lock still held, this would wait for ever (flock: a second descriptor waits).
  const std::vector<Table> t = cachedOrComputed(cache, true, twoRequests(), [] { return twoTables(); }, o);
  EXPECT_EQ(o.computed, 2);
  EXPECT_EQ(entries(dir_).size(), 2u);  // the two tables; no lock file
}

}  // namespace
}  // namespace umbra::tables::test
