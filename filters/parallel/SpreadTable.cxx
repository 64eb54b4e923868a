#include "SpreadTable.h"

#include "Ranks.hpp"

#include <optional>
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
  // The cache, read by every rank (a shared directory: nothing to send); else as rank 0 finds it.
  tables::Table table;
  std::string found;
  if (useCache)
    if (std::optional<tables::Table> t = cache.load(request.kind, request.parameters);
        t && t->width == request.width && t->height == request.height && t->channels == request.channels &&
        t->data.size() == values) {
      table = std::move(*t);
      found = "1";
    }
  if (ranks.all(found == "1")) {
    outcome.hits = 1;
    return table;
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

std::vector<tables::Table> spreadChannelsOrCached(const tables::TableCache& cache, bool useCache,
                                                  const std::vector<tables::TableRequest>& requests, bool spread,
                                                  const std::function<int(int channel, int count)>& owner,
                                                  const std::function<std::vector<tables::Table>(int index, int count)>& compute,
                                                  tables::CacheOutcome& outcome) {
  parallel::Ranks& ranks = parallel::Ranks::world();
  if (!spread || ranks.size() == 1)
    return tables::cachedOrComputed(cache, useCache, requests, [&] { return compute(0, 1); }, outcome);
  outcome = {};
  int needed = 0;
  for (const tables::TableRequest& r : requests) needed += r.needed ? 1 : 0;
  // The cache, read by every rank (a shared directory: nothing to send); else rank 0's
  // hit goes to every rank.
  std::optional<std::vector<tables::Table>> cached;
  if (useCache) cached = tables::cachedTables(cache, requests);
  if (ranks.all(cached.has_value())) {
    outcome.hits = needed;
    return std::move(*cached);
  }
  if (ranks.broadcast(cached ? "1" : "") == "1") {
    std::vector<tables::Table> out(requests.size());
    for (std::size_t i = 0; i < requests.size(); ++i) {
      if (!requests[i].needed) continue;
      tables::Table& t = out[i];
      if (ranks.root()) t = std::move((*cached)[i]);
      std::vector<float> data = ranks.allGather(ranks.root() ? t.data : std::vector<float>{});
      if (!ranks.root()) {  // (the request says the size: the cached table has it)
        t.width = requests[i].width, t.height = requests[i].height, t.channels = requests[i].channels;
        t.parameters = requests[i].parameters;
      }
      t.data = std::move(data);
    }
    outcome.hits = needed;
    return out;
  }
  // Every rank its channels; each value gathered from the rank that has it.
  std::vector<tables::Table> out;
  std::string error;
  try {
    out = compute(ranks.rank(), ranks.size());
    if (out.size() != requests.size()) throw std::logic_error("spreadChannelsOrCached: another number of tables");
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (const std::string errors = ranks.finish(error); !errors.empty()) throw std::runtime_error(errors);
  for (tables::Table& t : out) {
    const std::size_t nc = t.channels.size(), texels = nc ? t.data.size() / nc : 0;
    std::vector<float> mine;
    for (std::size_t k = 0; k < texels; ++k)
      for (std::size_t c = 0; c < nc; ++c)
        if (owner(static_cast<int>(c), ranks.size()) == ranks.rank()) mine.push_back(t.data[k * nc + c]);
    const std::vector<float> all = ranks.allGather(mine);
    std::size_t at = 0;
    for (int r = 0; r < ranks.size(); ++r)
      for (std::size_t k = 0; k < texels; ++k)
        for (std::size_t c = 0; c < nc; ++c)
          if (owner(static_cast<int>(c), ranks.size()) == r) t.data[k * nc + c] = all[at++];
  }
  outcome.computed = needed;
  if (ranks.root() && useCache)
    for (std::size_t i = 0; i < requests.size(); ++i) {
      try {
        cache.store(requests[i].kind, requests[i].parameters, out[i]);
      } catch (const std::exception& e) {
        if (outcome.warning.empty()) outcome.warning = e.what();
      }
    }
  return out;
}

}  // namespace umbra::filters
