#include "umbra/tables/Exr.h"

#include "ExrInternal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <system_error>
#include <thread>

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>
#include <ImfThreading.h>
#include <ImfVersion.h>

namespace fs = std::filesystem;

namespace umbra::tables {

namespace {
/// The largest table read: 2^28 values (1 GiB of floats), at most 65536 a side.
constexpr uint64_t kMaxTableValues = uint64_t{1} << 28;
constexpr int kMaxTableSide = 1 << 16;
/// Whether `values` floats can come from a file of `fileBytes`: deflate's limit is
/// 1032:1 and EXR's other compressions pack less, so 2048:1 (and 64 KiB) is generous.
bool valuesFitFile(uint64_t values, uint64_t fileBytes) {
  return values * sizeof(float) <= 2048 * fileBytes + (uint64_t{1} << 16);
}

std::string errorText(int err) { return std::error_code(err, std::generic_category()).message(); }

// OpenEXR's messages may span lines; ours are one line.
std::string oneLine(std::string s) {
  for (char& ch : s) {
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// OpenEXR's messages often begin 'Cannot read image file "<path>". '; the path is already
// at the start of ours.
std::string withoutFileName(std::string message, const std::string& path) {
  const std::string marker = "\"" + path + "\". ";
  const size_t at = message.find(marker);
  if (at != std::string::npos) message.erase(0, at + marker.size());
  return message;
}

// Closes a file descriptor unless released.
class Fd {
public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  // Closes now and returns 0 or the errno of close().
  int close() {
    int err = 0;
    if (fd_ >= 0 && ::close(fd_) != 0) err = errno;
    fd_ = -1;
    return err;
  }

private:
  int fd_;
};

// An OpenEXR output stream on a file descriptor. Remembers the first error (errno), because
// OpenEXR's OutputFile destructor writes the line-offset table and swallows exceptions.
class FdOStream final : public Imf::OStream {
public:
  FdOStream(int fd, const std::string& name) : Imf::OStream(name.c_str()), fd_(fd) {}
  void write(const char c[], int n) override {
    if (error_ != 0) throw Iex::IoExc(errorText(error_));
    size_t done = 0;
    const size_t total = n > 0 ? static_cast<size_t>(n) : 0;
    while (done < total) {
      const ssize_t r =
          ::pwrite(fd_, c + done, total - done, static_cast<off_t>(pos_ + done));
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) {
        error_ = r < 0 ? errno : EIO;
        throw Iex::IoExc(errorText(error_));
      }
      done += static_cast<size_t>(r);
    }
    pos_ += total;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  int error() const { return error_; }

private:
  int fd_;
  uint64_t pos_ = 0;
  int error_ = 0;
};

// OpenEXR trusts a file's header: it allocates each attribute at its declared size (and a
// string list's strings, a preview's pixels, line buffers for the data window at theirs)
// before reading, and reads fixed-size types without checking the declared size, so that a
// damaged size desynchronises the rest. This walks the header as OpenEXR will (name, type,
// size, value; an empty name ends it) and refuses, before OpenEXR sees it, any size that
// disagrees with its type or with the file. Multi-part and deep files are not tables.
void checkHeader(int fd, uint64_t size, const std::string& path) {
  std::vector<unsigned char> window;
  uint64_t windowStart = 0;
  const auto byteAt = [&](uint64_t pos) -> unsigned char {
    if (pos >= size) throw TableError(path, "truncated or corrupt OpenEXR file: the header runs past the end of the file");
    if (pos < windowStart || pos >= windowStart + window.size()) {
      window.resize(static_cast<size_t>(std::min<uint64_t>(size - pos, 1 << 16)));
      windowStart = pos;
      if (::pread(fd, window.data(), window.size(), static_cast<off_t>(pos)) != static_cast<ssize_t>(window.size()))
        throw TableError(path, "cannot read: " + errorText(errno));
    }
    return window[static_cast<size_t>(pos - windowStart)];
  };
  const auto int32At = [&](uint64_t pos) {
    return static_cast<int32_t>(byteAt(pos) | (byteAt(pos + 1) << 8) | (byteAt(pos + 2) << 16) |
                                (uint32_t{byteAt(pos + 3)} << 24));
  };
  const auto corrupt = [&](const std::string& what) { return TableError(path, "corrupt OpenEXR file: " + what); };
  if (static_cast<uint32_t>(int32At(4)) & (0x800u | 0x1000u))
    throw TableError(path, "not a table: a deep or multi-part OpenEXR file");
  uint64_t at = 8;
  const auto name = [&](uint64_t& pos) {
    std::string text;
    for (unsigned char c; (c = byteAt(pos++)) != 0;) {
      if (text.size() >= 255) throw corrupt("a header name over 255 bytes");
      text += static_cast<char>(c);
    }
    return text;
  };
  static const std::map<std::string, uint32_t> fixedSizes{
      {"box2i", 16}, {"box2f", 16}, {"v2i", 8},   {"v2f", 8},         {"v3i", 12},       {"v3f", 12},
      {"v2d", 16},   {"v3d", 24},   {"int", 4},   {"float", 4},       {"double", 8},     {"compression", 1},
      {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1}, {"tiledesc", 9}, {"rational", 8},
      {"timecode", 8}, {"keycode", 28}, {"chromaticities", 32}, {"m33f", 36}, {"m44f", 64}, {"m33d", 72},
      {"m44d", 128}};
  for (int count = 0; count < 4096; ++count) {
    const std::string attribute = name(at);
    if (attribute.empty()) return;
    const std::string type = name(at);
    const int32_t declared = int32At(at);
    at += 4;
    if (declared < 0 || static_cast<uint64_t>(declared) > size - std::min(at, size))
      throw corrupt("header attribute '" + attribute + "' of " + std::to_string(static_cast<uint32_t>(declared)) +
                    " bytes runs past the end of the file");
    const auto bytes = static_cast<uint64_t>(declared);
    const auto wrongSize = [&] {
      return corrupt("header attribute '" + attribute + "' (" + type + ") of " + std::to_string(bytes) + " bytes");
    };
    if (const auto fixed = fixedSizes.find(type); fixed != fixedSizes.end() && fixed->second != bytes) throw wrongSize();
    if (type == "chlist") {  // entries of a name and 16 bytes, up to an empty name
      uint64_t pos = at;
      while (!name(pos).empty()) pos += 16;
      if (pos != at + bytes) throw wrongSize();
    } else if (type == "stringvector") {  // entries of a length and that many bytes
      uint64_t pos = at;
      while (pos < at + bytes) {
        const int32_t length = int32At(pos);
        if (length < 0 || static_cast<uint64_t>(length) > at + bytes - pos - 4) throw wrongSize();
        pos += 4 + static_cast<uint64_t>(length);
      }
    } else if (type == "preview") {  // width, height, then 4 bytes a pixel
      if (bytes < 8 || uint64_t{static_cast<uint32_t>(int32At(at))} * static_cast<uint32_t>(int32At(at + 4)) * 4 !=
                           bytes - 8)
        throw wrongSize();
    } else if (attribute == "dataWindow" && type == "box2i") {  // OpenEXR sizes its line buffers from it
      const int64_t width = int64_t{int32At(at + 8)} - int32At(at) + 1;
      const int64_t height = int64_t{int32At(at + 12)} - int32At(at + 4) + 1;
      if (width > 0 && height > 0 && width <= kMaxTableSide && height <= kMaxTableSide &&
          !valuesFitFile(static_cast<uint64_t>(width * height), size))
        throw corrupt(std::to_string(width) + " x " + std::to_string(height) + " values cannot come from " +
                      std::to_string(size) + " bytes");
    }
    at += bytes;
  }
  throw corrupt("over 4096 header attributes");
}

// An OpenEXR input stream on a file descriptor of known size.
class FdIStream final : public Imf::IStream {
public:
  FdIStream(int fd, const std::string& name, uint64_t size)
      : Imf::IStream(name.c_str()), fd_(fd), size_(size) {}
  bool read(char c[], int n) override {
    const uint64_t total = n > 0 ? static_cast<uint64_t>(n) : 0;
    if (pos_ > size_ || total > size_ - pos_) {
      throw Iex::InputExc("early end of file: " + std::to_string(total) +
                          " bytes requested at offset " + std::to_string(pos_) + " of " +
                          std::to_string(size_));
    }
    size_t done = 0;
    while (done < total) {
      const ssize_t r = ::pread(fd_, c + done, total - done, static_cast<off_t>(pos_ + done));
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw Iex::InputExc(errorText(errno));
      if (r == 0) throw Iex::InputExc("early end of file");
      done += static_cast<size_t>(r);
    }
    pos_ += total;
    return pos_ < size_;
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = pos; }

private:
  int fd_;
  uint64_t size_;
  uint64_t pos_ = 0;
};

std::string randomSuffix() {
  static thread_local std::mt19937_64 engine = [] {
    std::seed_seq seed{
        static_cast<unsigned>(std::random_device{}()),
        static_cast<unsigned>(::getpid()),
        static_cast<unsigned>(std::chrono::steady_clock::now().time_since_epoch().count())};
    return std::mt19937_64(seed);
  }();
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(engine()));
  return text;
}

void validateParameters(const std::map<std::string, std::string>& parameters,
                        const std::string& path) {
  // Attribute names are at most 255 characters in OpenEXR (longer ones are truncated).
  const size_t maxKey = 255 - std::char_traits<char>::length(kParameterPrefix);
  for (const auto& entry : parameters) {
    const std::string& key = entry.first;
    if (key.empty()) throw TableError(path, "invalid table: empty parameter name");
    if (key.find('\0') != std::string::npos) {
      throw TableError(path, "invalid table: parameter name contains a NUL character");
    }
    if (key.size() > maxKey) {
      throw TableError(path, "invalid table: parameter name longer than " +
                                 std::to_string(maxKey) + " characters: '" +
                                 key.substr(0, 40) + "...'");
    }
  }
}

// Throws TableError unless the directory that will hold path exists.
void checkDirectory(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (st.type() == fs::file_type::not_found) {
    throw TableError(path, "cannot write: directory '" + dir.string() + "' does not exist");
  }
  if (ec) throw TableError(path, "cannot write: " + ec.message());
  if (st.type() != fs::file_type::directory) {
    throw TableError(path, "cannot write: '" + dir.string() + "' is not a directory");
  }
}

// OpenEXR compresses and decompresses a file's blocks of lines on its own threads, one a
// core (the bytes written are the same): ZIP is most of a big table's write.
void compressOnEveryCore() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))); });
}

