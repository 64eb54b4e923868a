#include "umbra/tables/Summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace umbra::tables {
namespace {

std::string number(double v) {
  if (std::isnan(v)) return "n/a";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// Parameter values may hold anything; keep the text output one entry per line.
std::string escaped(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '\n') {
      out += "\\n";
    } else if (ch == '\r') {
      out += "\\r";
    } else if (ch == '\t') {
      out += "\\t";
    } else {
      out += ch;
    }
  }
  return out;
}

nlohmann::json numberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

TableSummary summarize(const Table& table, const std::string& path) {
  validateTable(table, path);
  TableSummary summary;
  summary.path = path;
  summary.width = table.width;
  summary.height = table.height;
  summary.parameters = table.parameters;
  const size_t nc = table.channels.size();
  const size_t pixels = static_cast<size_t>(table.width) * static_cast<size_t>(table.height);
  for (size_t c = 0; c < nc; ++c) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    double sum = 0.0, compensation = 0.0;  // Kahan summation
    long long finite = 0, nonFinite = 0;
    for (size_t p = 0; p < pixels; ++p) {
      const double v = table.data[p * nc + c];
      if (!std::isfinite(v)) {
        ++nonFinite;
        continue;
      }
      ++finite;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      const double y = v - compensation;
      const double t = sum + y;
      compensation = (t - sum) - y;
      sum = t;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ChannelStats stats{table.channels[c], nan, nan, nan, nonFinite};
    if (finite > 0) {
      stats.min = lo;
      stats.max = hi;
      stats.mean = sum / static_cast<double>(finite);
    }
    summary.channels.push_back(stats);
  }
  return summary;
}

std::string formatText(const TableSummary& s) {
  std::string out = s.path + "\n";
  out += "  size: " + std::to_string(s.width) + " x " + std::to_string(s.height) + ", " +
         std::to_string(s.channels.size()) +
         (s.channels.size() == 1 ? " channel\n" : " channels\n");
  for (const ChannelStats& c : s.channels) {
    out += "  " + c.name + ": ";
    if (std::isnan(c.min)) {
      out += "no finite values";
    } else {
      out += "min " + number(c.min) + "  max " + number(c.max) + "  mean " + number(c.mean);
    }
    out += "  non-finite " + std::to_string(c.nonFinite) + "\n";
  }
  if (s.parameters.empty()) {
    out += "  parameters: none\n";
  } else {
    out += "  parameters:\n";
    for (const auto& [key, value] : s.parameters) {
      out += "    " + escaped(key) + " = " + escaped(value) + "\n";
    }
  }
  return out;
}

nlohmann::json toJson(const TableSummary& s) {
  nlohmann::json channels = nlohmann::json::array();
  for (const ChannelStats& c : s.channels) {
    channels.push_back({{"name", c.name},
                        {"min", numberOrNull(c.min)},
                        {"max", numberOrNull(c.max)},
                        {"mean", numberOrNull(c.mean)},
                        {"nonFinite", c.nonFinite}});
  }
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& [key, value] : s.parameters) parameters[key] = value;
  return {{"path", s.path},
          {"width", s.width},
          {"height", s.height},
          {"channels", channels},
          {"parameters", parameters}};
}

}  // namespace umbra::tables
