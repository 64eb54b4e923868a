// TableCache: default directory, keys, hits, misses and failures; the size cap.

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>

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
  // params_ plus {"n": n}: tables of the same size on disk for n in 0..9.
  Parameters numbered(int n) const {
    Parameters p = params_;
    p["n"] = std::to_string(n);
    return p;
  }
  // Stores the n-th "lut" table through cache; its path.
  std::string storeNumbered(const TableCache& cache, int n) const {
    cache.store("lut", numbered(n), makeTable(16, 16, {"R", "G", "B"}));
    return cache.pathFor("lut", numbered(n));
  }
  static void setUsedHoursAgo(const std::string& path, int hours) {
    fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::hours(hours));
  }
  static std::string name(const std::string& path) { return fs::path(path).filename().string(); }
  static std::vector<std::string> sortedNames(std::vector<std::string> paths) {
    for (std::string& p : paths) p = name(p);
    std::sort(paths.begin(), paths.end());
    return paths;
  }
};

constexpr std::uint64_t kMiB = 1024 * 1024;

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
  // The file's header: the parameters, the kind and the values' checksum (16 hex digits).
  Parameters header = readExr(cache.pathFor("shadow", params_)).parameters;
  ASSERT_EQ(header.count("values-checksum"), 1u);
  EXPECT_EQ(header["values-checksum"].size(), 16u);
  header.erase("values-checksum");
  EXPECT_EQ(header, withKind("shadow"));
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

  t.parameters = withKind("shadow");  // right parameters, no checksum: not the cache's
  writeExr(path, t);
  EXPECT_FALSE(cache.load("shadow", params_).has_value());
  cache.store("shadow", params_, t);
  EXPECT_TRUE(cache.load("shadow", params_).has_value());
}

// A file from before the word-wise checksum (its header's "checksum" entry, none of the new
// one) is stale: a miss without a word on stderr, then overwritten by the next store.
TEST_F(TableCacheTest, AFileWithTheEarlierChecksumIsAQuietMiss) {
  const TableCache cache(dir_.string());
  const std::string path = cache.pathFor("shadow", params_);
  Table t = makeTable(3, 2, {"R", "G", "B"});
  t.parameters = withKind("shadow");
  t.parameters["checksum"] = "0123456789abcdef";
  fs::create_directories(dir_);
  writeExr(path, t);
  testing::internal::CaptureStderr();
  EXPECT_FALSE(cache.load("shadow", params_).has_value());
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  cache.store("shadow", params_, t);
  EXPECT_TRUE(cache.load("shadow", params_).has_value());
}

// A table whose content is not what its header says: the right header over NaN values, a
// short table, another table's values: a miss (the caller computes it again and
// overwrites), never a hit; and a table with a NaN is not stored.
TEST_F(TableCacheTest, ContentIsCheckedOnEveryLoad) {
  const TableCache cache(dir_.string());
  const std::string path = cache.pathFor("shadow", params_);
  const Table good = makeTable(4, 4, {"R", "G", "B"});
  cache.store("shadow", params_, good);
  const Parameters header = readExr(path).parameters;
  ASSERT_TRUE(cache.load("shadow", params_).has_value());

  Table nan = good;
  nan.data[7] = std::nanf("");
  nan.parameters = header;
  writeExr(path, nan);
  EXPECT_FALSE(cache.load("shadow", params_).has_value());

  Table other = good;
  other.data[3] += 0.5f;  // the header's checksum is the good table's
  other.parameters = header;
  writeExr(path, other);
  EXPECT_FALSE(cache.load("shadow", params_).has_value());

  Table smaller = makeTable(2, 2, {"R", "G", "B"});
  smaller.parameters = header;
  writeExr(path, smaller);
  EXPECT_FALSE(cache.load("shadow", params_).has_value());

  EXPECT_THROW(cache.store("shadow", params_, nan), TableError);
  cache.store("shadow", params_, good);  // rebuilt
  const auto hit = cache.load("shadow", params_);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->data, good.data);
}