// A new temporary beside path (so that the rename is atomic), <path>.tmp-<pid>-<random>,
// open for writing; its name in tmp. Throws TableError naming path.
int openTemporaryFor(const std::string& path, std::string& tmp) {
  int openErr = 0;
  for (int attempt = 0; attempt < 16; ++attempt) {
    tmp = path + ".tmp-" + std::to_string(::getpid()) + "-" + randomSuffix();
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    openErr = errno;
    if (openErr != EEXIST) break;
  }
  throw TableError(path, "cannot write: " + errorText(openErr));
}

// The written temporary flushed, closed and renamed over path: empty, or what failed.
std::string commitTemporary(Fd& fd, const std::string& tmp, const std::string& path) {
  if (::fsync(fd.get()) != 0) return errorText(errno);
  if (const int err = fd.close(); err != 0) return errorText(err);
  if (::rename(tmp.c_str(), path.c_str()) != 0) return errorText(errno);
  return {};
}

void syncDirectoryOf(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    (void)::fsync(fd);  // best effort: durability of the rename
    ::close(fd);
  }
}

}  // namespace

void writeExr(const std::string& path, const Table& table) {
  detail::writeExr(path, table, table.parameters);
}

namespace detail {

void writeExr(const std::string& path, const Table& table,
              const std::map<std::string, std::string>& parameters) {
  validateTable(table, path);
  const std::size_t rowValues = static_cast<std::size_t>(table.width) * table.channels.size();
  writeExrRows(path, table, parameters, table.height,
               [&](int y0, int) { return table.data.data() + static_cast<std::size_t>(y0) * rowValues; });
}

void writeExrRows(const std::string& path, const Table& shape, const std::map<std::string, std::string>& parameters,
                  int rowsPerBlock, const RowSource& rows) {
  compressOnEveryCore();
  validateShape(shape, path);
  validateParameters(parameters, path);
  checkDirectory(path);

  std::string tmp;
  Fd fd(openTemporaryFor(path, tmp));

  std::string failure;
  try {
    const size_t nc = shape.channels.size();
    Imf::Header header(shape.width, shape.height);
    const uint64_t bytes = uint64_t{sizeof(float)} * static_cast<uint64_t>(shape.width) * shape.height * nc;
    if (bytes > kUncompressedAboveBytes) {
      header.compression() = Imf::NO_COMPRESSION;
    } else {
      header.compression() = Imf::ZIP_COMPRESSION;
      header.zipCompressionLevel() = 1;
    }
    header.lineOrder() = Imf::INCREASING_Y;
    for (const std::string& name : shape.channels) {
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    }
    header.insert(kChannelOrderAttribute, Imf::StringVectorAttribute(shape.channels));
    for (const auto& [key, value] : parameters) {
      header.insert(kParameterPrefix + key, Imf::StringAttribute(value));
    }

    FdOStream out(fd.get(), path);
    {
      Imf::OutputFile file(out, header);
      const size_t xStride = nc * sizeof(float), yStride = xStride * static_cast<size_t>(shape.width);
      for (int y0 = 0; y0 < shape.height; y0 += std::max(1, rowsPerBlock)) {
        const int n = std::min(std::max(1, rowsPerBlock), shape.height - y0);
        // Pixel (x, y) of channel c is at block[((y - y0) * w + x) * nc + c]: the slices'
        // base is where row 0 would be.
        char* base = reinterpret_cast<char*>(const_cast<float*>(rows(y0, n))) - static_cast<std::ptrdiff_t>(y0) * yStride;
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < nc; ++c) {
          frame.insert(shape.channels[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
        }
        file.setFrameBuffer(frame);
        file.writePixels(n);
      }
    }  // the destructor writes the line-offset table
    failure = out.error() != 0 ? errorText(out.error()) : commitTemporary(fd, tmp, path);
  } catch (const std::exception& e) {
    failure = oneLine(withoutFileName(e.what(), path));
    if (failure.empty()) failure = "unknown error";
  } catch (...) {
    failure = "unknown error";
  }
  if (!failure.empty()) {
    fd.close();
    ::unlink(tmp.c_str());
    throw TableError(path, "cannot write: " + failure);
  }
  syncDirectoryOf(path);
}

void copyFile(const std::string& from, const std::string& path) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw TableError(from, "cannot open: " + errorText(errno));
  Fd source(in);
  checkDirectory(path);
  std::string tmp;
  Fd fd(openTemporaryFor(path, tmp));
  std::string failure;
  std::vector<char> buffer(1 << 20);
  for (;;) {
    const ssize_t n = ::read(source.get(), buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      failure = "cannot read " + from + ": " + errorText(errno);
      break;
    }
    if (n == 0) break;
    for (ssize_t done = 0; done < n && failure.empty();) {
      const ssize_t w = ::write(fd.get(), buffer.data() + done, static_cast<size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) failure = errorText(w < 0 ? errno : EIO);
      else done += w;
    }
    if (!failure.empty()) break;
  }
  if (failure.empty()) failure = commitTemporary(fd, tmp, path);
  if (!failure.empty()) {
    fd.close();
    ::unlink(tmp.c_str());
    throw TableError(path, "cannot write: " + failure);
  }
  syncDirectoryOf(path);
}

void writeTextFile(const std::string& path, const std::string& text) {
  checkDirectory(path);
  std::string tmp;
  Fd fd(openTemporaryFor(path, tmp));
  std::string failure;
  for (std::size_t done = 0; done < text.size() && failure.empty();) {
    const ssize_t n = ::write(fd.get(), text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) failure = errorText(n < 0 ? errno : EIO);
    else done += static_cast<std::size_t>(n);
  }
  if (failure.empty()) failure = commitTemporary(fd, tmp, path);
  if (!failure.empty()) {
    fd.close();
    ::unlink(tmp.c_str());
    throw TableError(path, "cannot write: " + failure);
  }
  syncDirectoryOf(path);
}

}  // namespace detail

