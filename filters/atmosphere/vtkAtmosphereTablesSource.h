#pragma once
// vtkAtmosphereTablesSource: the precomputed tables of a model atmosphere (issue #3) as
// a vtkMultiBlockDataSet of vtkImageData blocks, each with its parameters in field data.
// Only the tables asked for (SetTables) are made; each is cached on disk as EXR, keyed by
// a hash of the parameters it depends on, and read back instead of recomputed on a hit.
//
// Tables so far:
//   "refraction": the deviation / contact-altitude table of the eclipse paper (Figure 6)
//     over the transmittance parametrisation: 2D, point coordinates (x_mu, x_r) with
//     texel centres on the ends of [0, 1], arrays "deviation_rad", "contact_altitude_m".
#include <vtkMultiBlockDataSetAlgorithm.h>

#include <string>

class vtkAtmosphereTablesSource : public vtkMultiBlockDataSetAlgorithm {
public:
  static vtkAtmosphereTablesSource* New();
  vtkTypeMacro(vtkAtmosphereTablesSource, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Table { Refraction = 1 << 3 };

  /// Preset name ("earth", "mars", "earth-2015-calbuco") or the path of a JSON file.
  vtkSetStdStringFromCharMacro(Atmosphere);
  vtkGetCharFromStdStringMacro(Atmosphere);
  /// Which tables to make (bitwise or of Table values; default all).
  vtkSetMacro(Tables, int);
  vtkGetMacro(Tables, int);

  vtkSetClampMacro(RefractionWidth, int, 2, 8192);
  vtkGetMacro(RefractionWidth, int);
  vtkSetClampMacro(RefractionHeight, int, 2, 8192);
  vtkGetMacro(RefractionHeight, int);
  /// RK4 step along the rays [m] (default 10 km).
  vtkSetClampMacro(RefractionStepM, double, 1.0, 1e6);
  vtkGetMacro(RefractionStepM, double);

  /// Cache directory; empty = umbra::tables::TableCache::defaultDirectory().
  vtkSetStdStringFromCharMacro(CacheDirectory);
  vtkGetCharFromStdStringMacro(CacheDirectory);
  vtkSetMacro(UseCache, bool);
  vtkGetMacro(UseCache, bool);
  vtkBooleanMacro(UseCache, bool);

  /// After an update: the tables read from the cache, computed, and the error (if any).
  int GetLastCacheHits() const { return this->CacheHits; }
  int GetLastComputed() const { return this->Computed; }
  const std::string& GetLastError() const { return this->Error; }

protected:
  vtkAtmosphereTablesSource();
  ~vtkAtmosphereTablesSource() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkAtmosphereTablesSource(const vtkAtmosphereTablesSource&) = delete;
  void operator=(const vtkAtmosphereTablesSource&) = delete;

  std::string Atmosphere = "earth";
  int Tables = Refraction;
  int RefractionWidth = 512;
  int RefractionHeight = 256;
  double RefractionStepM = 10e3;
  std::string CacheDirectory;
  bool UseCache = true;

  int CacheHits = 0;
  int Computed = 0;
  std::string Error;
};
