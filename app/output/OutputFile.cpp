#include "OutputFile.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>

namespace fs = std::filesystem;

namespace umbra::output {

std::string extensionOf(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void checkWritable(const std::string& path, std::initializer_list<const char*> extensions) {
  if (path.empty()) throw std::runtime_error("output path is empty");
  if (extensions.size() > 0) {
    const std::string ext = extensionOf(path);
    std::string list;
    bool ok = false;
    for (const char* e : extensions) {
      ok = ok || ext == e;
      list += (list.empty() ? "" : ", ") + std::string(e);
    }
    if (!ok) throw std::runtime_error(path + ": unsupported file type (expected " + list + ")");
  }
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw std::runtime_error(path + ": is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw std::runtime_error(path + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(path + ": cannot write to directory " + dir.string() + ": " + std::strerror(errno));
}

OutputFile::OutputFile(std::string path) : target(std::move(path)) {
  std::random_device rd;
  const fs::path p(this->target);
  // keep the extension last: writers (VTK's PNG writer, OpenEXR) do not care, people do
  this->temp = (p.parent_path() / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                                   std::to_string(rd() % 1000000) + p.extension().string()))
                   .string();
}

OutputFile::~OutputFile() {
  if (!this->committed) {
    std::error_code ec;
    fs::remove(this->temp, ec);
  }
}

void OutputFile::commit() {
  std::error_code ec;
  if (!fs::exists(this->temp, ec)) throw std::runtime_error(this->target + ": nothing was written");
  fs::rename(this->temp, this->target, ec);
  if (ec) throw std::runtime_error(this->target + ": cannot write: " + ec.message());
  this->committed = true;
}

} // namespace umbra::output
