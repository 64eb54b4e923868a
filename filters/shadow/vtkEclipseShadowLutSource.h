#pragma once
// vtkEclipseShadowLutSource: the eclipse-shadow lookup table (eclipse paper, Eq. 3-4) as a
// 2D vtkImageData of I / I_sun (float RGB point scalars "I_over_Isun"), point coordinates
// (u, v) at texel centres, the defining parameters in field data. Built by
// umbra::eclipse::buildAirlessShadowLut, cached on disk as EXR keyed by a parameter hash.
//
// The bodies (Sun and occluder) are carried into the output's field data for the filters
// downstream; they do not change the airless table's values and are not part of its key.
#include "SolarDisc.hpp"

#include <vtkImageAlgorithm.h>

#include <string>

class vtkEclipseShadowLutSource : public vtkImageAlgorithm {
public:
  static vtkEclipseShadowLutSource* New();
  vtkTypeMacro(vtkEclipseShadowLutSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Texels along u and v (default 256 x 256).
  vtkSetClampMacro(Width, int, 2, 16384);
  vtkGetMacro(Width, int);
  vtkSetClampMacro(Height, int, 2, 16384);
  vtkGetMacro(Height, int);
  /// Linear limb-darkening coefficient u of Eq. 1 (default 0.6).
  vtkSetClampMacro(LimbDarkening, double, 0.0, 1.0);
  vtkGetMacro(LimbDarkening, double);
  /// Relative tolerance of the per-texel quadrature (default 1e-10).
  vtkSetClampMacro(RelativeTolerance, double, 1e-15, 1e-2);
  vtkGetMacro(RelativeTolerance, double);

  /// The bodies, passed on in field data [m].
  vtkSetStdStringFromCharMacro(OccluderName);
  vtkGetCharFromStdStringMacro(OccluderName);
  vtkSetMacro(OccluderRadiusM, double);
  vtkGetMacro(OccluderRadiusM, double);
  vtkSetMacro(SunRadiusM, double);
  vtkGetMacro(SunRadiusM, double);
  vtkSetMacro(SunOccluderDistanceM, double);
  vtkGetMacro(SunOccluderDistanceM, double);

  /// Cache directory; empty (default) = umbra::tables::TableCache::defaultDirectory().
  vtkSetStdStringFromCharMacro(CacheDirectory);
  vtkGetCharFromStdStringMacro(CacheDirectory);
  /// Read and write the cache (default on).
  vtkSetMacro(UseCache, bool);
  vtkGetMacro(UseCache, bool);
  vtkBooleanMacro(UseCache, bool);

  /// After an update: whether the table came from the cache, and the cache file's path.
  bool GetLastUpdateWasCacheHit() const { return this->LastCacheHit; }
  const std::string& GetCachePath() const { return this->CachePath; }
  /// After an update: a cache store that failed (the table is still produced), or empty.
  const std::string& GetCacheWarning() const { return this->CacheWarning; }

protected:
  vtkEclipseShadowLutSource();
  ~vtkEclipseShadowLutSource() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkEclipseShadowLutSource(const vtkEclipseShadowLutSource&) = delete;
  void operator=(const vtkEclipseShadowLutSource&) = delete;

  int Width = 256;
  int Height = 256;
  double LimbDarkening = 0.6;
  double RelativeTolerance = 1e-10;
  std::string OccluderName;
  double OccluderRadiusM = 6371.0084e3;
  double SunRadiusM = umbra::eclipse::kSunRadiusM;
  double SunOccluderDistanceM = 149597870700.0;
  std::string CacheDirectory;
  bool UseCache = true;

  bool LastCacheHit = false;
  std::string CachePath;
  std::string CacheWarning;
};
