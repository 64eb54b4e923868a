#include "umbra/tables/CachedTables.h"

#include <memory>
#include <optional>
#include <stdexcept>

namespace umbra::tables {

std::optional<std::vector<Table>> cachedTables(const TableCache& cache, const std::vector<TableRequest>& requests) {
  std::vector<Table> tables(requests.size());
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const TableRequest& r = requests[i];
    if (!r.needed) continue;
    std::optional<Table> t = cache.load(r.kind, r.parameters);
    if (!t || (r.width != 0 && t->width != r.width) || (r.height != 0 && t->height != r.height) ||
        (!r.channels.empty() && t->channels != r.channels))
      return std::nullopt;
    tables[i] = std::move(*t);
  }
  return tables;
}

std::vector<Table> cachedOrComputed(const TableCache& cache, bool useCache, const std::vector<TableRequest>& requests,
                                    const std::function<std::vector<Table>()>& compute, CacheOutcome& outcome) {
  outcome = {};
  std::unique_ptr<TableCache::Lock> lock;
  if (useCache) {
    std::optional<std::vector<Table>> cached = cachedTables(cache, requests);
    // Not there: made by one process at a time (the first request names the set), and
    // looked for again once this one may make it: another may just have stored it.
    if (!cached && !requests.empty()) {
      lock = cache.lock(requests.front().kind, requests.front().parameters);
      if (lock) cached = cachedTables(cache, requests);
    }
    if (cached) {
      for (const TableRequest& r : requests) outcome.hits += r.needed ? 1 : 0;
      return std::move(*cached);
    }
  }
  std::vector<Table> tables = compute();
  if (tables.size() != requests.size())
    throw std::logic_error("cachedOrComputed: " + std::to_string(requests.size()) + " tables asked for, " +
                           std::to_string(tables.size()) + " computed");
  for (std::size_t i = 0; i < requests.size(); ++i) {
    outcome.computed += requests[i].needed ? 1 : 0;
    if (!useCache) continue;
    try {
      cache.store(requests[i].kind, requests[i].parameters, tables[i]);
    } catch (const std::exception& e) {
      if (outcome.warning.empty()) outcome.warning = e.what();
    }
  }
  return tables;
}

}  // namespace umbra::tables
