#pragma once
// The Lorenz-Mie optics of the atmospheres a program loads, kept in its table cache:
// JSON entries mie-optics-<hash>.json beside the tables, under the same size cap, read back
// to the bit by the next run (atmosphere/MieCache.hpp keeps them in memory meanwhile).
#include <string>

namespace umbra::filters {

/// From now on, the Lorenz-Mie optics are read from and written to the table cache in
/// `directory` (empty: tables::TableCache::defaultDirectory()); `enabled` false: in memory
/// only (--no-cache). A cache that cannot be written is passed over silently: the optics
/// are computed again next time.
void keepMieOpticsInCache(const std::string& directory, bool enabled = true);

}  // namespace umbra::filters
