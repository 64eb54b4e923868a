#include "umbra/tables/PlanarTableFile.h"

#include "umbra/tables/Table.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <stdexcept>
#include <system_error>

namespace umbra::tables {
namespace {

std::string errorText(int err) { return std::error_code(err, std::generic_category()).message(); }

}  // namespace

PlanarTableFile::PlanarTableFile(const std::string& directory, int width, int height, std::vector<std::string> channels)
    : directory_(directory), width_(width), height_(height), channels_(std::move(channels)) {
  if (width_ <= 0 || height_ <= 0 || channels_.empty())
    throw TableError(directory, "a table of " + std::to_string(width_) + " x " + std::to_string(height_) + " x " +
                                    std::to_string(channels_.size()) + " values");
#ifdef O_TMPFILE
  fd_ = ::open(directory.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
#endif
  if (fd_ < 0) {  // no O_TMPFILE here: a named file, unlinked at once
    std::string name = directory + "/.planes-XXXXXX";
    fd_ = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd_ >= 0) ::unlink(name.c_str());
  }
  if (fd_ < 0) throw TableError(directory, "cannot make a temporary file: " + errorText(errno));
}

PlanarTableFile::~PlanarTableFile() {
  if (fd_ >= 0) ::close(fd_);
}

void PlanarTableFile::put(int first, int count, const float* values) {
  const int nc = static_cast<int>(channels_.size());
  if (first < 0 || count < 1 || first + count > nc)
    throw std::out_of_range("PlanarTableFile::put: channels " + std::to_string(first) + " to " +
                            std::to_string(first + count - 1) + " of " + std::to_string(nc));
  const std::size_t n = static_cast<std::size_t>(width_) * height_;
  std::vector<float> plane(n);
  for (int k = 0; k < count; ++k) {
    for (std::size_t i = 0; i < n; ++i) plane[i] = values[i * static_cast<std::size_t>(count) + k];
    const auto* bytes = reinterpret_cast<const char*>(plane.data());
    const std::size_t total = n * sizeof(float);
    const off_t at = static_cast<off_t>(static_cast<std::uint64_t>(first + k) * total);
    for (std::size_t done = 0; done < total;) {
      const ssize_t w = ::pwrite(fd_, bytes + done, total - done, at + static_cast<off_t>(done));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) throw TableError(directory_, "cannot write a temporary file: " + errorText(w < 0 ? errno : EIO));
      done += static_cast<std::size_t>(w);
    }
  }
}

void PlanarTableFile::rows(int y0, int rows, std::vector<float>& out) const {
  const std::size_t nc = channels_.size(), n = static_cast<std::size_t>(width_) * rows;
  const std::size_t plane = static_cast<std::size_t>(width_) * height_ * sizeof(float);
  out.assign(n * nc, 0.0f);
  std::vector<float> line(n);
  for (std::size_t c = 0; c < nc; ++c) {
    auto* bytes = reinterpret_cast<char*>(line.data());
    const std::size_t total = n * sizeof(float);
    const off_t at = static_cast<off_t>(c * plane + static_cast<std::size_t>(y0) * width_ * sizeof(float));
    std::size_t done = 0;
    while (done < total) {
      const ssize_t r = ::pread(fd_, bytes + done, total - done, at + static_cast<off_t>(done));
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw TableError(directory_, "cannot read a temporary file: " + errorText(errno));
      if (r == 0) break;  // a channel never put: a hole past the end reads as zeros
      done += static_cast<std::size_t>(r);
    }
    std::fill(bytes + done, bytes + total, 0);
    for (std::size_t i = 0; i < n; ++i) out[i * nc + c] = line[i];
  }
}

}  // namespace umbra::tables