Table readExr(const std::string& path, const std::vector<std::string>& requiredChannels) {
  compressOnEveryCore();
  const int rawFd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (rawFd < 0) throw TableError(path, "cannot open: " + errorText(errno));
  Fd fd(rawFd);
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw TableError(path, "cannot open: " + errorText(errno));
  if (S_ISDIR(st.st_mode)) throw TableError(path, "cannot open: " + errorText(EISDIR));
  if (!S_ISREG(st.st_mode)) throw TableError(path, "cannot open: not a regular file");
  const uint64_t size = static_cast<uint64_t>(st.st_size);

  char magic[4] = {0, 0, 0, 0};
  if (size < 4 || ::pread(fd.get(), magic, 4, 0) != 4 || !Imf::isImfMagic(magic)) {
    throw TableError(path, "not an OpenEXR file");
  }

  try {
    // OpenEXR sizes its line buffers from the header before any pixel is read: a damaged
    // header must not make it allocate gigabytes.
    static const bool limited = [] {
      Imf::Header::setMaxImageSize(kMaxTableSide, kMaxTableSide);
      Imf::Header::setMaxTileSize(kMaxTableSide, kMaxTableSide);
      return true;
    }();
    (void)limited;
    checkHeader(fd.get(), size, path);
    FdIStream in(fd.get(), path, size);
    Imf::InputFile file(in);
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    const int64_t width = static_cast<int64_t>(dw.max.x) - dw.min.x + 1;
    const int64_t height = static_cast<int64_t>(dw.max.y) - dw.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX) {
      throw TableError(path, "corrupt OpenEXR file: invalid data window");
    }

    // Channels as stored: OpenEXR keeps them sorted by name; the writer records the table's
    // order in kChannelOrderAttribute.
    const Imf::ChannelList& list = header.channels();
    std::vector<std::string> stored;
    for (auto it = list.begin(); it != list.end(); ++it) stored.emplace_back(it.name());
    if (const auto* order =
            header.findTypedAttribute<Imf::StringVectorAttribute>(kChannelOrderAttribute)) {
      const std::vector<std::string>& names = order->value();
      const std::set<std::string> a(names.begin(), names.end()), b(stored.begin(), stored.end());
      if (names.size() == stored.size() && a == b) stored = names;
    }
    if (stored.empty()) throw TableError(path, "corrupt OpenEXR file: no channels");

    const std::vector<std::string>& wanted = requiredChannels.empty() ? stored : requiredChannels;
    std::vector<std::string> missing;
    std::set<std::string> seen;
    for (const std::string& name : wanted) {
      if (!seen.insert(name).second) {
        throw TableError(path, "channel '" + name + "' requested twice");
      }
      const Imf::Channel* channel = list.findChannel(name);
      if (channel == nullptr) {
        missing.push_back(name);
        continue;
      }
      if (channel->type != Imf::FLOAT) {
        const char* type = channel->type == Imf::HALF ? "HALF" : channel->type == Imf::UINT
                                                                     ? "UINT"
                                                                     : "of an unknown type";
        throw TableError(path, "channel '" + name + "' is " + type + ", expected FLOAT");
      }
      if (channel->xSampling != 1 || channel->ySampling != 1) {
        throw TableError(path, "channel '" + name + "' is subsampled");
      }
    }
    if (!missing.empty()) {
      std::string text = missing.size() == 1 ? "missing channel " : "missing channels ";
      for (size_t i = 0; i < missing.size(); ++i) {
        text += (i ? ", '" : "'") + missing[i] + "'";
      }
      text += " (has: ";
      for (size_t i = 0; i < stored.size(); ++i) text += (i ? ", " : "") + stored[i];
      throw TableError(path, text + ")");
    }

    const uint64_t count = static_cast<uint64_t>(width) * static_cast<uint64_t>(height) *
                           static_cast<uint64_t>(wanted.size());
    if (count > kMaxTableValues) {
      throw TableError(path, "table too large: " + std::to_string(width) + " x " +
                                 std::to_string(height) + " x " +
                                 std::to_string(wanted.size()));
    }
    // No compression of EXR packs more than about 1000 bytes into one: a header promising
    // more values than the file could hold is damaged (checked before allocating them).
    if (!valuesFitFile(count, size)) {
      throw TableError(path, "corrupt OpenEXR file: " + std::to_string(width) + " x " + std::to_string(height) +
                                 " x " + std::to_string(wanted.size()) + " values cannot come from " +
                                 std::to_string(size) + " bytes");
    }

    if (!file.isComplete()) {
      throw TableError(path, "truncated or incomplete OpenEXR file (scanlines are missing)");
    }

    Table table;
    table.width = static_cast<int>(width);
    table.height = static_cast<int>(height);
    table.channels = wanted;
    table.data.assign(static_cast<size_t>(count), 0.0f);
    const size_t nc = wanted.size();
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < nc; ++c) {
      frame.insert(wanted[c], Imf::Slice::Make(Imf::FLOAT, table.data.data() + c, dw,
                                               nc * sizeof(float),
                                               nc * sizeof(float) * static_cast<size_t>(width)));
    }
    file.setFrameBuffer(frame);
    file.readPixels(dw.min.y, dw.max.y);

    const std::string prefix = kParameterPrefix;
    for (auto it = header.begin(); it != header.end(); ++it) {
      const std::string name = it.name();
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      if (const auto* value = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
        table.parameters[name.substr(prefix.size())] = value->value();
      }
    }
    return table;
  } catch (const TableError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw TableError(path, "out of memory reading the table");
  } catch (const std::exception& e) {
    throw TableError(path, "corrupt or truncated OpenEXR file: " +
                                 oneLine(withoutFileName(e.what(), path)));
  }
}

}  // namespace umbra::tables
