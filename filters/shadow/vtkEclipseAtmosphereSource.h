#pragma once
// vtkEclipseAtmosphereSource: what the eclipse tables of an occluder with an atmosphere
// share (vtkEclipseShadowLutSource, vtkLimbLuminanceSource): the bodies, the atmosphere
// (preset name or JSON file; empty = airless) and the options of its precomputation
// (umbra::eclipse::EclipseAtmosphereOptions), the cache settings. The prepared atmosphere
// (Bruneton tables, the refraction table's top rows, limb ray profile) is made once per
// process for a given set of parameters and shared by the sources that ask for it.
//
// Input (optional, port 0): the tables of vtkAtmosphereTablesSource (a vtkMultiBlockDataSet,
// e.g. read from its EXR cache) instead of preparing them here. It needs the Bruneton
// tables, with Refraction on (the default) of refracted paths: SetRefractedPaths(true);
// its "refraction" block is read when present (SetTables(All)), else the two rows of it
// that the limb ray profile reads are traced here (RefractionSize, the input's step). The
// table sizes, orders and refraction step are then the input's (its field data feed the cache
// key); the atmosphere is the Atmosphere property, or when empty the input's "atmosphere"
// (a preset name), and must be the one the tables were made for. No input and no
// Atmosphere: the airless case.
#include "AtmosphereModel.hpp"
#include "ShadowLut.hpp"
#include "TableSizes.hpp"

#include <vtkImageAlgorithm.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace umbra::eclipse {
struct AtmosphericShadowModel;
struct EclipseAtmosphere;
struct EclipseAtmosphereOptions;
}

class vtkMultiBlockDataSet;

