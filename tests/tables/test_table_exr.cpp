// writeExr / readExr: round trips, file layout, atomic writes and every rejected file.

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cmath>
#include <cstring>
#include <limits>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include "TestSupport.h"
#include "umbra/tables/Exr.h"

namespace umbra::tables::test {
namespace {

// Message of the TableError that f throws; fails the test when f throws nothing (or
// something else).
template <typename F>
std::string tableErrorOf(F&& f) {
  try {
    f();
  } catch (const TableError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected TableError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected TableError, nothing was thrown";
  return {};
}

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Compares values bit for bit (NaN payloads and the sign of zero included).
void expectSameBits(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(bits(a[i]), bits(b[i])) << "value " << i << ": " << a[i] << " vs " << b[i];
  }
}

// A float table of pseudo-random values, large enough to span several ZIP chunks.
Table noiseTable(int width, int height) {
  Table t = makeTable(width, height, {"R", "G", "B"});
  uint64_t state = 0x9e3779b97f4a7c15ULL;
  for (float& v : t.data) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    v = static_cast<float>(state % 100000) * 1e-3f;
  }
  return t;
}

using ExrTest = TempDirTest;

TEST(TableTest, AtReadsInterleavedRowMajorData) {
  const Table t = makeTable(3, 2, {"R", "G"});
  EXPECT_FLOAT_EQ(t.at(0, 0, 0), 0.25f);
  EXPECT_FLOAT_EQ(t.at(2, 1, 1), 1012.25f);
  EXPECT_EQ(bits(t.at(2, 1, 1)), bits(t.data[(1 * 3 + 2) * 2 + 1]));
  EXPECT_THROW(t.at(3, 0, 0), std::out_of_range);
  EXPECT_THROW(t.at(0, 2, 0), std::out_of_range);
  EXPECT_THROW(t.at(0, 0, 2), std::out_of_range);
  EXPECT_THROW(t.at(-1, 0, 0), std::out_of_range);
  EXPECT_EQ(t.channelIndex("G"), 1);
  EXPECT_EQ(t.channelIndex("B"), -1);
}

TEST_F(ExrTest, RoundTripKeepsValuesParametersChannelOrderAndSize) {
  Table t = makeTable(7, 3, {"R", "G", "B"});
  const float inf = std::numeric_limits<float>::infinity();
  t.data[0] = std::numeric_limits<float>::quiet_NaN();
  t.data[(0 * 7 + 1) * 3 + 1] = inf;
  t.data[(2 * 7 + 6) * 3 + 2] = -inf;
  t.data[(1 * 7 + 3) * 3 + 0] = -0.0f;
  t.data[(1 * 7 + 4) * 3 + 1] = std::numeric_limits<float>::denorm_min();
  t.data[(1 * 7 + 5) * 3 + 2] = std::numeric_limits<float>::max();
  t.data[(2 * 7 + 0) * 3 + 0] = std::numeric_limits<float>::lowest();
  t.parameters = {{"kind", "shadow-lut"},
                  {"radius", "6371000"},
                  {"note", "a=b\nsecond line"},
                  {"empty", ""}};
  const std::string path = file("table.exr");
  writeExr(path, t);

  const Table r = readExr(path);
  EXPECT_EQ(r.width, 7);
  EXPECT_EQ(r.height, 3);
  EXPECT_EQ(r.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(r.parameters, t.parameters);
  expectSameBits(r.data, t.data);
  EXPECT_TRUE(std::isnan(r.at(0, 0, 0)));
  EXPECT_EQ(r.at(1, 0, 1), inf);
  EXPECT_EQ(r.at(6, 2, 2), -inf);
  EXPECT_EQ(entries(dir_), std::vector<std::string>{"table.exr"});  // no temporary left
}

TEST_F(ExrTest, RoundTripKeepsANonAlphabeticalChannelOrder) {
  const Table t = makeTable(2, 5, {"Z", "A", "M"});
  writeExr(file("t.exr"), t);
  const Table r = readExr(file("t.exr"));
  EXPECT_EQ(r.channels, (std::vector<std::string>{"Z", "A", "M"}));
  expectSameBits(r.data, t.data);
}

TEST_F(ExrTest, RequiredChannelsAreReadInTheGivenOrder) {
  const Table t = makeTable(4, 3, {"R", "G", "B"});
  writeExr(file("t.exr"), t);
  const Table r = readExr(file("t.exr"), {"B", "R"});
  ASSERT_EQ(r.channels, (std::vector<std::string>{"B", "R"}));
  ASSERT_EQ(r.data.size(), 4u * 3u * 2u);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(r.at(x, y, 0), t.at(x, y, 2));
      EXPECT_EQ(r.at(x, y, 1), t.at(x, y, 0));
    }
}

TEST_F(ExrTest, FileHasFloatZipChannelsPrefixedParametersAndRowZeroFirst) {
  Table t = makeTable(5, 4, {"R", "G"});
  t.parameters = {{"kind", "limb"}, {"samples", "64"}};
  writeExr(file("t.exr"), t);

  Imf::InputFile in(file("t.exr").c_str());
  const Imf::Header& h = in.header();
  EXPECT_EQ(h.compression(), Imf::ZIP_COMPRESSION);
  EXPECT_EQ(h.lineOrder(), Imf::INCREASING_Y);
  EXPECT_EQ(h.dataWindow().min, Imath::V2i(0, 0));
  EXPECT_EQ(h.dataWindow().max, Imath::V2i(4, 3));
  int channels = 0;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it, ++channels) {
    EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
  }
  EXPECT_EQ(channels, 2);
  const auto* kind = h.findTypedAttribute<Imf::StringAttribute>("umbra:kind");
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->value(), "limb");
  EXPECT_EQ(h.findTypedAttribute<Imf::StringAttribute>("kind"), nullptr);

  // The first scanline in the file (y = 0, increasing y) holds the table's row 0.
  std::vector<float> row(5);
  Imf::FrameBuffer frame;
  frame.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(row.data()), sizeof(float),
                               0));
  in.setFrameBuffer(frame);
  in.readPixels(0, 0);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(row[x], t.at(x, 0, 1)) << x;
}

