#pragma once
// On-disk cache of tables, keyed by kind and a hash of every parameter.

#include <map>
#include <optional>
#include <string>

#include "umbra/tables/Table.h"

namespace umbra::tables {

class TableCache {
public:
  // $UMBRA_CACHE_DIR if set and non-empty, else $XDG_CACHE_HOME/umbra (if absolute), else
  // $HOME/.cache/umbra (HOME from the password database if unset), else <tmp>/umbra-cache.
  static std::string defaultDirectory();

  // The directory is created (with parents) on the first store().
  explicit TableCache(std::string directory);

  // <dir>/<kind>-<parameterHash(parameters)>.exr. kind must be non-empty and made of
  // [A-Za-z0-9_.-], not starting with '.', else std::invalid_argument.
  std::string pathFor(const std::string& kind,
                      const std::map<std::string, std::string>& parameters) const;

  // The cached table, or nullopt when the file is missing, unreadable / corrupt, or its
  // stored parameters differ from parameters plus {"kind": kind}. The returned table's
  // parameters include "kind".
  std::optional<Table> load(const std::string& kind,
                            const std::map<std::string, std::string>& parameters) const;

  // Writes table with parameters plus {"kind": kind} (atomically, through writeExr),
  // replacing any cached file. table.parameters is ignored. Throws TableError when the
  // directory cannot be created or the file cannot be written. A "kind" entry in
  // parameters that differs from kind throws std::invalid_argument (also in load/pathFor).
  void store(const std::string& kind, const std::map<std::string, std::string>& parameters,
             const Table& table) const;

  const std::string& directory() const { return directory_; }

private:
  std::string directory_;
};

}  // namespace umbra::tables
