#pragma once
// On-disk cache of tables, keyed by kind and a hash of every parameter.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "umbra/tables/Table.h"

namespace umbra::tables {

class PlanarTableFile;

class TableCache {
public:
  // $UMBRA_CACHE_DIR if set and non-empty, else $XDG_CACHE_HOME/umbra (if absolute), else
  // $HOME/.cache/umbra (HOME from the password database if unset), else <tmp>/umbra-cache.
  static std::string defaultDirectory();

  // The size cap in bytes from $UMBRA_CACHE_MAX_MB (MiB, a non-negative decimal number such
  // as 512 or 0.5; 0 = no limit), default 2048 MiB when unset or empty. Any other value
  // (negative, not a number, trailing characters) prints one line on stderr naming the
  // variable and the value (once per distinct value) and gives the default.
  static std::uint64_t defaultMaxBytes();

  // The directory is created (with parents) on the first store(). maxBytes caps the total
  // size of the cache's own files in the directory (0 = no limit); see store().
  explicit TableCache(std::string directory, std::uint64_t maxBytes = defaultMaxBytes());

  // <dir>/<kind>-<parameterHash(parameters)>.exr. kind must be non-empty and made of
  // [A-Za-z0-9_.-], not starting with '.', else std::invalid_argument.
  std::string pathFor(const std::string& kind,
                      const std::map<std::string, std::string>& parameters) const;

  // The cached table, or nullopt when the file is missing, unreadable / corrupt, or its
  // stored parameters differ from parameters plus {"kind": kind}. The returned table's
  // parameters include "kind". A hit sets the file's modification time to now (its last
  // use, for the size cap); failing to (a read-only cache) is not an error.
  std::optional<Table> load(const std::string& kind,
                            const std::map<std::string, std::string>& parameters) const;

  // Writes table with parameters plus {"kind": kind} (atomically, through writeExr),
  // replacing any cached file. table.parameters is ignored. Throws TableError when the
  // directory cannot be created or the file cannot be written. A "kind" entry in
  // parameters that differs from kind throws std::invalid_argument (also in load/pathFor).
  // Then, while the cache's own files (regular files named <kind>-<16 hex digits>.exr, as
  // pathFor makes them, and storeJson's .json) total more than maxBytes, removes them least recently used (oldest
  // modification time) first, never the file just written. Other files, subdirectories and
  // the writer's temporaries are left alone; removal errors are ignored.
  void store(const std::string& kind, const std::map<std::string, std::string>& parameters,
             const Table& table) const;

  // store() of values held elsewhere: shape's size and channels (its data unused), the
  // values interleaved as Table::data holds them.
  void store(const std::string& kind, const std::map<std::string, std::string>& parameters, const Table& shape,
             const float* values) const;

  // store() of a table made a batch of channels at a time: written from its file a block of
  // rows at a time (the same file store() writes for the same values), never held whole.
  void store(const std::string& kind, const std::map<std::string, std::string>& parameters,
             const PlanarTableFile& table) const;

  // The table `other` holds for kind and parameters, copied here as it is (a stored file
  // read back by load() here), without reading its values; then the cap as store() keeps
  // it. Throws TableError naming the file that cannot be read or written.
  void copyFrom(const TableCache& other, const std::string& kind,
                const std::map<std::string, std::string>& parameters) const;

  // A JSON document kept beside the tables, for results that are not float images (the
  // Lorenz-Mie optics, which must come back to the bit): jsonPathFor, pathFor's path ending
  // in .json instead, under the
  // same size cap and checks of kind. loadJson gives the document stored with exactly these
  // parameters, or nullopt (missing, unreadable, not JSON, other parameters); a hit marks
  // the file used now. storeJson writes it atomically; it throws TableError like store().
  std::string jsonPathFor(const std::string& kind, const std::map<std::string, std::string>& parameters) const;
  std::optional<nlohmann::json> loadJson(const std::string& kind,
                                         const std::map<std::string, std::string>& parameters) const;
  void storeJson(const std::string& kind, const std::map<std::string, std::string>& parameters,
                 const nlohmann::json& document) const;

  // An exclusive lock on the making of the table pathFor names, shared by every process
  // using the directory (the ranks of an MPI run, two runs side by side): whoever holds it
  // makes and stores the table; the others wait, then find it stored. flock(2) on
  // pathFor's path ending in .lock; the file goes when the lock is released. Blocks while
  // another process holds it. Null when the lock file cannot be made (a read-only or
  // missing directory: then nothing can be stored either, and nothing is waited for).
  class Lock;
  std::unique_ptr<Lock> lock(const std::string& kind, const std::map<std::string, std::string>& parameters) const;

  const std::string& directory() const { return directory_; }
  std::uint64_t maxBytes() const { return maxBytes_; }

private:
  std::string pathWith(const std::string& kind, const std::map<std::string, std::string>& parameters,
                       const char* extension) const;
  void enforceCap(const std::string& keepPath) const;

  std::string directory_;
  std::uint64_t maxBytes_;
};

class TableCache::Lock {
public:
  Lock(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  ~Lock();  // removes the lock file, then releases the lock
  Lock(const Lock&) = delete;
  Lock& operator=(const Lock&) = delete;

private:
  int fd_;
  std::string path_;
};

}  // namespace umbra::tables