// Tables over kUncompressedAboveBytes are stored without compression (ZIP gains little on
// them); one float more than the bound is enough, one at it stays ZIP. Both read back.
TEST_F(ExrTest, TablesOverTheBoundAreWrittenUncompressed) {
  const int width = 1024, rows = static_cast<int>(kUncompressedAboveBytes / sizeof(float) / width);
  for (int extra : {0, 1}) {
    Table t = makeTable(width, rows + extra, {"L"});
    const std::string path = file("big" + std::to_string(extra) + ".exr");
    writeExr(path, t);
    Imf::InputFile in(path.c_str());
    EXPECT_EQ(in.header().compression(), extra ? Imf::NO_COMPRESSION : Imf::ZIP_COMPRESSION) << extra;
    EXPECT_EQ(readExr(path).data, t.data) << extra;
  }
}

TEST_F(ExrTest, LongParameterNamesRoundTripAndTooLongOnesAreRejected) {
  Table t = makeTable(1, 1, {"Y"});
  const std::string longKey(200, 'k');
  t.parameters = {{longKey, "v"}, {"short", "s"}};
  writeExr(file("t.exr"), t);
  EXPECT_EQ(readExr(file("t.exr")).parameters, t.parameters);

  t.parameters = {{std::string(250, 'k'), "v"}};
  const std::string message = tableErrorOf([&] { writeExr(file("u.exr"), t); });
  EXPECT_TRUE(startsWith(message, file("u.exr") + ": ")) << message;
  EXPECT_FALSE(fs::exists(file("u.exr")));
}

TEST_F(ExrTest, ReadsAFileWrittenByOtherSoftwareWithAnOffsetDataWindow) {
  const std::string path = file("foreign.exr");
  const Imath::Box2i window(Imath::V2i(10, 20), Imath::V2i(13, 22));  // 4 x 3
  std::vector<float> y(12), a(12);
  for (int i = 0; i < 12; ++i) {
    y[i] = static_cast<float>(i);
    a[i] = 100.0f + static_cast<float>(i);
  }
  {
    Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(20, 30)), window);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.channels().insert("A", Imf::Channel(Imf::FLOAT));
    header.insert("owner", Imf::StringAttribute("someone"));
    header.insert("umbra:source", Imf::StringAttribute("test"));
    Imf::OutputFile out(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice::Make(Imf::FLOAT, y.data(), window));
    frame.insert("A", Imf::Slice::Make(Imf::FLOAT, a.data(), window));
    out.setFrameBuffer(frame);
    out.writePixels(3);
  }
  const Table r = readExr(path);
  EXPECT_EQ(r.width, 4);
  EXPECT_EQ(r.height, 3);
  EXPECT_EQ(r.channels, (std::vector<std::string>{"A", "Y"}));  // stored (sorted) order
  EXPECT_EQ(r.parameters, (std::map<std::string, std::string>{{"source", "test"}}));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(r.at(i, j, 0), a[j * 4 + i]);
      EXPECT_EQ(r.at(i, j, 1), y[j * 4 + i]);
    }
}

