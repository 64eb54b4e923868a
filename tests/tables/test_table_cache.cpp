// TableCache: default directory, keys, hits, misses and failures.

#include <unistd.h>

#include "TestSupport.h"
#include "umbra/tables/Exr.h"
#include "umbra/tables/TableCache.h"

namespace umbra::tables::test {
namespace {

using Parameters = std::map<std::string, std::string>;

class TableCacheTest : public TempDirTest {
protected:
  const Parameters params_ = {{"size", "16"}, {"radius", "6371000"}, {"order", "4"}};
  Parameters withKind(const std::string& kind) const {
    Parameters p = params_;
    p["kind"] = kind;
    return p;
  }
};

TEST(TableCacheDefaults, DirectoryHonoursUmbraCacheDirThenXdgThenHome) {
  ScopedEnv umbra("UMBRA_CACHE_DIR", "/cache/umbra-here");
  ScopedEnv xdg("XDG_CACHE_HOME", "/xdg/cache");
  ScopedEnv home("HOME", "/home/someone");
  EXPECT_EQ(TableCache::defaultDirectory(), "/cache/umbra-here");
  {
    ScopedEnv empty("UMBRA_CACHE_DIR", "");
    EXPECT_EQ(TableCache::defaultDirectory(), "/xdg/cache/umbra");
  }
  {
    ScopedEnv unset("UMBRA_CACHE_DIR", nullptr);
    EXPECT_EQ(TableCache::defaultDirectory(), "/xdg/cache/umbra");
    {
      ScopedEnv noXdg("XDG_CACHE_HOME", nullptr);
      EXPECT_EQ(TableCache::defaultDirectory(), "/home/someone/.cache/umbra");
    }
    {
      ScopedEnv emptyXdg("XDG_CACHE_HOME", "");
      EXPECT_EQ(TableCache::defaultDirectory(), "/home/someone/.cache/umbra");
    }
    {
      ScopedEnv relativeXdg("XDG_CACHE_HOME", "relative/cache");  // invalid per the XDG spec
      EXPECT_EQ(TableCache::defaultDirectory(), "/home/someone/.cache/umbra");
    }
    {
      ScopedEnv noXdg("XDG_CACHE_HOME", nullptr);
      ScopedEnv noHome("HOME", nullptr);
      const std::string dir = TableCache::defaultDirectory();
      EXPECT_FALSE(dir.empty());
      EXPECT_NE(dir.find("umbra"), std::string::npos) << dir;
    }
  }
  EXPECT_EQ(TableCache::defaultDirectory(), "/cache/umbra-here");  // restored
}

TEST_F(TableCacheTest, PathIsKindAndParameterHashInTheDirectory) {
  const TableCache cache(dir_.string());
  EXPECT_EQ(cache.directory(), dir_.string());
  EXPECT_EQ(cache.pathFor("shadow-lut", params_),
            (dir_ / ("shadow-lut-" + parameterHash(params_) + ".exr")).string());
  EXPECT_NE(cache.pathFor("shadow-lut", params_), cache.pathFor("limb-lut", params_));
  for (const char* bad : {"", "../up", "a/b", ".hidden", "sp ace"}) {
    EXPECT_THROW(cache.pathFor(bad, params_), std::invalid_argument) << bad;
  }
  Parameters conflicting = params_;
  conflicting["kind"] = "other";
  EXPECT_THROW(cache.pathFor("shadow-lut", conflicting), std::invalid_argument);
}

TEST_F(TableCacheTest, DirectoryIsCreatedOnFirstStore) {
  const fs::path nested = dir_ / "a" / "b";
  const TableCache cache(nested.string());
  EXPECT_FALSE(cache.load("shadow", params_).has_value());
  EXPECT_FALSE(fs::exists(dir_ / "a"));
  cache.store("shadow", params_, makeTable(4, 2, {"R", "G", "B"}));
  EXPECT_TRUE(fs::is_directory(nested));
  EXPECT_EQ(entries(nested), std::vector<std::string>{fs::path(cache.pathFor("shadow", params_))
                                                          .filename()
                                                          .string()});
}

TEST_F(TableCacheTest, StoreThenLoadHits) {
  const TableCache cache(dir_.string());
  Table t = makeTable(5, 3, {"R", "G", "B"});
  t.parameters = {{"ignored", "yes"}};  // the cache writes its own parameters
  cache.store("shadow", params_, t);

  const std::optional<Table> hit = cache.load("shadow", params_);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->width, 5);
  EXPECT_EQ(hit->height, 3);
  EXPECT_EQ(hit->channels, t.channels);
  EXPECT_EQ(hit->data, t.data);
  EXPECT_EQ(hit->parameters, withKind("shadow"));
  EXPECT_EQ(readExr(cache.pathFor("shadow", params_)).parameters, withKind("shadow"));
}

TEST_F(TableCacheTest, ChangedParameterOrKindMisses) {
  const TableCache cache(dir_.string());
  cache.store("shadow", params_, makeTable(2, 2, {"Y"}));
  ASSERT_TRUE(cache.load("shadow", params_).has_value());

  Parameters changed = params_;
  changed["size"] = "32";
  EXPECT_FALSE(cache.load("shadow", changed).has_value());
  Parameters added = params_;
  added["wavelengths"] = "3";
  EXPECT_FALSE(cache.load("shadow", added).has_value());
  Parameters removed = params_;
  removed.erase("order");
  EXPECT_FALSE(cache.load("shadow", removed).has_value());
  EXPECT_FALSE(cache.load("limb", params_).has_value());
}

TEST_F(TableCacheTest, CorruptCachedFileMissesAndIsOverwritten) {
  const TableCache cache(dir_.string());
  const Table t = makeTable(32, 32, {"R", "G", "B"});
  cache.store("shadow", params_, t);
  const std::string path = cache.pathFor("shadow", params_);
  const std::string full = readBytes(path);

  writeBytes(path, full.substr(0, full.size() / 2));
  EXPECT_FALSE(cache.load("shadow", params_).has_value());
  writeBytes(path, "garbage\n");
  EXPECT_FALSE(cache.load("shadow", params_).has_value());

  cache.store("shadow", params_, t);
  const std::optional<Table> hit = cache.load("shadow", params_);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->data, t.data);
}