class vtkEclipseAtmosphereSource : public vtkImageAlgorithm {
public:
  vtkTypeMacro(vtkEclipseAtmosphereSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The bodies, passed on in field data [m]. With an atmosphere the occluder's radius is
  /// the atmosphere's bottom radius.
  vtkSetStdStringFromCharMacro(OccluderName);
  vtkGetCharFromStdStringMacro(OccluderName);
  vtkSetMacro(OccluderRadiusM, double);
  vtkGetMacro(OccluderRadiusM, double);
  vtkSetMacro(SunRadiusM, double);
  vtkGetMacro(SunRadiusM, double);
  vtkSetMacro(SunOccluderDistanceM, double);
  vtkGetMacro(SunOccluderDistanceM, double);

  /// Preset name ("earth", "mars", "earth-2015-calbuco") or JSON file; empty (default):
  /// none. Read on the next update (once while it stays the same).
  vtkSetStdStringFromCharMacro(Atmosphere);
  vtkGetCharFromStdStringMacro(Atmosphere);
  /// The atmosphere as a value, read where the user named it: Atmosphere becomes its name
  /// (null: none). The tables source ConnectAtmosphereTables makes gets it too.
  void SetAtmosphereModel(umbra::atmosphere::AtmosphereModelPtr model);
  /// Bruneton tables: orders, wavelengths (3 = 680, 550, 440 nm), sizes.
  vtkSetClampMacro(Orders, int, 1, umbra::atmosphere::kMaxOrders);
  vtkGetMacro(Orders, int);
  vtkSetClampMacro(Wavelengths, int, 1, umbra::atmosphere::kMaxWavelengths);
  vtkGetMacro(Wavelengths, int);
  vtkSetVector2Macro(TransmittanceSize, int);
  vtkGetVector2Macro(TransmittanceSize, int);
  /// R, MU, MU_S, NU; NU = 0 (the default): eclipse::defaultScatteringNu(occluder, 8).
  vtkSetVector4Macro(ScatteringSize, int);
  vtkGetVector4Macro(ScatteringSize, int);
  vtkSetVector2Macro(IrradianceSize, int);
  vtkGetVector2Macro(IrradianceSize, int);
  /// Refraction (default on): the deviation / contact table and refracted paths.
  vtkSetMacro(Refraction, bool);
  vtkGetMacro(Refraction, bool);
  vtkBooleanMacro(Refraction, bool);
  vtkSetVector2Macro(RefractionSize, int);
  vtkGetVector2Macro(RefractionSize, int);
  vtkSetClampMacro(RefractionStepM, double, 1.0, 1e6);
  vtkGetMacro(RefractionStepM, double);
  /// Mean terrain elevation [m] for the contact attenuation; < 0 (default): the body's.
  vtkSetMacro(TerrainMeanElevationM, double);
  vtkGetMacro(TerrainMeanElevationM, double);

  /// The u and v ranges (Eq. 4) the width and height cover (default 0, 1: all of it).
  /// Narrower ones, e.g. umbra::eclipse::lutRangeForDistances of the receivers' distances,
  /// give full resolution there; outside them the edge texels are read (both LuTs:
  /// vtkEclipseShadowLutSource, vtkLimbLuminanceSource). Recorded in the
  /// field data and the cache key (uMin, uMax, vMin, vMax), read back downstream.
  vtkSetVector2Macro(URange, double);
  vtkGetVector2Macro(URange, double);
  vtkSetVector2Macro(VRange, double);
  vtkGetVector2Macro(VRange, double);
  /// Fraction of the rows for v in [0, VRange[0]] (default 0; eclipse::ShadowLut).
  vtkSetMacro(VLowFraction, double);
  vtkGetMacro(VLowFraction, double);
  /// All of the above from umbra::eclipse::lutRangeForDistances.
  void SetLutRange(const umbra::eclipse::LutRange& r) {
    this->SetURange(r.uMin, r.uMax);
    this->SetVRange(r.vMin, r.vMax);
    this->SetVLowFraction(r.vLowFraction);
  }
  umbra::eclipse::LutRange GetLutRange() const {
    return {this->URange[0], this->URange[1], this->VRange[0], this->VRange[1], this->VLowFraction};
  }

  vtkSetStdStringFromCharMacro(CacheDirectory);
  vtkGetCharFromStdStringMacro(CacheDirectory);
  vtkSetMacro(UseCache, bool);
  vtkGetMacro(UseCache, bool);
  vtkBooleanMacro(UseCache, bool);

  /// Under mpirun: the LuT's texels shared by the ranks, gathered on every rank, stored by
  /// rank 0 (filters::spreadOrCached; every rank must update the source). Off by default:
  /// an animation's ranks each make their own frames' tables. Run directly: no change.
  vtkSetMacro(SpreadOverRanks, bool);
  vtkGetMacro(SpreadOverRanks, bool);
  vtkBooleanMacro(SpreadOverRanks, bool);

  /// The prepared atmosphere (tables, deviation table, the shadow model), made now if
  /// needed, with progress events; for computations outside the tables, e.g. a profile
  /// computed directly. Throws on a bad atmosphere or options.
  std::shared_ptr<const umbra::eclipse::EclipseAtmosphere> GetPreparedAtmosphere();

  /// Feeds the input from a new vtkAtmosphereTablesSource asking for the tables these
  /// properties describe (atmosphere, wavelengths, sizes, orders, refracted paths, cache):
  /// the Bruneton tables then come from their EXR cache across runs; made on
  /// demand, their progress is the first half of this source's ProgressEvents. A later
  /// call re-configures that tables source from the properties. Does nothing without an
  /// Atmosphere or when another input is connected. Returns the tables source (or null).
  vtkAlgorithm* ConnectAtmosphereTables();

  /// After an update: whether the table came from the cache, and the cache file's path.
  bool GetLastUpdateWasCacheHit() const { return this->LastCacheHit; }
  const std::string& GetCachePath() const { return this->CachePath; }
  /// After an update: a cache store that failed (the table is still produced), or empty.
  const std::string& GetCacheWarning() const { return this->CacheWarning; }
  /// After an update: whether it was aborted (SetAbortExecute, e.g. from a progress
  /// observer; a cancel of the input's precomputation). A cancel is not an error: the
  /// output is empty and nothing is printed; the next update computes it.
  bool GetLastUpdateAborted() const { return this->LastAborted; }
  /// After an update that failed: why (the exception's message, one line), else empty.
  const std::string& GetLastError() const { return this->LastError; }

protected:
  vtkEclipseAtmosphereSource();
  ~vtkEclipseAtmosphereSource() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override { return 1; }
  bool HasAtmosphere() const;
  umbra::eclipse::EclipseAtmosphereOptions Options() const;
  /// The atmosphere tables on the input port, or null.
  vtkMultiBlockDataSet* InputTables() const;
  /// The parameters of the prepared atmosphere (loads the atmosphere file; throws its error).
  std::map<std::string, std::string> AtmosphereParameters() const;
  /// Prepared once per process and parameters; progress goes to this algorithm (from
  /// `from` to `to`); throws on errors and when aborted.
  std::shared_ptr<const umbra::eclipse::EclipseAtmosphere> PrepareAtmosphere(double from, double to);
  /// An RGB table of `kind` and `width` x `height` texels (`slices` slices stacked along
  /// the height): read from the cache when there, else `compute` runs with the prepared
  /// model (this limb darkening; its progress from 0.5 to 1, empty result = aborted; the
  /// texels of the share, all of them unless SpreadOverRanks) and the result is stored.
  /// Sets the cache status.
  using Compute = std::function<std::vector<float>(
      const umbra::eclipse::AtmosphericShadowModel&, const umbra::eclipse::Progress&, const umbra::eclipse::TexelShare&)>;
  std::vector<float> CachedOrComputed(const char* kind, const std::map<std::string, std::string>& parameters,
                                      int width, int height, int slices, double limbDarkening, const Compute& compute);
  /// What RequestData returns when it caught `e`: after an abort (GetAbortExecute, or
  /// atmosphere::PrecomputeCancelled) 1 with `output` emptied and LastAborted set (the
  /// executive would print a failure); else the error is reported (vtkErrorMacro) and 0.
  /// RequestData clears LastAborted and LastError first; RequestFailed keeps the message.
  int RequestFailed(const std::exception& e, vtkDataObject* output);

  /// Whole extent, spacing and origin of a LuT with texel centres at
  /// uMin + (uMax - uMin)(i + 0.5) / width, vMin + (vMax - vMin)(j + 0.5) / height and
  /// `depth` slices.
  /// A split v axis (vLowFraction > 0) has y = the texture coordinate (j + 0.5) / height.
  static void SetLutInformation(vtkInformationVector* out, int width, int height, int depth,
                                const double uRange[2] = nullptr, const double vRange[2] = nullptr,
                                double vLowFraction = 0.0);
  /// The spacing and origin that SetLutInformation gives (for RequestData to set on its output).
  static void LutSpacingOrigin(int width, int height, const double uRange[2], const double vRange[2],
                               double vLowFraction, double spacing[3], double origin[3]);

  std::string OccluderName;
  double OccluderRadiusM = 6371.0084e3;
  double SunRadiusM = umbra::eclipse::kSunRadiusM;
  double SunOccluderDistanceM = 149597870700.0;
  std::string Atmosphere;
  mutable umbra::atmosphere::AtmosphereModelPtr Model;  // the one Atmosphere names, once read
  int Orders = umbra::atmosphere::kDefaultTableSizes.orders;
  int Wavelengths = 3;
  int TransmittanceSize[2] = {umbra::atmosphere::kDefaultTableSizes.transmittance[0],
                              umbra::atmosphere::kDefaultTableSizes.transmittance[1]};
  // NU 0: the occluder's (eclipse::defaultScatteringNu).
  int ScatteringSize[4] = {umbra::atmosphere::kDefaultTableSizes.scattering[0], umbra::atmosphere::kDefaultTableSizes.scattering[1],
                           umbra::atmosphere::kDefaultTableSizes.scattering[2], 0};
  int IrradianceSize[2] = {umbra::atmosphere::kDefaultTableSizes.irradiance[0],
                           umbra::atmosphere::kDefaultTableSizes.irradiance[1]};
  bool Refraction = true;
  int RefractionSize[2] = {umbra::atmosphere::kDefaultTableSizes.refraction[0],
                           umbra::atmosphere::kDefaultTableSizes.refraction[1]};
  double RefractionStepM = 10e3;
  double TerrainMeanElevationM = -1.0;
  std::string CacheDirectory;
  bool UseCache = true;
  bool SpreadOverRanks = false;
  double URange[2] = {0.0, 1.0};
  double VRange[2] = {0.0, 1.0};
  double VLowFraction = 0.0;

  vtkSmartPointer<vtkAlgorithm> TablesSource;
  unsigned long TablesProgressObserver = 0;  ///< on TablesSource: TablesProgress
  void TablesProgress(vtkObject*, unsigned long, void* fraction);
  /// The atmosphere this source prepared last (keeps it shared while the source lives).
  std::shared_ptr<const umbra::eclipse::EclipseAtmosphere> Prepared;
  bool LastCacheHit = false;
  bool LastAborted = false;
  std::string LastError;
  std::string CachePath;
  std::string CacheWarning;

private:
  vtkEclipseAtmosphereSource(const vtkEclipseAtmosphereSource&) = delete;
  void operator=(const vtkEclipseAtmosphereSource&) = delete;
};
