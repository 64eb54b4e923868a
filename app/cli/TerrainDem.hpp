#pragma once
// Reading a DEM for `umbra terrain`: GeoTIFF (or any raster GDAL reads), band 1, heights
// in metres above the body's sphere. The raster must be in a projected CRS in metres with
// square pixels and no rotation (e.g. the polar stereographic LOLA products); it is taken
// as the gnomonic tangent grid of terrain::HeightField, centred on the raster's centre,
// with the pixel size as the spacing. The two projections differ in scale by about
// c^2 / 4 at a central angle c from their centres (2e-4 at 50 km, 8e-4 at 100 km on the
// Moon): lengths across a 100 km DEM are good to ~0.1 %.
// Rows are turned so that +j points up the raster (north for a north-up DEM).
#include "HeightField.hpp"

#include <optional>
#include <string>

namespace umbra::cli {

struct Dem {
  terrain::HeightField field;
  std::optional<double> centreLatitudeDeg, centreLongitudeDeg;  ///< when georeferenced
  std::string crs;  ///< a short description
};

/// Throws CommandError("<path>: ...") for a file GDAL cannot read, a geographic or rotated
/// raster, non-square pixels. `spacingM` is used when the raster has no geotransform;
/// `bodyRadiusM` (> 0) overrides the CRS's semi-major axis (the Moon's if it has none).
Dem readDem(const std::string& path, double spacingM, double bodyRadiusM);

} // namespace umbra::cli
