#pragma once
// Per-channel statistics of a table, for `umbra inspect`.

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "umbra/tables/Table.h"

namespace umbra::tables {

struct ChannelStats {
  std::string name;
  double min, max, mean;  // over finite values only; NaN when none is finite
  long long nonFinite;    // count of NaN and +-inf values
};

struct TableSummary {
  std::string path;
  int width, height;
  std::vector<ChannelStats> channels;
  std::map<std::string, std::string> parameters;
};

// Throws TableError if the table is invalid (see validateTable).
TableSummary summarize(const Table& table, const std::string& path);
// A few human-readable lines, ending with a newline.
std::string formatText(const TableSummary& summary);
// {"path","width","height","channels":[{name,min,max,mean,nonFinite}],"parameters":{...}};
// NaN statistics are written as null.
nlohmann::json toJson(const TableSummary& summary);

}  // namespace umbra::tables
