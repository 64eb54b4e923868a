#include "umbra/tables/CachedTables.h"

#include <stdexcept>

namespace umbra::tables {

std::vector<Table> cachedOrComputed(const TableCache& cache, bool useCache, const std::vector<TableRequest>& requests,
                                    const std::function<std::vector<Table>()>& compute, CacheOutcome& outcome) {
  outcome = {};
  std::vector<Table> tables(requests.size());
  bool allHit = useCache;
  for (std::size_t i = 0; i < requests.size() && allHit; ++i) {
    const TableRequest& r = requests[i];
    if (!r.needed) continue;
    std::optional<Table> t = cache.load(r.kind, r.parameters);
    allHit = t && (r.width == 0 || t->width == r.width) && (r.height == 0 || t->height == r.height) &&
             (r.channels.empty() || t->channels == r.channels);
    if (allHit) tables[i] = std::move(*t);
  }
  if (allHit) {
    for (const TableRequest& r : requests) outcome.hits += r.needed ? 1 : 0;
    return tables;
  }
  tables = compute();
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
