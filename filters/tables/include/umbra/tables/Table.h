#pragma once
// A precomputed table: a 2D float image with named channels and string parameters.

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace umbra::tables {

struct Table {
  int width = 0, height = 0;  // depth (3D tables) may come later
  std::vector<std::string> channels;  // e.g. {"R","G","B"}
  std::vector<float> data;  // interleaved per pixel, row-major, row y=0 first
  std::map<std::string, std::string> parameters;  // stored in the EXR header

  // Value of channel c at pixel (x, y). Throws std::out_of_range for bad indices.
  float at(int x, int y, int c) const;
  // Index of a channel by name, or -1.
  int channelIndex(const std::string& name) const;
};

// Every error about a table file. what() always starts with "<path>: ".
class TableError : public std::runtime_error {
public:
  TableError(const std::string& path, const std::string& detail);
  const std::string& path() const noexcept { return path_; }

private:
  std::string path_;
};

// Throws TableError("<path>: invalid table: ...") unless width/height > 0, channels are
// non-empty and unique, and data.size() == width * height * channels.size().
void validateTable(const Table& table, const std::string& path);

// FNV-1a 64-bit over the sorted "key=value\n" lines, as 16 lowercase hex digits.
std::string parameterHash(const std::map<std::string, std::string>& parameters);

}  // namespace umbra::tables