TEST_F(TableCacheTest, FileWithOtherStoredParametersMisses) {
  // A stale file (or a hash collision) at the right path.
  const TableCache cache(dir_.string());
  const std::string path = cache.pathFor("shadow", params_);
  Table t = makeTable(2, 2, {"Y"});
  t.parameters = withKind("shadow");
  t.parameters["size"] = "8";
  writeExr(path, t);
  EXPECT_FALSE(cache.load("shadow", params_).has_value());

  t.parameters = params_;  // right parameters, but no kind
  writeExr(path, t);
  EXPECT_FALSE(cache.load("shadow", params_).has_value());

  t.parameters = withKind("shadow");
  writeExr(path, t);
  EXPECT_TRUE(cache.load("shadow", params_).has_value());
}

TEST_F(TableCacheTest, StoreIntoAnUnusableDirectoryThrows) {
  writeBytes(file("plain-file"), "x");
  const TableCache cache((dir_ / "plain-file" / "cache").string());  // not creatable, even as root
  const std::string path = cache.pathFor("shadow", params_);
  try {
    cache.store("shadow", params_, makeTable(2, 2, {"Y"}));
    FAIL() << "store did not throw";
  } catch (const TableError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
  }
  EXPECT_EQ(entries(dir_), std::vector<std::string>{"plain-file"});

  if (::geteuid() != 0) {
    const fs::path ro = dir_ / "ro";
    fs::create_directory(ro);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
    const TableCache readOnly(ro.string());
    EXPECT_THROW(readOnly.store("shadow", params_, makeTable(2, 2, {"Y"})), TableError);
    fs::permissions(ro, fs::perms::owner_all);
    EXPECT_TRUE(entries(ro).empty());
  }
}

}  // namespace
}  // namespace umbra::tables::test
