#pragma once
// Internal to umbra_tables.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "umbra/tables/Table.h"

namespace umbra::tables::detail {

// writeExr with the header parameters given separately (table.parameters is ignored), so
// that TableCache::store need not copy the table.
void writeExr(const std::string& path, const Table& table,
              const std::map<std::string, std::string>& parameters);

// The rows of a table as they are written: rows(y0, n) points at rows [y0, y0 + n) of every
// channel, interleaved per pixel (Table::data's layout), valid until the next call.
using RowSource = std::function<const float*(int y0, int n)>;

// writeExr of a table of width x height x channels given a block of rows at a time (at
// most rowsPerBlock, in order): the bytes are those writeExr writes for the same values.
void writeExrRows(const std::string& path, const Table& shape, const std::map<std::string, std::string>& parameters,
                  int rowsPerBlock, const RowSource& rows);

// What validateTable checks but the values: the size, the channels' names.
void validateShape(const Table& table, const std::string& path);

// A copy of the file `from` at path, through a temporary beside path and a rename; throws
// TableError naming the file that failed.
void copyFile(const std::string& from, const std::string& path);

// text written to path through a temporary beside it and a rename (never half a file);
// throws TableError naming path.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace umbra::tables::detail