TEST_F(ExrTest, InvalidTablesAreRejectedBeforeTouchingTheDisk) {
  const std::string existing = file("existing.exr");
  writeBytes(existing, "old contents");
  const std::string fresh = file("fresh.exr");

  std::vector<std::pair<std::string, Table>> cases;
  {
    Table t = makeTable(3, 2, {"R"});
    t.data.pop_back();
    cases.emplace_back("short data", t);
  }
  {
    Table t = makeTable(3, 2, {"R"});
    t.data.push_back(1.0f);
    cases.emplace_back("long data", t);
  }
  {
    Table t = makeTable(1, 1, {"R"});
    t.width = 0;
    t.data.clear();
    cases.emplace_back("zero width", t);
  }
  {
    Table t = makeTable(1, 1, {"R"});
    t.height = -1;
    cases.emplace_back("negative height", t);
  }
  {
    Table t;
    t.width = t.height = 1;
    cases.emplace_back("no channels", t);
  }
  cases.emplace_back("duplicate channel", makeTable(2, 2, {"R", "G", "R"}));
  cases.emplace_back("empty channel name", makeTable(2, 2, {"R", ""}));
  {
    Table t = makeTable(1, 1, {"R"});
    t.parameters[""] = "x";
    cases.emplace_back("empty parameter name", t);
  }
  for (const auto& [name, table] : cases) {
    SCOPED_TRACE(name);
    for (const std::string& path : {existing, fresh}) {
      const std::string message = tableErrorOf([&] { writeExr(path, table); });
      EXPECT_TRUE(startsWith(message, path + ": invalid table: ")) << message;
    }
    EXPECT_EQ(readBytes(existing), "old contents");
    EXPECT_EQ(entries(dir_), std::vector<std::string>{"existing.exr"});
  }
}

TEST_F(ExrTest, WriteIntoAMissingDirectoryThrowsAndLeavesNothing) {
  const std::string path = file("missing/x.exr");
  const std::string message = tableErrorOf([&] { writeExr(path, makeTable(2, 2, {"Y"})); });
  EXPECT_TRUE(startsWith(message, path + ": cannot write: ")) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
  EXPECT_TRUE(entries(dir_).empty());
}

TEST_F(ExrTest, WriteIntoAReadOnlyDirectoryThrowsAndLeavesNothing) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path ro = dir_ / "ro";
  fs::create_directory(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string path = (ro / "x.exr").string();
  const std::string message = tableErrorOf([&] { writeExr(path, makeTable(2, 2, {"Y"})); });
  EXPECT_EQ(message, path + ": cannot write: Permission denied");
  fs::permissions(ro, fs::perms::owner_all);
  EXPECT_TRUE(entries(ro).empty());
}

TEST_F(ExrTest, FailedRenameRemovesTheTemporaryAndKeepsWhatIsAtThePath) {
  // A directory where the file should go: everything succeeds up to the rename.
  fs::create_directory(dir_ / "x.exr");
  writeBytes((dir_ / "x.exr" / "inside").string(), "keep");
  const std::string path = file("x.exr");
  const std::string message = tableErrorOf([&] { writeExr(path, noiseTable(32, 32)); });
  EXPECT_TRUE(startsWith(message, path + ": cannot write: ")) << message;
  EXPECT_EQ(entries(dir_), std::vector<std::string>{"x.exr"});
  EXPECT_EQ(readBytes((dir_ / "x.exr" / "inside").string()), "keep");
}

// Limits the size of files this process writes, for the scope of a test.
class ScopedFileSizeLimit {
public:
  explicit ScopedFileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &old_);
    oldHandler_ = std::signal(SIGXFSZ, SIG_IGN);  // make write() fail with EFBIG instead
    rlimit limit = old_;
    limit.rlim_cur = bytes;
    ok_ = ::setrlimit(RLIMIT_FSIZE, &limit) == 0;
  }
  ~ScopedFileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, oldHandler_);
  }
  bool ok() const { return ok_; }

private:
  rlimit old_{};
  void (*oldHandler_)(int) = SIG_DFL;
  bool ok_ = false;
};

