// cachedOrComputed: tables read from the cache when all the needed ones match, else
// computed together and stored; a store that fails is a warning.

#include "TestSupport.h"
#include "umbra/tables/CachedTables.h"

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

}  // namespace
}  // namespace umbra::tables::test
