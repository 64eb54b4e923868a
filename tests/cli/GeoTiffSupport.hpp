#pragma once
// Writing a height field as a GeoTIFF in the CLI tests (needs GDAL).
#include "HeightField.hpp"

#include <gdal.h>
#include <ogr_srs_api.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace umbra::test {

/// A north-up GeoTIFF of the field in lunar south polar stereographic coordinates, 30 m
/// pixels, centred `eastM` from the pole; `noData` cells (if any) are written as -32768.
inline void writeGeoTiff(const std::string& path, const terrain::HeightField& f, double eastM,
                         const std::vector<int>& noData = {},
                         const char* proj = "+proj=stere +lat_0=-90 +lon_0=0 +k=1 +x_0=0 +y_0=0 +R=1737400 +units=m +no_defs") {
  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  GDALDatasetH ds = GDALCreate(driver, path.c_str(), f.width, f.height, 1, GDT_Float64, nullptr);
  const double half = 0.5 * f.width * f.spacingM;
  double gt[6] = {eastM - half, f.spacingM, 0.0, half, 0.0, -f.spacingM};
  GDALSetGeoTransform(ds, gt);
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromProj4(srs, proj);
  GDALSetSpatialRef(ds, srs);
  OSRDestroySpatialReference(srs);
  std::vector<double> rows(f.heightsM.size());
  for (int r = 0; r < f.height; ++r)
    for (int i = 0; i < f.width; ++i) rows[r * f.width + i] = f.at(i, f.height - 1 - r);
  for (int k : noData) rows[k] = -32768.0;
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  if (!noData.empty()) GDALSetRasterNoDataValue(band, -32768.0);
  EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, f.width, f.height, rows.data(), f.width, f.height, GDT_Float64, 0, 0),
            CE_None);
  GDALClose(ds);
}

} // namespace umbra::test
