#include "umbra/tables/TableCache.h"

#include <pwd.h>
#include <unistd.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <signal.h>

#include <algorithm>
#include <cstdio>
#include <csignal>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <locale>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "ExrInternal.h"
#include "umbra/tables/Exr.h"
#include "umbra/tables/PlanarTableFile.h"

namespace fs = std::filesystem;

namespace umbra::tables {
namespace {

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? std::string(value) : std::string();
}

std::string homeFromPasswordDatabase() {
  long size = ::sysconf(_SC_GETPW_R_SIZE_MAX);
  std::vector<char> buffer(size > 0 ? static_cast<size_t>(size) : 16384);
  struct passwd entry {};
  struct passwd* result = nullptr;
  if (::getpwuid_r(::getuid(), &entry, buffer.data(), buffer.size(), &result) == 0 &&
      result != nullptr && result->pw_dir != nullptr) {
    return result->pw_dir;
  }
  return {};
}

bool isKindCharacter(char ch) {
  return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
         ch == '_' || ch == '-' || ch == '.';
}

void checkKind(const std::string& kind, const std::map<std::string, std::string>& parameters) {
  if (kind.empty()) throw std::invalid_argument("TableCache: empty table kind");
  if (kind[0] == '.') {
    throw std::invalid_argument("TableCache: table kind '" + kind + "' starts with '.'");
  }
  if (!std::all_of(kind.begin(), kind.end(), isKindCharacter)) {
    throw std::invalid_argument("TableCache: table kind '" + kind +
                                "' may only contain letters, digits, '_', '-' and '.'");
  }
  const auto it = parameters.find("kind");
  if (it != parameters.end() && it->second != kind) {
    throw std::invalid_argument("TableCache: parameter kind='" + it->second +
                                "' differs from the table kind '" + kind + "'");
  }
}

std::map<std::string, std::string> withKind(const std::string& kind,
                                            std::map<std::string, std::string> parameters) {
  parameters["kind"] = kind;
  return parameters;
}

// The header entry that holds the checksum of a cached table's values (not a parameter),
// and the one that held the byte-by-byte checksum before it: a file with that is stale.
constexpr const char* kChecksumKey = "values-checksum";
constexpr const char* kOldChecksumKey = "checksum";

// FNV-1a (64 bits) over the values' 8-byte words in four interleaved lanes (word i into lane
// i % 4, the last word padded with zeros), the lanes and the byte count folded together at
// the end, as 16 hex digits: a truncated, swapped or edited table no longer matches its
// header. Fed the values in order, a block of rows at a time or all at once (the same
// words whatever the blocks). The lanes' multiplications are independent, so that the
// checksum is not one multiplication's latency per byte.
class Checksum {
public:
  Checksum(int width, int height, std::size_t channels) {
    const std::int64_t dims[3] = {width, height, static_cast<std::int64_t>(channels)};
    mix(dims, sizeof dims);
  }
  void mix(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_ += n;
    while (n > 0 && pending_ > 0) {  // complete a word begun by the last block
      word_[pending_++] = *p++, --n;
      if (pending_ == 8) addWord(word_), pending_ = 0;
    }
    for (; n >= 8; p += 8, n -= 8) addWord(p);
    if (n > 0) std::memcpy(word_, p, n), pending_ = static_cast<int>(n);  // pending_ was 0
  }
  std::string text() const {
    Checksum c = *this;
    if (c.pending_ > 0) {
      std::fill(c.word_ + c.pending_, c.word_ + 8, 0);
      c.addWord(c.word_);
    }
    std::uint64_t h = kOffset;
    for (std::uint64_t lane : c.lanes_) h = (h ^ lane) * kPrime;
    h = (h ^ c.bytes_) * kPrime;
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
  }

private:
  static constexpr std::uint64_t kOffset = 1469598103934665603ull, kPrime = 1099511628211ull;
  void addWord(const unsigned char* p) {
    std::uint64_t w;
    std::memcpy(&w, p, sizeof w);
    std::uint64_t& lane = lanes_[words_++ & 3];
    lane = (lane ^ w) * kPrime;
  }
  std::uint64_t lanes_[4] = {kOffset, kOffset ^ 1, kOffset ^ 2, kOffset ^ 3};
  std::uint64_t words_ = 0, bytes_ = 0;
  unsigned char word_[8] = {};
  int pending_ = 0;
};

/// Whether every value is finite (a test of the exponent bits, branch-free: it vectorises).
bool allFinite(const float* v, std::size_t n) {
  std::uint32_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t bits;
    std::memcpy(&bits, v + i, sizeof bits);
    bad |= static_cast<std::uint32_t>((bits & 0x7f800000u) == 0x7f800000u);
  }
  return bad == 0;
}

