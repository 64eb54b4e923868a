#pragma once
// Tables through the cache: read when matching ones are there, else computed together and
// stored. What every source of tables does with the cache, in one place.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "umbra/tables/Table.h"
#include "umbra/tables/TableCache.h"

namespace umbra::tables {

/// A table asked of the cache: its kind and parameters (the key), what a cached one must be
/// to be taken (its size and channels; 0 and empty: any), and whether the caller needs it
/// now (a table that the same computation makes and that is only worth storing: not needed).
struct TableRequest {
  std::string kind;
  std::map<std::string, std::string> parameters;
  int width = 0, height = 0;
  std::vector<std::string> channels;
  bool needed = true;
};

/// What became of the needed tables: how many were read from the cache, how many computed,
/// and why a computed table could not be stored (a read-only directory, a full disc): not
/// an error, the table is still given.
struct CacheOutcome {
  int hits = 0, computed = 0;
  std::string warning;
};

/// The needed tables of `requests` from `cache` (the others left empty), when every needed
/// one is there as its request says; else nullopt.
std::optional<std::vector<Table>> cachedTables(const TableCache& cache, const std::vector<TableRequest>& requests);

/// The tables of `requests`, in their order. When `useCache` and each needed one is in
/// `cache` as its request says, those are read (the others are left empty). Else compute()
/// gives all of them, in the same order (it may throw: then nothing is stored), and each is
/// stored when `useCache`; under the cache's lock (TableCache::lock, named by the first
/// request), so that of several processes asking at once one computes and the others read.
/// Throws std::logic_error when compute() gives another number of tables.
std::vector<Table> cachedOrComputed(const TableCache& cache, bool useCache, const std::vector<TableRequest>& requests,
                                    const std::function<std::vector<Table>()>& compute, CacheOutcome& outcome);

}  // namespace umbra::tables
