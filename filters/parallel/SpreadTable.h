#pragma once
// A table whose texels are computed each on its own (the eclipse LuTs), through the cache
// and, under mpirun, over the ranks.
#include "umbra/tables/CachedTables.h"

#include <functional>

namespace umbra::filters {

/// The table of `request`: `texels` texels (u, v) in `slices` slices, the slice outermost,
/// request.channels values per texel. compute(index, count) gives the whole table with the
/// texels k (row-major within a slice) for which k % count == index filled (eclipse::
/// TexelShare); it may throw. On one rank (or `spread` false): tables::cachedOrComputed
/// with compute(0, 1). Over ranks: collective; every rank looks in the cache (found by all:
/// each reads its own; found by rank 0 alone: sent from it to every rank); on a miss every
/// rank computes its share, the values are gathered on every
/// rank, rank 0 alone stores the table; an error on any rank is thrown on every rank
/// ("rank R: message"). The result is the same to the bit as compute(0, 1).
tables::Table spreadOrCached(const tables::TableCache& cache, bool useCache, const tables::TableRequest& request,
                             int texels, int slices, bool spread,
                             const std::function<tables::Table(int index, int count)>& compute,
                             tables::CacheOutcome& outcome);

/// The tables of `requests` (each with one value per texel and channel, the channels the
/// wavelengths), through the cache and, over ranks with `spread`, made in shares of their
/// channels: compute(index, count) gives every table with the channels c for which
/// owner(c, count) == index filled (the others 0). On one rank (or `spread` false):
/// tables::cachedOrComputed with compute(0, 1). Over ranks: collective; every rank looks in
/// the cache (found by all: each reads its own; found by rank 0 alone: the needed tables sent
/// to every rank, the requests then giving their sizes and channels); on a miss
/// every rank computes its share, the values are gathered on every rank, rank 0 alone
/// stores the tables; an error on any rank is thrown on every rank.
std::vector<tables::Table> spreadChannelsOrCached(const tables::TableCache& cache, bool useCache,
                                                  const std::vector<tables::TableRequest>& requests, bool spread,
                                                  const std::function<int(int channel, int count)>& owner,
                                                  const std::function<std::vector<tables::Table>(int index, int count)>& compute,
                                                  tables::CacheOutcome& outcome);

}  // namespace umbra::filters