// A writer killed (kill -9) leaves its temporary: removed at the next store when its
// process is gone or it is over an hour old, and counted in the cap while its writer lives.
TEST_F(TableCacheTest, StaleTemporariesAreRemovedLiveOnesCounted) {
  const TableCache unlimited(dir_.string(), 0);
  const std::string a = storeNumbered(unlimited, 1);
  const std::uintmax_t size = fs::file_size(a);
  const std::string dead = a + ".tmp-999999999-0123456789abcdef";  // no such process
  const std::string old = a + ".tmp-" + std::to_string(::getpid()) + "-00000000000000aa";
  const std::string live = a + ".tmp-" + std::to_string(::getpid()) + "-00000000000000bb";
  for (const std::string& t : {dead, old, live}) writeBytes(t, std::string(size, 'x'));
  setUsedHoursAgo(old, 2);
  // A cap of three tables: a, the live temporary and the new table fill it.
  storeNumbered(TableCache(dir_.string(), 3 * size + size / 2), 2);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_FALSE(fs::exists(old));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(a));
  // A cap of two: the live temporary counts, so a goes.
  storeNumbered(TableCache(dir_.string(), 2 * size + size / 2), 3);
  EXPECT_TRUE(fs::exists(live));
  EXPECT_FALSE(fs::exists(a));
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

TEST(TableCacheDefaults, MaxBytesFromUmbraCacheMaxMb) {
  const std::uint64_t defaultBytes = 2048 * kMiB;
  {
    ScopedEnv unset("UMBRA_CACHE_MAX_MB", nullptr);
    EXPECT_EQ(TableCache::defaultMaxBytes(), defaultBytes);
    EXPECT_EQ(TableCache("/nowhere").maxBytes(), defaultBytes);
  }
  const std::vector<std::pair<const char*, std::uint64_t>> valid = {
      {"", defaultBytes},  // empty = unset, like UMBRA_CACHE_DIR
      {"100", 100 * kMiB},
      {"007", 7 * kMiB},
      {"0", 0},
      {"0.0", 0},
      {"0.5", kMiB / 2},
      {"1.25", kMiB + kMiB / 4},
      {"3.", 3 * kMiB},
      {".5", kMiB / 2},
      {"0.0000001", 1},  // rounded up: a tiny cap, not "no limit"
      {"99999999999999999999999", UINT64_MAX}};
  for (const auto& [text, bytes] : valid) {
    ScopedEnv env("UMBRA_CACHE_MAX_MB", text);
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(TableCache::defaultMaxBytes(), bytes) << text;
    EXPECT_EQ(TableCache("/nowhere").maxBytes(), bytes) << text;
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << text;
  }
  for (const char* text : {"abc", "-5", "-0", "+5", "10MB", "10 ", " 10", "1e3", "0x10", "inf",
                           "nan", ".", "1.2.3", "1,5"}) {
    ScopedEnv env("UMBRA_CACHE_MAX_MB", text);
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(TableCache::defaultMaxBytes(), defaultBytes) << text;
    const std::string warning = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warning.find("UMBRA_CACHE_MAX_MB='" + std::string(text) + "'"), std::string::npos)
        << warning;
    EXPECT_NE(warning.find("2048 MiB"), std::string::npos) << warning;
    EXPECT_EQ(std::count(warning.begin(), warning.end(), '\n'), 1) << warning;
    EXPECT_EQ(warning.back(), '\n');
    // The same value again (a cache made per frame) is not repeated.
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(TableCache("/nowhere").maxBytes(), defaultBytes) << text;
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << text;
  }
}

TEST_F(TableCacheTest, CapRemovesLeastRecentlyUsedFirst) {
  const TableCache unlimited(dir_.string(), 0);
  const std::string a = storeNumbered(unlimited, 1);
  const std::string b = storeNumbered(unlimited, 2);
  const std::uintmax_t size = fs::file_size(a);
  ASSERT_EQ(fs::file_size(b), size);
  // Not the order of writing nor of names: b is the least recently used.
  setUsedHoursAgo(a, 1);
  setUsedHoursAgo(b, 3);

  const TableCache capped(dir_.string(), 2 * size + size / 2);  // fewer than three tables
  const std::string c = storeNumbered(capped, 3);
  ASSERT_EQ(fs::file_size(c), size);
  EXPECT_EQ(entries(dir_), sortedNames({a, c}));

  setUsedHoursAgo(c, 2);  // now older than a
  const std::string d = storeNumbered(capped, 4);
  EXPECT_EQ(entries(dir_), sortedNames({a, d}));
  EXPECT_LE(fs::file_size(a) + fs::file_size(d), capped.maxBytes());

  // Storing a cached table again makes it the most recent: a goes, not d.
  setUsedHoursAgo(d, 5);
  EXPECT_EQ(storeNumbered(capped, 4), d);
  const std::string e = storeNumbered(capped, 5);
  EXPECT_EQ(entries(dir_), sortedNames({d, e}));
}

