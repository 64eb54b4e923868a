// The GDAL DEM reader, a module of its own (DemModule.hpp): band 1 of any raster GDAL reads,
// checked for what TerrainDem.hpp requires (projected, not rotated, square pixels).
#include "DemModule.hpp"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>

namespace {

using umbra::cli::DemRaster;

struct QuietGdal {
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); }
  ~QuietGdal() { CPLPopErrorHandler(); }
};

std::string lastGdalError() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(" (") + m + ")" : std::string();
}

/// The CRS's name, semi-major axis and the raster centre's latitude and longitude.
void readCrs(OGRSpatialReferenceH srs, const double gt[6], DemRaster& out) {
  OGRErr err = OGRERR_NONE;
  const double a = OSRGetSemiMajor(srs, &err);
  if (err == OGRERR_NONE && a > 0.0) out.semiMajorAxisM = a;
  const char* name = OSRGetName(srs);
  out.crs = name ? name : "projected";
  OGRSpatialReferenceH geo = OSRCloneGeogCS(srs);
  if (!geo) return;
  OSRSetAxisMappingStrategy(geo, OAMS_TRADITIONAL_GIS_ORDER);
  OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
  if (OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(srs, geo)) {
    double x = gt[0] + 0.5 * out.width * gt[1], y = gt[3] + 0.5 * out.height * gt[5], z = 0.0;
    if (OCTTransform(ct, 1, &x, &y, &z)) out.centreLongitudeDeg = x, out.centreLatitudeDeg = y;
    OCTDestroyCoordinateTransformation(ct);
  }
  OSRDestroySpatialReference(geo);
}

void read(const std::string& path, DemRaster& out) {
  QuietGdal quiet;
  GDALAllRegister();
  std::unique_ptr<void, void (*)(void*)> dataset(GDALOpen(path.c_str(), GA_ReadOnly),
                                                 [](void* d) { if (d) GDALClose(d); });
  if (!dataset) throw std::runtime_error(path + ": cannot read as a raster" + lastGdalError());
  GDALDatasetH ds = dataset.get();
  const int width = GDALGetRasterXSize(ds), height = GDALGetRasterYSize(ds);
  if (GDALGetRasterCount(ds) < 1) throw std::runtime_error(path + ": no raster band");
  if (width < 2 || height < 2) throw std::runtime_error(path + ": needs at least 2 x 2 samples");
  if (double(width) * height > 8192.0 * 8192.0) throw std::runtime_error(path + ": larger than 8192 x 8192 samples");
  out.width = width, out.height = height;

  double gt[6];
  const bool hasTransform = GDALGetGeoTransform(ds, gt) == CE_None && !(gt[1] == 1.0 && gt[5] == 1.0 && gt[0] == 0.0);
  bool northUp = true;
  if (hasTransform) {
    if (gt[2] != 0.0 || gt[4] != 0.0) throw std::runtime_error(path + ": rotated rasters are not supported");
    if (std::abs(std::abs(gt[1]) - std::abs(gt[5])) > 1e-6 * std::abs(gt[1]))
      throw std::runtime_error(path + ": pixels are not square (" + std::to_string(gt[1]) + " x " +
                               std::to_string(gt[5]) + ")");
    northUp = gt[5] < 0.0;
    double toMetres = 1.0;
    if (OGRSpatialReferenceH srs = GDALGetSpatialRef(ds)) {
      if (OSRIsGeographic(srs))
        throw std::runtime_error(path + ": geographic (latitude/longitude) rasters are not supported; reproject to a "
                                        "projected CRS in metres (e.g. gdalwarp to polar stereographic)");
      if (OSRIsProjected(srs)) toMetres = OSRGetLinearUnits(srs, nullptr);
      readCrs(srs, gt, out);
    }
    out.pixelSizeM = std::abs(gt[1]) * toMetres;
  }

  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  std::vector<double> rows(static_cast<std::size_t>(width) * height);
  if (GDALRasterIO(band, GF_Read, 0, 0, width, height, rows.data(), width, height, GDT_Float64, 0, 0) != CE_None)
    throw std::runtime_error(path + ": cannot read the heights" + lastGdalError());
  int hasNoData = 0;
  const double noData = GDALGetRasterNoDataValue(band, &hasNoData);
  int hasScale = 0, hasOffset = 0;
  const double scale = GDALGetRasterScale(band, &hasScale), offset = GDALGetRasterOffset(band, &hasOffset);
  out.heightsM.resize(rows.size());
  for (int r = 0; r < height; ++r)
    for (int i = 0; i < width; ++i) {
      double h = rows[static_cast<std::size_t>(r) * width + i];
      if ((hasNoData && (h == noData || (std::isnan(noData) && std::isnan(h)))) || !std::isfinite(h))
        h = std::numeric_limits<double>::quiet_NaN();
      else
        h = h * (hasScale ? scale : 1.0) + (hasOffset ? offset : 0.0);
      const int j = northUp ? height - 1 - r : r;
      out.heightsM[static_cast<std::size_t>(j) * width + i] = h;
    }
}

} // namespace

extern "C" __attribute__((visibility("default"))) bool umbra_read_dem_raster(const char* path, DemRaster* out,
                                                                            std::string* error) noexcept {
  try {
    *out = DemRaster();
    read(path, *out);
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
  } catch (...) {
    *error = std::string(path) + ": cannot read as a raster";
  }
  return false;
}
