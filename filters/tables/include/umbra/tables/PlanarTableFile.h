#pragma once
// A table made a few channels at a time (a batch of wavelengths), held until it is whole in
// an unlinked temporary file, channel by channel: its memory is never the whole table's.
// It is then written out row block by row block (TableCache::store, writeExr), the channels
// of each block put side by side as an EXR file holds them.

#include <string>
#include <vector>

namespace umbra::tables {

class PlanarTableFile {
public:
  /// The table's file in `directory` (which must exist), unlinked at once (O_TMPFILE where
  /// the file system has it): a killed process leaves nothing. Throws TableError naming the
  /// directory.
  PlanarTableFile(const std::string& directory, int width, int height, std::vector<std::string> channels);
  ~PlanarTableFile();
  PlanarTableFile(const PlanarTableFile&) = delete;
  PlanarTableFile& operator=(const PlanarTableFile&) = delete;

  /// Channels [first, first + count) of every pixel, from values interleaved per pixel
  /// (values[pixel * count + k] is channel first + k, pixels row by row). Throws TableError
  /// when the file cannot be written (a full disc), std::out_of_range for bad channels.
  void put(int first, int count, const float* values);

  /// Rows [y0, y0 + rows) with every channel, interleaved per pixel as Table::data holds
  /// them, into out. Channels never put read as 0.
  void rows(int y0, int rows, std::vector<float>& out) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::string>& channels() const { return channels_; }

private:
  std::string directory_;
  int width_, height_;
  std::vector<std::string> channels_;
  int fd_ = -1;
};

}  // namespace umbra::tables