TEST_F(TableCacheTest, LoadRefreshesUse) {
  const TableCache unlimited(dir_.string(), 0);
  const std::string a = storeNumbered(unlimited, 1);
  const std::string b = storeNumbered(unlimited, 2);
  const std::uintmax_t size = fs::file_size(a);
  setUsedHoursAgo(a, 3);
  setUsedHoursAgo(b, 2);

  const TableCache capped(dir_.string(), 2 * size + size / 2);
  const auto before = fs::file_time_type::clock::now() - std::chrono::minutes(1);
  ASSERT_TRUE(capped.load("lut", numbered(1)).has_value());
  EXPECT_GT(fs::last_write_time(a), before);
  EXPECT_GT(fs::last_write_time(a), fs::last_write_time(b));
  // A miss (other parameters stored at b's path) is no use: b keeps its time.
  const auto bUsed = fs::last_write_time(b);
  Parameters stale = numbered(2);
  stale["size"] = "8";
  EXPECT_FALSE(capped.load("lut", stale).has_value());
  EXPECT_FALSE(capped.load("lut", numbered(7)).has_value());
  EXPECT_EQ(fs::last_write_time(b), bUsed);

  const std::string c = storeNumbered(capped, 3);
  EXPECT_EQ(entries(dir_), sortedNames({a, c}));
}

TEST_F(TableCacheTest, CapLeavesForeignFilesAlone) {
  const TableCache unlimited(dir_.string(), 0);
  const std::string a = storeNumbered(unlimited, 1);
  const std::uintmax_t size = fs::file_size(a);
  setUsedHoursAgo(a, 5);

  // Not the cache's: none is removed, nor counted in its size.
  const std::string big(4 * size, 'x');
  const std::vector<std::string> foreign = {
      "notes.txt",
      "x.exr",
      "lut-0123456789ABCDEF.exr",  // parameterHash is lower case
      "lut-0123456789abcde.exr",   // 15 digits
      "lut-0123456789abcdefa.exr",
      "lut0123456789abcdef.exr",
      "-0123456789abcdef.exr",
      ".lut-0123456789abcdef.exr",
      "lut-0123456789abcdef.exr.bak"};
  for (const std::string& f : foreign) {
    writeBytes(file(f), big);
    setUsedHoursAgo(file(f), 10);
  }
  const fs::path sub = dir_ / "sub-0123456789abcdef.exr";  // a directory with a cache name
  fs::create_directory(sub);
  writeBytes((sub / name(a)).string(), big);
  setUsedHoursAgo((sub / name(a)).string(), 10);
  setUsedHoursAgo(sub.string(), 10);
  fs::create_symlink("notes.txt", dir_ / "link-0123456789abcdef.exr");

  std::vector<std::string> expected = foreign;
  expected.push_back(sub.filename().string());
  expected.push_back("link-0123456789abcdef.exr");

  // a and b fit under the cap; the foreign files (far larger) do not count.
  const std::string b = storeNumbered(TableCache(dir_.string(), 2 * size + size / 2), 2);
  std::vector<std::string> now = expected;
  now.push_back(name(a));
  now.push_back(name(b));
  std::sort(now.begin(), now.end());
  EXPECT_EQ(entries(dir_), now);

  // A cap for one table: a and b go, the foreign files stay.
  const std::string c = storeNumbered(TableCache(dir_.string(), size + size / 2), 3);
  now = expected;
  now.push_back(name(c));
  std::sort(now.begin(), now.end());
  EXPECT_EQ(entries(dir_), now);
  for (const std::string& f : foreign) EXPECT_EQ(fs::file_size(file(f)), big.size()) << f;
  EXPECT_EQ(entries(sub), std::vector<std::string>{name(a)});
}