TEST_F(ExrTest, WriteFailingHalfWayKeepsTheOldFileAndLeavesNoTemporary) {
  const std::string path = file("x.exr");
  Table old = makeTable(3, 2, {"Y"});
  old.parameters = {{"kind", "old"}};
  writeExr(path, old);
  const std::string oldBytes = readBytes(path);
  ASSERT_LT(oldBytes.size(), 4096u);

  std::string message;
  {
    ScopedFileSizeLimit limit(8192);  // the new table needs about 48 KiB
    ASSERT_TRUE(limit.ok());
    message = tableErrorOf([&] { writeExr(path, noiseTable(64, 64)); });
  }
  EXPECT_EQ(message, path + ": cannot write: File too large");
  EXPECT_EQ(readBytes(path), oldBytes);
  EXPECT_EQ(readExr(path).parameters, old.parameters);
  EXPECT_EQ(entries(dir_), std::vector<std::string>{"x.exr"});
}

TEST_F(ExrTest, OverwritingReplacesTheWholeFile) {
  const std::string path = file("t.exr");
  writeExr(path, noiseTable(40, 30));
  Table small = makeTable(2, 1, {"Y"});
  small.parameters = {{"kind", "new"}};
  writeExr(path, small);
  const Table r = readExr(path);
  EXPECT_EQ(r.width, 2);
  EXPECT_EQ(r.height, 1);
  EXPECT_EQ(r.parameters, small.parameters);
  expectSameBits(r.data, small.data);
  EXPECT_EQ(entries(dir_), std::vector<std::string>{"t.exr"});
}

TEST_F(ExrTest, MissingFileIsReported) {
  const std::string path = file("nothing.exr");
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }),
            path + ": cannot open: No such file or directory");
}

TEST_F(ExrTest, DirectoryIsNotATable) {
  fs::create_directory(dir_ / "d.exr");
  const std::string path = file("d.exr");
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }), path + ": cannot open: Is a directory");
}

TEST_F(ExrTest, TextFileNamedExrIsRejected) {
  const std::string path = file("notes.exr");
  writeBytes(path, "This is not an image.\nJust text.\n");
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }), path + ": not an OpenEXR file");
  writeBytes(path, "");
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }), path + ": not an OpenEXR file");
}

// A damaged header must be refused before anything is allocated at its word: an attribute
// claiming 2 GB (OpenEXR would allocate it), a data window of more values than the file
// could hold, and one over the largest table read.
TEST_F(ExrTest, HeadersPromisingMoreThanTheFileHoldsAreRejected) {
  const std::string path = file("h.exr");
  Table t = makeTable(8, 8, {"R", "G", "B"});
  t.parameters["marker"] = "MMMMMMMM";
  writeExr(path, t);
  const std::string good = readBytes(path);
  const auto patched = [&](std::size_t at, std::initializer_list<std::int32_t> values) {
    std::string bytes = good;
    for (std::int32_t v : values) {
      for (int b = 0; b < 4; ++b) bytes[at++] = static_cast<char>((static_cast<std::uint32_t>(v) >> (8 * b)) & 0xff);
    }
    writeBytes(path, bytes);
  };
  const std::size_t marker = good.find("MMMMMMMM");
  ASSERT_NE(marker, std::string::npos);
  patched(marker - 4, {0x7fffffff});
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }),
            path + ": corrupt OpenEXR file: header attribute 'umbra:marker' of 2147483647 bytes runs past the end "
                   "of the file");

  // The fuzzer's find: a channel list shorter than its declared size made OpenEXR read the
  // next attribute from the middle of this one, with a size of 1.8 GB.
  const std::string channels = std::string("channels") + '\0' + "chlist" + '\0';
  const std::size_t channelsSize = good.find(channels) + channels.size();
  std::int32_t declared = 0;
  std::memcpy(&declared, good.data() + channelsSize, 4);
  patched(channelsSize, {declared - 18});
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }),
            path + ": corrupt OpenEXR file: header attribute 'channels' (chlist) of " + std::to_string(declared - 18) +
                " bytes");

  const std::string window = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const std::size_t box = good.find(window) + window.size() + 4;  // after the size: xMin, yMin, xMax, yMax
  patched(box, {0, 0, 60000, 7});  // still one block of scanlines: OpenEXR opens it
  const std::string tooMany = tableErrorOf([&] { readExr(path); });
  EXPECT_NE(tooMany.find("60001 x 8 values cannot come from"), std::string::npos) << tooMany;
  patched(box, {0, 0, 3999, 3999});
  EXPECT_NE(tableErrorOf([&] { readExr(path); }).find("4000 x 4000 values cannot come from"), std::string::npos);
  patched(box, {0, 0, 65535, 65535});
  EXPECT_NE(tableErrorOf([&] { readExr(path); }).find("corrupt"), std::string::npos);
}

