// EXR tables and shadow LuTs (filters/tables/src/Exr.cpp, filters/shadow/ShadowLutData):
// any file gives a table or a TableError, and a table a LuT or an error naming the file.
#include "ShadowLutData.h"
#include "umbra/tables/Exr.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("umbra-fuzz-" + std::to_string(::getpid()) + ".exr")).string();
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  umbra::tables::Table table;
  try {
    table = umbra::tables::readExr(path);
  } catch (const umbra::tables::TableError&) {
    return 0;
  }
  try {
    umbra::filters::fromTable(table, path);
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  }
  return 0;
}
