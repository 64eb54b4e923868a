// PlanarTableFile: a table made a batch of channels at a time, stored by TableCache without
// being held whole: the same file as the whole table's, read back to the bit.

#include <sys/stat.h>

#include "TestSupport.h"
#include "umbra/tables/Exr.h"
#include "umbra/tables/PlanarTableFile.h"
#include "umbra/tables/TableCache.h"

namespace umbra::tables::test {
namespace {

using Parameters = std::map<std::string, std::string>;
using PlanarTableTest = TempDirTest;

// A table whose every value differs (pixel, channel), over 256 rows so that its rows are
// written in more than one block.
Table distinctTable(int width, int height, const std::vector<std::string>& channels) {
  Table t;
  t.width = width, t.height = height, t.channels = channels;
  const std::size_t nc = channels.size();
  t.data.resize(static_cast<std::size_t>(width) * height * nc);
  for (std::size_t i = 0; i < t.data.size(); ++i) t.data[i] = 0.5f + static_cast<float>(i % 7919) * 1e-3f + static_cast<float>(i / nc % 3);
  return t;
}

// Channels [first, first + count) of t, interleaved per pixel as a batch hands them on.
std::vector<float> batchOf(const Table& t, int first, int count) {
  const std::size_t n = static_cast<std::size_t>(t.width) * t.height, nc = t.channels.size();
  std::vector<float> v(n * static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < count; ++k) v[i * count + k] = t.data[i * nc + first + k];
  return v;
}

TEST_F(PlanarTableTest, BatchesOfChannelsStoreTheFileOfTheWholeTable) {
  const Table whole = distinctTable(24, 600, {"L400nm", "L500nm", "L600nm", "L700nm", "L800nm"});
  const Parameters parameters = {{"size", "24x600"}, {"order", "4"}};
  const TableCache a((dir_ / "a").string(), 0), b((dir_ / "b").string(), 0);
  a.store("scattering", parameters, whole);

  fs::create_directories(dir_ / "b");
  PlanarTableFile planes((dir_ / "b").string(), whole.width, whole.height, whole.channels);
  // Batches in any order, of any size: 2 + 1 + 2 channels.
  planes.put(3, 2, batchOf(whole, 3, 2).data());
  planes.put(0, 2, batchOf(whole, 0, 2).data());
  planes.put(2, 1, batchOf(whole, 2, 1).data());
  b.store("scattering", parameters, planes);

  EXPECT_EQ(readBytes(a.pathFor("scattering", parameters)), readBytes(b.pathFor("scattering", parameters)));
  const std::optional<Table> back = b.load("scattering", parameters);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->channels, whole.channels);
  EXPECT_EQ(back->data, whole.data);
  // The planes' file has no name: only the table is left in the directory.
  EXPECT_EQ(entries(dir_ / "b"), std::vector<std::string>{fs::path(b.pathFor("scattering", parameters)).filename()});
}

TEST_F(PlanarTableTest, RowsGiveEveryChannelAndZerosForChannelsNotPut) {
  const Table whole = distinctTable(5, 9, {"R", "G", "B"});
  PlanarTableFile planes(dir_.string(), 5, 9, whole.channels);
  planes.put(1, 1, batchOf(whole, 1, 1).data());
  std::vector<float> rows;
  planes.rows(4, 3, rows);
  ASSERT_EQ(rows.size(), 5u * 3 * 3);
  for (int y = 4; y < 7; ++y)
    for (int x = 0; x < 5; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y - 4) * 5 + x) * 3;
      EXPECT_EQ(rows[i], 0.0f);
      EXPECT_EQ(rows[i + 1], whole.at(x, y, 1));
      EXPECT_EQ(rows[i + 2], 0.0f);
    }
  EXPECT_THROW(planes.put(2, 2, batchOf(whole, 0, 2).data()), std::out_of_range);
}

TEST_F(PlanarTableTest, ANonFiniteValueIsNotStored) {
  Table whole = distinctTable(4, 4, {"R"});
  whole.data[5] = std::nanf("");
  PlanarTableFile planes(dir_.string(), 4, 4, whole.channels);
  planes.put(0, 1, whole.data.data());
  const TableCache cache((dir_ / "c").string(), 0);
  EXPECT_THROW(cache.store("lut", {{"n", "1"}}, planes), TableError);
  EXPECT_FALSE(fs::exists(cache.pathFor("lut", {{"n", "1"}})));
}

TEST_F(PlanarTableTest, AnUnusableDirectoryIsNamed) {
  try {
    PlanarTableFile planes((dir_ / "missing").string(), 4, 4, {"R"});
    FAIL() << "no error";
  } catch (const TableError& e) {
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
}

TEST_F(PlanarTableTest, CopyFromAnotherCacheIsTheStoredFileReadBack) {
  const Table whole = distinctTable(8, 8, {"R", "G"});
  const Parameters parameters = {{"n", "2"}};
  const TableCache from((dir_ / "from").string(), 0), to((dir_ / "to").string(), 0);
  from.store("lut", parameters, whole);
  to.copyFrom(from, "lut", parameters);
  EXPECT_EQ(readBytes(from.pathFor("lut", parameters)), readBytes(to.pathFor("lut", parameters)));
  const std::optional<Table> back = to.load("lut", parameters);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->data, whole.data);
  EXPECT_THROW(to.copyFrom(from, "lut", {{"n", "3"}}), TableError);  // nothing there
}

}  // namespace
}  // namespace umbra::tables::test
