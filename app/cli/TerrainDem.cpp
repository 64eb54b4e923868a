#include "TerrainDem.hpp"

#include "Commands.hpp"
#include "DemModule.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace umbra::cli {
namespace {

/// The GDAL reader (DemModule.hpp), loaded once: from beside the running program (`umbra`
/// in its build directory), else from where the build put it (programs elsewhere that link
/// the commands: the tests). Throws CommandError naming `path` and what went wrong.
ReadDemRaster demReader(const std::string& path) {
  static std::mutex mutex;
  static ReadDemRaster reader = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  if (reader) return reader;
  std::vector<std::string> candidates;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back((exe.parent_path() / UMBRA_DEM_MODULE_NAME).string());
  candidates.push_back(UMBRA_DEM_MODULE_PATH);
  std::string problems;
  for (const std::string& module : candidates) {
    if (!std::filesystem::exists(module, ec)) continue;
    if (void* handle = ::dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL)) {  // kept open: GDAL cleans up at exit
      if ((reader = reinterpret_cast<ReadDemRaster>(::dlsym(handle, kReadDemRasterSymbol)))) return reader;
      problems += "; " + module + ": no " + kReadDemRasterSymbol;
    } else {
      const char* why = ::dlerror();
      problems += "; " + (why ? std::string(why) : module + ": cannot be loaded");
    }
  }
  if (problems.empty()) problems = "; " + std::string(UMBRA_DEM_MODULE_NAME) + " is not beside the program nor at " + UMBRA_DEM_MODULE_PATH;
  throw CommandError(path + ": the DEM reader (GDAL) is missing" + problems);
}

} // namespace

Dem readDem(const std::string& path, double spacingM, double bodyRadiusM) {
  DemRaster raster;
  std::string error;
  if (!demReader(path)(path.c_str(), &raster, &error)) throw CommandError(error);
  Dem dem;
  dem.field.width = raster.width;
  dem.field.height = raster.height;
  dem.field.spacingM = raster.pixelSizeM.value_or(spacingM);
  dem.field.bodyRadiusM = bodyRadiusM > 0.0 ? bodyRadiusM : raster.semiMajorAxisM.value_or(terrain::kMoonRadiusM);
  dem.field.heightsM = std::move(raster.heightsM);
  dem.centreLatitudeDeg = raster.centreLatitudeDeg;
  dem.centreLongitudeDeg = raster.centreLongitudeDeg;
  dem.crs = std::move(raster.crs);
  try {
    dem.field.validate();
  } catch (const std::exception& e) {
    throw CommandError(path + ": " + e.what());
  }
  return dem;
}

} // namespace umbra::cli
