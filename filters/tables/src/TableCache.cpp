#include "umbra/tables/TableCache.h"

#include <pwd.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "ExrInternal.h"
#include "umbra/tables/Exr.h"

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

void checkKind(const std::string& kind, const std::map<std::string, std::string>& parameters) {
  if (kind.empty()) throw std::invalid_argument("TableCache: empty table kind");
  if (kind[0] == '.') {
    throw std::invalid_argument("TableCache: table kind '" + kind + "' starts with '.'");
  }
  for (char ch : kind) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                    (ch >= '0' && ch <= '9') || ch == '_' || ch == '-' || ch == '.';
    if (!ok) {
      throw std::invalid_argument("TableCache: table kind '" + kind +
                                  "' may only contain letters, digits, '_', '-' and '.'");
    }
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

}  // namespace

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

TableCache::TableCache(std::string directory) : directory_(std::move(directory)) {}

std::string TableCache::pathFor(const std::string& kind,
                                const std::map<std::string, std::string>& parameters) const {
  checkKind(kind, parameters);
  return (fs::path(directory_) / (kind + "-" + parameterHash(parameters) + ".exr")).string();
}

std::optional<Table> TableCache::load(const std::string& kind,
                                      const std::map<std::string, std::string>& parameters) const {
  const std::string path = pathFor(kind, parameters);
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  Table table;
  try {
    table = readExr(path);
  } catch (const TableError&) {
    return std::nullopt;  // corrupt or unreadable: the caller recomputes and overwrites
  }
  if (table.parameters != withKind(kind, parameters)) {
    return std::nullopt;  // stale file or hash collision
  }
  return table;
}

void TableCache::store(const std::string& kind,
                       const std::map<std::string, std::string>& parameters,
                       const Table& table) const {
  const std::string path = pathFor(kind, parameters);
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec) {
    throw TableError(path, "cannot create cache directory '" + directory_ + "': " + ec.message());
  }
  detail::writeExr(path, table, withKind(kind, parameters));
}

}  // namespace umbra::tables