TEST_F(TableCacheTest, JustWrittenFileSurvivesACapSmallerThanItself) {
  const TableCache tiny(dir_.string(), 1);
  const std::string a = storeNumbered(tiny, 1);
  EXPECT_EQ(entries(dir_), std::vector<std::string>{name(a)});
  EXPECT_GT(fs::file_size(a), tiny.maxBytes());
  ASSERT_TRUE(tiny.load("lut", numbered(1)).has_value());

  const std::string b = storeNumbered(tiny, 2);
  EXPECT_EQ(entries(dir_), std::vector<std::string>{name(b)});
  EXPECT_TRUE(tiny.load("lut", numbered(2)).has_value());
}

TEST_F(TableCacheTest, ZeroCapIsUnlimited) {
  ScopedEnv env("UMBRA_CACHE_MAX_MB", "0");
  const TableCache cache(dir_.string());
  EXPECT_EQ(cache.maxBytes(), 0u);
  std::vector<std::string> names;
  for (int n = 0; n < 6; ++n) {
    const std::string path = storeNumbered(cache, n);
    setUsedHoursAgo(path, 10 - n);
    names.push_back(name(path));
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(entries(dir_), names);
}

TEST_F(TableCacheTest, JsonDocumentsComeBackToTheBitUnderTheirOwnParameters) {
  const TableCache cache(dir_.string());
  // Doubles that a float (or a decimal with too few digits) would change.
  const nlohmann::json document = {{"values", {0.1, 1.0 / 3.0, 6.02214076e23, 4.9406564584124654e-324, -2.5e-308}},
                                   {"converged", true}};
  cache.storeJson("mie-optics", params_, document);
  const std::string path = cache.jsonPathFor("mie-optics", params_);
  EXPECT_EQ(name(path), "mie-optics-" + parameterHash(params_) + ".json");
  ASSERT_TRUE(fs::exists(path));
  const std::optional<nlohmann::json> hit = cache.loadJson("mie-optics", params_);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(*hit, document);
  const auto values = (*hit)["values"].get<std::vector<double>>();
  const auto expected = document["values"].get<std::vector<double>>();
  for (std::size_t i = 0; i < values.size(); ++i)
    EXPECT_EQ(std::memcmp(&values[i], &expected[i], sizeof(double)), 0) << i;

  Parameters changed = params_;
  changed["size"] = "32";
  EXPECT_FALSE(cache.loadJson("mie-optics", changed).has_value());
  EXPECT_FALSE(cache.loadJson("other", params_).has_value());
  EXPECT_FALSE(cache.load("mie-optics", params_).has_value());  // a JSON entry is not a table

  // Truncated, or not ours: missed, then overwritten.
  const std::string full = readBytes(path);
  writeBytes(path, full.substr(0, full.size() / 2));
  EXPECT_FALSE(cache.loadJson("mie-optics", params_).has_value());
  writeBytes(path, R"({"parameters": {"kind": "mie-optics"}, "document": 1})");
  EXPECT_FALSE(cache.loadJson("mie-optics", params_).has_value());
  cache.storeJson("mie-optics", params_, document);
  EXPECT_EQ(cache.loadJson("mie-optics", params_), document);
  EXPECT_THROW(cache.storeJson("../up", params_, document), std::invalid_argument);
}

TEST_F(TableCacheTest, JsonDocumentsCountTowardsTheCap) {
  const TableCache unlimited(dir_.string(), 0);
  const std::string table = storeNumbered(unlimited, 1);
  setUsedHoursAgo(table, 3);
  const nlohmann::json big = {{"values", std::vector<double>(4096, 1.0 / 7.0)}};
  unlimited.storeJson("mie-optics", numbered(2), big);
  const std::string json = unlimited.jsonPathFor("mie-optics", numbered(2));
  ASSERT_TRUE(fs::exists(json));
  setUsedHoursAgo(json, 2);
  // Room for two of the three: the least recently used (the table) goes.
  const TableCache capped(dir_.string(), fs::file_size(json) + fs::file_size(json) + 1);
  capped.storeJson("mie-optics", numbered(3), big);
  EXPECT_FALSE(fs::exists(table));
  EXPECT_TRUE(fs::exists(json));
  EXPECT_TRUE(capped.loadJson("mie-optics", numbered(3)).has_value());
}

}  // namespace
}  // namespace umbra::tables::test
