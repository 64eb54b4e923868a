#pragma once
// Internal to umbra_tables.

#include <map>
#include <string>

#include "umbra/tables/Table.h"

namespace umbra::tables::detail {

// writeExr with the header parameters given separately (table.parameters is ignored), so
// that TableCache::store need not copy the table.
void writeExr(const std::string& path, const Table& table,
              const std::map<std::string, std::string>& parameters);

// text written to path through a temporary beside it and a rename (never half a file);
// throws TableError naming path.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace umbra::tables::detail
