#include "SpreadTable.h"

#include "Ranks.hpp"

#include <stdexcept>
#include <string>

namespace umbra::filters {

tables::Table spreadOrCached(const tables::TableCache& cache, bool useCache, const tables::TableRequest& request,
                             int texels, int slices, bool spread,
                             const std::function<tables::Table(int index, int count)>& compute,
                             tables::CacheOutcome& outcome) {
  parallel::Ranks& ranks = parallel::Ranks::world();
  if (!spread || ranks.size() == 1)
    return tables::cachedOrComputed(cache, useCache, {request}, [&] { return std::vector<tables::Table>{compute(0, 1)}; },
                                    outcome)
        .front();
  outcome = {};
  const std::size_t nc = request.channels.size();
  const std::size_t values = static_cast<std::size_t>(texels) * slices * nc;
  // The cache, as rank 0 finds it.
  tables::Table table;
  std::string found;
  if (ranks.root() && useCache)
    if (std::optional<tables::Table> t = cache.load(request.kind, request.parameters);
        t && t->width == request.width && t->height == request.height && t->channels == request.channels &&
        t->data.size() == values) {
      table = std::move(*t);
      found = "1";
    }
  if (ranks.broadcast(found) == "1") {
    table.data = ranks.allGather(ranks.root() ? table.data : std::vector<float>{});
    if (!ranks.root()) {
      table.width = request.width, table.height = request.height, table.channels = request.channels;
      table.parameters = request.parameters;
    }
    outcome.hits = 1;
    return table;
  }
  // Every rank its share; each texel's values gathered from the rank that has them.
  std::string error;
  try {
    table = compute(ranks.rank(), ranks.size());
    if (table.data.size() != values) throw std::logic_error("spreadOrCached: the table computed has another size");
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (const std::string errors = ranks.finish(error); !errors.empty()) throw std::runtime_error(errors);
  std::vector<float> mine;
  for (int d = 0; d < slices; ++d)
    for (int k = ranks.rank(); k < texels; k += ranks.size()) {
      const float* v = table.data.data() + (static_cast<std::size_t>(d) * texels + k) * nc;
      mine.insert(mine.end(), v, v + nc);
    }
  const std::vector<float> all = ranks.allGather(mine);
  std::size_t at = 0;
  for (int r = 0; r < ranks.size(); ++r)
    for (int d = 0; d < slices; ++d)
      for (int k = r; k < texels; k += ranks.size()) {
        float* v = table.data.data() + (static_cast<std::size_t>(d) * texels + k) * nc;
        for (std::size_t q = 0; q < nc; ++q) v[q] = all[at++];
      }
  outcome.computed = 1;
  if (ranks.root() && useCache) {
    try {
      cache.store(request.kind, request.parameters, table);
    } catch (const std::exception& e) {
      outcome.warning = e.what();
    }
  }
  return table;
}

}  // namespace umbra::filters
