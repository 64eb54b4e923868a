#pragma once
// Reading and writing tables as OpenEXR files (FLOAT channels, ZIP compression up to
// kUncompressedAboveBytes, parameters as "umbra:<key>" string attributes in the header).

#include <string>
#include <vector>

#include "umbra/tables/Table.h"

namespace umbra::tables {

// Tables of more values than this [bytes of float] are written without compression: ZIP
// packs the precomputed tables' floats by only 10-20 %, and was a sixth of the CPU time of a
// 15-wavelength atmosphere precomputation (docs/accuracy-vs-speed/atmosphere-tables.md, "Wavelengths computed
// together").
inline constexpr unsigned long long kUncompressedAboveBytes = 4ull << 20;

// Prefix of the header attributes that hold Table::parameters.
inline constexpr const char* kParameterPrefix = "umbra:";
// Header attribute (string vector) recording the table's channel order; OpenEXR itself
// stores channels sorted by name.
inline constexpr const char* kChannelOrderAttribute = "umbraChannelOrder";

// Validates the table, writes it to "<path>.tmp-<pid>-<random>" in the same directory and
// renames that over path. Throws TableError naming path on any failure; never leaves a
// partial file at path nor a temporary behind.
void writeExr(const std::string& path, const Table& table);

// Reads a table. With requiredChannels empty, reads every channel in the stored order;
// otherwise exactly those channels, in that order. Throws TableError (one line, starting
// with path) for a missing / unreadable file, a file that is not OpenEXR, a truncated or
// corrupt file, a missing channel or a channel that is not FLOAT, a table of more than
// 2^28 values or 65536 a side, and a header promising more values than the file's size
// could hold (before allocating them). Non-finite values are returned as they are.
Table readExr(const std::string& path, const std::vector<std::string>& requiredChannels = {});

}  // namespace umbra::tables
