#pragma once
// Between `umbra` and its GDAL DEM reader (TerrainDemGdal.cpp), a module that TerrainDem.cpp
// loads the first time a command reads a DEM. GDAL and the hundred-odd libraries it needs
// take about 33 MiB of memory and a quarter of a second to load; linked into `umbra`, every
// command would pay that, most of them for nothing.
// Both sides are built together by this project, so the types are plain C++ (same compiler,
// same standard library); no exception crosses the boundary.
#include <optional>
#include <string>
#include <vector>

namespace umbra::cli {

/// A DEM's band 1 as the reader found it.
struct DemRaster {
  int width = 0, height = 0;
  std::vector<double> heightsM;                  ///< row-major (j * width + i), +j up the raster; NaN = no data
  std::optional<double> pixelSizeM;              ///< from the geotransform, in metres
  std::optional<double> semiMajorAxisM;          ///< the CRS's
  std::optional<double> centreLatitudeDeg, centreLongitudeDeg;
  std::string crs;                               ///< a short description
};

/// Reads `path` into `out`; false with `error` set to "<path>: <reason>" when it cannot.
using ReadDemRaster = bool (*)(const char* path, DemRaster* out, std::string* error);
inline constexpr const char* kReadDemRasterSymbol = "umbra_read_dem_raster";

} // namespace umbra::cli