// The cache's directory (with parents) before a file at path goes into it.
void createDirectory(const std::string& directory, const std::string& path) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) throw TableError(path, "cannot create cache directory '" + directory + "': " + ec.message());
}

std::string checksumOf(const Table& t) {
  Checksum sum(t.width, t.height, t.channels.size());
  sum.mix(t.data.data(), t.data.size() * sizeof(float));
  return sum.text();
}

// Why a cached table cannot be used as it is (its size, a non-finite value, its checksum),
// or empty.
std::string contentProblem(const Table& t) {
  const std::size_t expected = static_cast<std::size_t>(std::max(t.width, 0)) * std::max(t.height, 0) * t.channels.size();
  if (t.data.size() != expected || expected == 0)
    return std::to_string(t.data.size()) + " values for " + std::to_string(t.width) + "x" + std::to_string(t.height) +
           "x" + std::to_string(t.channels.size());
  if (!allFinite(t.data.data(), t.data.size()))
    for (std::size_t i = 0; i < t.data.size(); ++i)
      if (!std::isfinite(t.data[i])) return "a non-finite value (at " + std::to_string(i) + ")";
  const auto stored = t.parameters.find(kChecksumKey);
  if (stored == t.parameters.end()) return "no checksum in its header";
  if (stored->second != checksumOf(t)) return "its values do not match the checksum in its header";
  return {};
}

// A writer's temporary: <name>.tmp-<pid>-<random>; its pid, or 0 for another name.
long temporaryOwner(const std::string& name) {
  const auto at = name.rfind(".tmp-");
  if (at == std::string::npos) return 0;
  const std::string rest = name.substr(at + 5);
  const auto dash = rest.find('-');
  if (dash == std::string::npos || dash == 0) return 0;
  try {
    std::size_t used = 0;
    const long pid = std::stol(rest.substr(0, dash), &used);
    return used == dash && pid > 0 ? pid : 0;
  } catch (const std::exception&) {
    return 0;
  }
}

