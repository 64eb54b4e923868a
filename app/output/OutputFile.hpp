#pragma once
// Output files that never exist half-written: write to a temporary name beside the
// target, then rename over it. Also the early check that an output path can be written,
// so that a long computation does not end in "cannot write".
#include <initializer_list>
#include <string>

namespace umbra::output {

/// Throws std::runtime_error("<path>: ...") unless `path` names a file in an existing,
/// writable directory and is not itself a directory. If `extensions` is non-empty
/// (e.g. {".png", ".exr"}), the path must end with one of them (case-insensitive).
void checkWritable(const std::string& path, std::initializer_list<const char*> extensions = {});

/// Lowercase extension with the dot (".png"), or "".
std::string extensionOf(const std::string& path);

/// A temporary file beside `path`; commit() renames it over `path`; the destructor
/// removes it if commit() was not reached.
class OutputFile {
public:
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& tempPath() const { return this->temp; }
  const std::string& path() const { return this->target; }
  /// Rename the temporary over the target; throws std::runtime_error naming the path.
  void commit();

private:
  std::string target;
  std::string temp;
  bool committed = false;
};

} // namespace umbra::output
