#include "TerrainDem.hpp"

#include "Commands.hpp"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <limits>
#include <memory>

namespace umbra::cli {
namespace {

struct QuietGdal {
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); }
  ~QuietGdal() { CPLPopErrorHandler(); }
};

std::string lastGdalError() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(" (") + m + ")" : std::string();
}

} // namespace

Dem readDem(const std::string& path, double spacingM, double bodyRadiusM) {
  QuietGdal quiet;
  GDALAllRegister();
  std::unique_ptr<void, void (*)(void*)> dataset(GDALOpen(path.c_str(), GA_ReadOnly),
                                                 [](void* d) { if (d) GDALClose(d); });
  if (!dataset) throw CommandError(path + ": cannot read as a raster" + lastGdalError());
  GDALDatasetH ds = dataset.get();
  const int width = GDALGetRasterXSize(ds), height = GDALGetRasterYSize(ds);
  if (GDALGetRasterCount(ds) < 1) throw CommandError(path + ": no raster band");
  if (width < 2 || height < 2) throw CommandError(path + ": needs at least 2 x 2 samples");
  if (double(width) * height > 8192.0 * 8192.0) throw CommandError(path + ": larger than 8192 x 8192 samples");

  Dem dem;
  dem.field.width = width;
  dem.field.height = height;
  dem.field.spacingM = spacingM;
  dem.field.bodyRadiusM = bodyRadiusM > 0.0 ? bodyRadiusM : terrain::kMoonRadiusM;

  double gt[6];
  const bool hasTransform = GDALGetGeoTransform(ds, gt) == CE_None && !(gt[1] == 1.0 && gt[5] == 1.0 && gt[0] == 0.0);
  bool northUp = true;
  if (hasTransform) {
    if (gt[2] != 0.0 || gt[4] != 0.0) throw CommandError(path + ": rotated rasters are not supported");
    if (std::abs(std::abs(gt[1]) - std::abs(gt[5])) > 1e-6 * std::abs(gt[1]))
      throw CommandError(path + ": pixels are not square (" + std::to_string(gt[1]) + " x " + std::to_string(gt[5]) + ")");
    northUp = gt[5] < 0.0;
    double toMetres = 1.0;
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    if (srs) {
      if (OSRIsGeographic(srs))
        throw CommandError(path + ": geographic (latitude/longitude) rasters are not supported; reproject to a "
                                  "projected CRS in metres (e.g. gdalwarp to polar stereographic)");
      if (OSRIsProjected(srs)) toMetres = OSRGetLinearUnits(srs, nullptr);
      OGRErr err = OGRERR_NONE;
      const double a = OSRGetSemiMajor(srs, &err);
      if (bodyRadiusM <= 0.0 && err == OGRERR_NONE && a > 0.0) dem.field.bodyRadiusM = a;
      const char* name = OSRGetName(srs);
      dem.crs = name ? name : "projected";
      // The centre's latitude / longitude in the CRS's own geographic system.
      OGRSpatialReferenceH geo = OSRCloneGeogCS(srs);
      if (geo) {
        OSRSetAxisMappingStrategy(geo, OAMS_TRADITIONAL_GIS_ORDER);
        OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(srs, geo);
        if (ct) {
          double x = gt[0] + 0.5 * width * gt[1], y = gt[3] + 0.5 * height * gt[5], z = 0.0;
          if (OCTTransform(ct, 1, &x, &y, &z)) dem.centreLongitudeDeg = x, dem.centreLatitudeDeg = y;
          OCTDestroyCoordinateTransformation(ct);
        }
        OSRDestroySpatialReference(geo);
      }
    }
    dem.field.spacingM = std::abs(gt[1]) * toMetres;
  }

  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  std::vector<double> rows(static_cast<std::size_t>(width) * height);
  if (GDALRasterIO(band, GF_Read, 0, 0, width, height, rows.data(), width, height, GDT_Float64, 0, 0) != CE_None)
    throw CommandError(path + ": cannot read the heights" + lastGdalError());
  int hasNoData = 0;
  const double noData = GDALGetRasterNoDataValue(band, &hasNoData);
  int hasScale = 0, hasOffset = 0;
  const double scale = GDALGetRasterScale(band, &hasScale), offset = GDALGetRasterOffset(band, &hasOffset);
  dem.field.heightsM.resize(rows.size());
  for (int r = 0; r < height; ++r)
    for (int i = 0; i < width; ++i) {
      double h = rows[static_cast<std::size_t>(r) * width + i];
      if ((hasNoData && (h == noData || (std::isnan(noData) && std::isnan(h)))) || !std::isfinite(h))
        h = std::numeric_limits<double>::quiet_NaN();
      else
        h = h * (hasScale ? scale : 1.0) + (hasOffset ? offset : 0.0);
      const int j = northUp ? height - 1 - r : r;
      dem.field.heightsM[static_cast<std::size_t>(j) * width + i] = h;
    }
  try {
    dem.field.validate();
  } catch (const std::exception& e) {
    throw CommandError(path + ": " + e.what());
  }
  return dem;
}

} // namespace umbra::cli