// A temporary left by a writer that is gone (its process does not exist) or that has been
// writing for more than an hour.
bool staleTemporary(const fs::path& path, long pid) {
  std::error_code ec;
  const auto age = fs::file_time_type::clock::now() - fs::last_write_time(path, ec);
  if (!ec && age > std::chrono::hours(1)) return true;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// Whether name is one pathFor makes: <kind>-<16 lowercase hex digits (parameterHash)>.exr,
// or storeJson's .json. The writer's temporaries (<name>.tmp-<pid>-<random>) end in neither.
bool isCacheFileName(const std::string& name) {
  constexpr size_t hashLength = 16;
  for (const std::string suffix : {".exr", ".json"}) {
    if (name.size() < 1 + 1 + hashLength + suffix.size() ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
      continue;
    }
    const size_t hashStart = name.size() - suffix.size() - hashLength;
    const std::string kind = name.substr(0, hashStart - 1);
    const auto hash = name.begin() + static_cast<std::ptrdiff_t>(hashStart);
    return name[hashStart - 1] == '-' && kind[0] != '.' &&
           std::all_of(kind.begin(), kind.end(), isKindCharacter) &&
           std::all_of(hash, hash + hashLength,
                       [](char ch) { return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f'); });
  }
  return false;
}

constexpr std::uint64_t kMiB = 1024 * 1024;
constexpr std::uint64_t kDefaultMaxMiB = 2048;

// MiB as a plain decimal number ("512", "0.5", "0") in bytes, rounded up; nullopt for
// anything else (sign, exponent, spaces, hex, inf/nan, trailing characters).
std::optional<std::uint64_t> parseMiB(const std::string& text) {
  const auto digits = std::count_if(text.begin(), text.end(),
                                    [](char ch) { return ch >= '0' && ch <= '9'; });
  const auto points = std::count(text.begin(), text.end(), '.');
  if (digits == 0 || points > 1 || static_cast<size_t>(digits + points) != text.size()) {
    return std::nullopt;
  }
  std::istringstream in(text);
  in.imbue(std::locale::classic());  // '.' whatever the program's locale
  double mib = 0.0;
  if (!(in >> mib)) return std::nullopt;
  const double bytes = std::ceil(mib * static_cast<double>(kMiB));
  if (bytes >= static_cast<double>(std::numeric_limits<std::uint64_t>::max())) {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return static_cast<std::uint64_t>(bytes);
}

}  // namespace

std::uint64_t TableCache::defaultMaxBytes() {
  const std::string value = environment("UMBRA_CACHE_MAX_MB");
  if (value.empty()) return kDefaultMaxMiB * kMiB;
  if (const std::optional<std::uint64_t> bytes = parseMiB(value)) return *bytes;
  // Warn once per value: a GUI makes a TableCache per frame.
  static std::mutex mutex;
  static std::string lastWarned;
  const std::lock_guard<std::mutex> lock(mutex);
  if (value != lastWarned) {
    std::cerr << "umbra: UMBRA_CACHE_MAX_MB='" << value
              << "' is not a size in MiB (a number >= 0, 0 = no limit); using the default "
              << kDefaultMaxMiB << " MiB\n";
    lastWarned = value;
  }
  return kDefaultMaxMiB * kMiB;
}

std::string TableCache::defaultDirectory() {
  if (std::string dir = environment("UMBRA_CACHE_DIR"); !dir.empty()) return dir;
  // The XDG base directory spec says relative paths are invalid and must be ignored.
  if (std::string xdg = environment("XDG_CACHE_HOME"); !xdg.empty() && xdg[0] == '/') {
    return (fs::path(xdg) / "umbra").string();
  }
  std::string home = environment("HOME");
  if (home.empty()) home = homeFromPasswordDatabase();
  if (!home.empty()) return (fs::path(home) / ".cache" / "umbra").string();
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  return ((ec ? fs::path("/tmp") : tmp) / "umbra-cache").string();
}

TableCache::TableCache(std::string directory, std::uint64_t maxBytes)
    : directory_(std::move(directory)), maxBytes_(maxBytes) {}

std::string TableCache::pathWith(const std::string& kind, const std::map<std::string, std::string>& parameters,
                                 const char* extension) const {
  checkKind(kind, parameters);
  return (fs::path(directory_) / (kind + "-" + parameterHash(parameters) + extension)).string();
}

std::string TableCache::pathFor(const std::string& kind,
                                const std::map<std::string, std::string>& parameters) const {
  return pathWith(kind, parameters, ".exr");
}

std::unique_ptr<TableCache::Lock> TableCache::lock(const std::string& kind,
                                                   const std::map<std::string, std::string>& parameters) const {
  const std::string path = pathWith(kind, parameters, ".lock");
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  // The file locked must still be the one named: a holder removes it on release, and a
  // process that opened it before then would hold a lock nobody else sees.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return nullptr;
    int rc;
    do rc = ::flock(fd, LOCK_EX);
    while (rc != 0 && errno == EINTR);
    struct stat held {}, named {};
    if (rc == 0 && ::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev)
      return std::make_unique<Lock>(fd, path);
    ::close(fd);
    if (rc != 0) return nullptr;  // no locks on this file system
  }
  return nullptr;
}

TableCache::Lock::~Lock() {
  ::unlink(path_.c_str());
  ::close(fd_);  // releases the lock
}

std::string TableCache::jsonPathFor(const std::string& kind,
                                    const std::map<std::string, std::string>& parameters) const {
  return pathWith(kind, parameters, ".json");
}

std::optional<nlohmann::json> TableCache::loadJson(const std::string& kind,
                                                   const std::map<std::string, std::string>& parameters) const {
  const std::string path = jsonPathFor(kind, parameters);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const nlohmann::json file = nlohmann::json::parse(in, nullptr, false);
  if (file.is_discarded() || !file.is_object() || !file.contains("parameters") || !file.contains("document"))
    return std::nullopt;  // truncated or not ours: the caller computes it again and overwrites
  std::map<std::string, std::string> stored;
  for (const auto& [key, value] : file["parameters"].items()) {
    if (!value.is_string()) return std::nullopt;
    stored[key] = value.get<std::string>();
  }
  if (stored != withKind(kind, parameters)) return std::nullopt;  // stale file or hash collision
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // used now; may fail
  return file["document"];
}

void TableCache::storeJson(const std::string& kind, const std::map<std::string, std::string>& parameters,
                           const nlohmann::json& document) const {
  const std::string path = jsonPathFor(kind, parameters);
  createDirectory(directory_, path);
  const nlohmann::json file = {{"parameters", withKind(kind, parameters)}, {"document", document}};
  detail::writeTextFile(path, file.dump());
  enforceCap(path);
}

std::optional<Table> TableCache::load(const std::string& kind,
                                      const std::map<std::string, std::string>& parameters) const {
  const std::string path = pathFor(kind, parameters);
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  Table table;
  try {
    table = readExr(path);
  } catch (const TableError& e) {
    std::cerr << "umbra: cache: " << e.what() << "; computing it again\n";
    return std::nullopt;  // corrupt or unreadable: the caller recomputes and overwrites
  }
  if (table.parameters.count(kOldChecksumKey) && !table.parameters.count(kChecksumKey))
    return std::nullopt;  // written with the earlier checksum: stale, computed again
  if (const std::string problem = contentProblem(table); !problem.empty()) {
    std::cerr << "umbra: cache: " << path << ": " << problem << "; computing it again\n";
    return std::nullopt;
  }
  table.parameters.erase(kChecksumKey);
  if (table.parameters != withKind(kind, parameters)) {
    return std::nullopt;  // stale file or hash collision
  }
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // used now; may fail
  return table;
}

void TableCache::store(const std::string& kind,
                       const std::map<std::string, std::string>& parameters,
                       const Table& table) const {
  validateTable(table, pathFor(kind, parameters));
  store(kind, parameters, table, table.data.data());
}

void TableCache::store(const std::string& kind, const std::map<std::string, std::string>& parameters,
                       const Table& shape, const float* values) const {
  const std::string path = pathFor(kind, parameters);
  createDirectory(directory_, path);
  detail::validateShape(shape, path);
  const std::size_t rowValues = static_cast<std::size_t>(shape.width) * shape.channels.size();
  const std::size_t n = rowValues * static_cast<std::size_t>(shape.height);
  if (!allFinite(values, n)) throw TableError(path, "not cached: the table holds a non-finite value");
  Checksum sum(shape.width, shape.height, shape.channels.size());
  sum.mix(values, n * sizeof(float));
  auto header = withKind(kind, parameters);
  header[kChecksumKey] = sum.text();
  detail::writeExrRows(path, shape, header, shape.height,
                       [&](int y0, int) { return values + static_cast<std::size_t>(y0) * rowValues; });
  enforceCap(path);
}

void TableCache::store(const std::string& kind, const std::map<std::string, std::string>& parameters,
                       const PlanarTableFile& table) const {
  const std::string path = pathFor(kind, parameters);
  createDirectory(directory_, path);
  // Twice through the rows: the checksum goes in the header, before them.
  constexpr int kRows = 256;
  std::vector<float> block;
  Checksum sum(table.width(), table.height(), table.channels().size());
  for (int y0 = 0; y0 < table.height(); y0 += kRows) {
    table.rows(y0, std::min(kRows, table.height() - y0), block);
    if (!allFinite(block.data(), block.size()))
      throw TableError(path, "not cached: the table holds a non-finite value");
    sum.mix(block.data(), block.size() * sizeof(float));
  }
  auto header = withKind(kind, parameters);
  header[kChecksumKey] = sum.text();
  Table shape;
  shape.width = table.width();
  shape.height = table.height();
  shape.channels = table.channels();
  detail::writeExrRows(path, shape, header, kRows, [&](int y0, int n) {
    table.rows(y0, n, block);
    return block.data();
  });
  enforceCap(path);
}

void TableCache::copyFrom(const TableCache& other, const std::string& kind,
                          const std::map<std::string, std::string>& parameters) const {
  const std::string path = pathFor(kind, parameters);
  createDirectory(directory_, path);
  detail::copyFile(other.pathFor(kind, parameters), path);
  enforceCap(path);
}

void TableCache::enforceCap(const std::string& keepPath) const {
  if (maxBytes_ == 0) return;
  struct CacheFile {
    fs::file_time_type usedAt;
    fs::path path;
    std::uintmax_t bytes;
  };
  std::vector<CacheFile> files;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(directory_, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& path = it->path();
    std::error_code fileEc;
    // A writer's temporary: removed when its writer is gone (kill -9), else counted.
    const std::string name = path.filename().string();
    const auto tmp = name.rfind(".tmp-");
    if (tmp != std::string::npos && isCacheFileName(name.substr(0, tmp)) &&
        fs::is_regular_file(fs::symlink_status(path, fileEc))) {
      if (const long pid = temporaryOwner(name); pid > 0 && staleTemporary(path, pid)) {
        fs::remove(path, fileEc);
      } else {
        total += fs::file_size(path, fileEc);
      }
      continue;
    }
    // symlink_status: a link is never one of ours, even with a cache file's name.
    if (!isCacheFileName(name) || !fs::is_regular_file(fs::symlink_status(path, fileEc))) {
      continue;
    }
    const std::uintmax_t bytes = fs::file_size(path, fileEc);
    if (fileEc) continue;  // removed meanwhile by another process
    const fs::file_time_type usedAt = fs::last_write_time(path, fileEc);
    if (fileEc) continue;
    total += bytes;
    files.push_back({usedAt, path, bytes});
  }
  if (total <= maxBytes_) return;
  std::sort(files.begin(), files.end(), [](const CacheFile& a, const CacheFile& b) {
    return std::tie(a.usedAt, a.path) < std::tie(b.usedAt, b.path);
  });
  const fs::path keepName = fs::path(keepPath).filename();
  for (const CacheFile& file : files) {
    if (total <= maxBytes_) break;
    if (file.path.filename() == keepName) continue;
    std::error_code removeEc;
    fs::remove(file.path, removeEc);  // gone already (another process) counts as removed
    if (!removeEc) total -= file.bytes;
  }
}

}  // namespace umbra::tables
