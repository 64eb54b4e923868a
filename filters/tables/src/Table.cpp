#include "umbra/tables/Table.h"

#include "ExrInternal.h"

#include <set>

namespace umbra::tables {

float Table::at(int x, int y, int c) const {
  const int nc = static_cast<int>(channels.size());
  if (x < 0 || x >= width || y < 0 || y >= height || c < 0 || c >= nc) {
    throw std::out_of_range("Table::at(" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                            std::to_string(c) + ") outside " + std::to_string(width) + " x " +
                            std::to_string(height) + " x " + std::to_string(nc));
  }
  const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) *
                       static_cast<size_t>(nc) +
                   static_cast<size_t>(c);
  if (i >= data.size()) throw std::out_of_range("Table::at: data is shorter than the table");
  return data[i];
}

int Table::channelIndex(const std::string& name) const {
  for (size_t i = 0; i < channels.size(); ++i) {
    if (channels[i] == name) return static_cast<int>(i);
  }
  return -1;
}

TableError::TableError(const std::string& path, const std::string& detail)
    : std::runtime_error(path + ": " + detail), path_(path) {}

namespace detail {

void validateShape(const Table& table, const std::string& path) {
  auto fail = [&](const std::string& why) { throw TableError(path, "invalid table: " + why); };
  if (table.width <= 0 || table.height <= 0) {
    fail("size " + std::to_string(table.width) + " x " + std::to_string(table.height) +
         " (width and height must be > 0)");
  }
  if (table.channels.empty()) fail("no channels");
  std::set<std::string> seen;
  for (const std::string& name : table.channels) {
    if (name.empty()) fail("empty channel name");
    if (name.find('\0') != std::string::npos) fail("channel name contains a NUL character");
    if (name.size() > 255) fail("channel name longer than 255 characters");
    if (!seen.insert(name).second) fail("duplicate channel '" + name + "'");
  }
}

}  // namespace detail

void validateTable(const Table& table, const std::string& path) {
  detail::validateShape(table, path);
  const unsigned long long expected = static_cast<unsigned long long>(table.width) *
                                      static_cast<unsigned long long>(table.height) *
                                      table.channels.size();
  if (table.data.size() != expected) {
    throw TableError(path, "invalid table: data has " + std::to_string(table.data.size()) + " values, expected " +
                               std::to_string(table.width) + " x " + std::to_string(table.height) + " x " +
                               std::to_string(table.channels.size()) + " = " + std::to_string(expected));
  }
}

}  // namespace umbra::tables