TEST_F(ExrTest, TruncatedFilesAreRejected) {
  const std::string path = file("t.exr");
  writeExr(path, noiseTable(64, 64));
  const std::string full = readBytes(path);
  ASSERT_GT(full.size(), 10000u);
  ASSERT_NO_THROW(readExr(path));

  for (size_t size : {full.size() / 2, size_t{10}, size_t{200}, full.size() / 4,
                      full.size() * 3 / 4, full.size() - 1}) {
    SCOPED_TRACE("truncated to " + std::to_string(size) + " of " +
                 std::to_string(full.size()) + " bytes");
    writeBytes(path, full.substr(0, size));
    const std::string message = tableErrorOf([&] { readExr(path); });
    EXPECT_TRUE(startsWith(message, path + ": ")) << message;
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_F(ExrTest, FileOfAnInterruptedWriterIsRejectedAsIncomplete) {
  // OpenEXR writers leave the line-offset table zero until they finish. Simulate a writer
  // that stopped half way: zero the table and cut the file in half.
  const std::string path = file("t.exr");
  const int height = 64;  // ZIP: 16 scanlines per chunk, so 4 offsets
  writeExr(path, noiseTable(64, height));
  std::string bytes = readBytes(path);
  const size_t offsets = height / 16;
  size_t table = std::string::npos;
  for (size_t p = 0; p + 8 <= bytes.size(); ++p) {  // the first offset points just past the table
    uint64_t first;
    std::memcpy(&first, bytes.data() + p, 8);
    if (first == p + 8 * offsets) {
      table = p;
      break;
    }
  }
  ASSERT_NE(table, std::string::npos);
  std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(table),
            bytes.begin() + static_cast<std::ptrdiff_t>(table + 8 * offsets), '\0');
  writeBytes(path, bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }),
            path + ": truncated or incomplete OpenEXR file (scanlines are missing)");
}

TEST_F(ExrTest, CorruptedPixelDataIsRejected) {
  const std::string path = file("t.exr");
  writeExr(path, makeTable(64, 64, {"R", "G", "B"}));  // smooth: ZIP really compresses it
  std::string bytes = readBytes(path);
  for (size_t i = bytes.size() / 2; i < bytes.size() / 2 + 64; ++i) bytes[i] ^= 0x5a;
  writeBytes(path, bytes);
  const std::string message = tableErrorOf([&] { readExr(path); });
  EXPECT_TRUE(startsWith(message, path + ": ")) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST_F(ExrTest, MissingRequiredChannelsAreNamed) {
  const std::string gray = file("gray.exr");
  writeExr(gray, makeTable(3, 3, {"Y"}));
  EXPECT_EQ(tableErrorOf([&] { readExr(gray, {"R", "G", "B"}); }),
            gray + ": missing channels 'R', 'G', 'B' (has: Y)");

  const std::string rb = file("rb.exr");
  writeExr(rb, makeTable(3, 3, {"R", "B"}));
  EXPECT_EQ(tableErrorOf([&] { readExr(rb, {"R", "G", "B"}); }),
            rb + ": missing channel 'G' (has: R, B)");
  EXPECT_NO_THROW(readExr(rb, {"B"}));

  const std::string message = tableErrorOf([&] { readExr(rb, {"R", "R"}); });
  EXPECT_TRUE(startsWith(message, rb + ": ")) << message;
}

TEST_F(ExrTest, HalfChannelIsRejected) {
  const std::string path = file("half.exr");
  std::vector<half> r(4, half(1.5f));
  std::vector<float> g(4, 2.5f);
  {
    Imf::Header header(2, 2);
    header.channels().insert("R", Imf::Channel(Imf::HALF));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile out(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(r.data()), sizeof(half),
                                 2 * sizeof(half)));
    frame.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), sizeof(float),
                                 2 * sizeof(float)));
    out.setFrameBuffer(frame);
    out.writePixels(2);
  }
  EXPECT_EQ(tableErrorOf([&] { readExr(path); }),
            path + ": channel 'R' is HALF, expected FLOAT");
  const Table t = readExr(path, {"G"});
  EXPECT_EQ(t.data, g);
}

}  // namespace
}  // namespace umbra::tables::test
