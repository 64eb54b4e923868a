#pragma once
// vtkAtmosphereTablesSource: the precomputed tables of a model atmosphere as
// a vtkMultiBlockDataSet of vtkImageData blocks, each with its parameters in field data
// (umbra::filters::fieldParameters; "kind" names the table). Only the tables asked for
// (SetTables) are made; each is cached on disk as one EXR file, keyed by a hash of the
// parameters it depends on, and read back instead of recomputed on a hit.
//
// Tables (block names in quotes, in this order; cache kinds "atmosphere-<block name>"):
//   Transmittance       "transmittance": T(r, mu) to the top, 2D (x_mu, x_r).
//   SingleScattering    "single-scattering-<component>": one 3D block per scattering
//                       component (without its phase function).
//   MultipleScattering  "multiple-scattering": orders 2..N, phases included, 3D.
//   Irradiance          "direct-irradiance" (E_0) and "irradiance" (indirect, orders
//                       1..N-1), 2D (x_mu_s, x_r).
//   Refraction          "refraction": the deviation / contact-altitude table of the eclipse
//     paper (Figure 6) over the transmittance parametrisation: 2D, arrays "deviation_rad",
//     "contact_altitude_m" (keyed by refractionParameters only: aerosols do not change it).
// Default: the four Bruneton tables (Bruneton); the refraction table only when asked for.
// RefractedPaths (the precomputation along refracted rays) does not add the refraction
// table by itself; the `umbra atmosphere precompute --refraction` command asks for both.
//
// The Bruneton tables (atmosphere/Precompute.hpp, per unit solar irradiance) come from one
// precompute() call: when every requested one is in the cache they are read, otherwise the
// precomputation runs once and every Bruneton table it made is stored. When Transmittance
// is the only Bruneton table asked for, scattering is not computed (the precomputation
// runs with 2x4x2x2 scattering and 2x2 irradiance tables, one order, and only the
// transmittance table, which does not depend on them, is kept and stored). Their cache key
// is atmosphereParameters(atm) plus every option that changes values (sizes, orders,
// samples, refracted paths and step, muSMin, sun radius) and the table's own "layout" /
// "depth" entries.
//
// Progress: ProgressEvent through the precomputation; SetAbortExecute(1) (from any
// thread, e.g. a GUI's cancel button while Update runs in a worker) stops it at the next
// chunk: the output is empty, GetLastError() says "precomputation cancelled", nothing is
// printed; call Modified() (and clear the flag) before updating again.
//
// Arrays: one float array per wavelength, named "L<nm>nm" (e.g. "L680nm"; a fractional
// wavelength writes '.' as 'p': "L393p57nm" — formatNumber digits), the same names as the
// EXR channels; parameter "wavelengthsNm" lists the exact values. Wavelengths: 3 = the
// R, G, B mode (680, 550, 440 nm, in that order), else WavelengthSet::uniform(N).
// The tables are computed in double precision and stored (EXR and arrays) as float.
//
// Geometry: 2D blocks have point coordinates over the unit ranges, texel centres on the
// ends of [0, 1] (Bruneton's convention): spacing 1/(n-1). 3D blocks (scattering) have
// dimensions (NU * MU_S) x MU x R, origin 0 and spacing 1 (texel indices): x = nu index *
// MU_S + mu_s index, y = mu (the lower half for rays that hit the ground), z = r.
// In EXR a 3D table is stored as 2D: width NU * MU_S, height MU * R, the MU rows of each
// R slice stacked (row y + MU * z, like Bruneton's 3D textures); parameters "layout",
// "depth" (= R), "scatteringSize" (R,MU,MU_S,NU) describe it.
#include <vtkMultiBlockDataSetAlgorithm.h>

#include "AtmosphereModel.hpp"
#include "Precompute.hpp"  // PrecomputeOptions (defaults)

#include <string>

class vtkMultiBlockDataSet;
namespace umbra::tables {
class TableCache;
struct CacheOutcome;
}

class vtkAtmosphereTablesSource : public vtkMultiBlockDataSetAlgorithm {
public:
  static vtkAtmosphereTablesSource* New();
  vtkTypeMacro(vtkAtmosphereTablesSource, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Table {
    Transmittance = 1 << 0,
    SingleScattering = 1 << 1,
    MultipleScattering = 1 << 2,
    Refraction = 1 << 3,
    Irradiance = 1 << 4,  ///< direct and indirect: two blocks
    Bruneton = Transmittance | SingleScattering | MultipleScattering | Irradiance,
    All = Bruneton | Refraction
  };

  /// Preset name ("earth", "mars", "earth-2015-calbuco") or the path of a JSON file, read
  /// on the next update (once while it stays the same).
  vtkSetStdStringFromCharMacro(Atmosphere);
  vtkGetCharFromStdStringMacro(Atmosphere);
  /// The atmosphere as a value, read where the user named it: Atmosphere becomes its name.
  void SetAtmosphereModel(umbra::atmosphere::AtmosphereModelPtr model);
  /// The model Atmosphere names (read now if it is not yet; throws AtmosphereError).
  umbra::atmosphere::AtmosphereModelPtr GetAtmosphereModel() const;
  /// Which tables to make (bitwise or of Table values; default Bruneton).
  vtkSetMacro(Tables, int);
  vtkGetMacro(Tables, int);

  // ---- the Bruneton tables (PrecomputeOptions) ----
  /// Scattering orders (1: single only; default 4).
  vtkSetClampMacro(Orders, int, 1, umbra::atmosphere::kMaxOrders);
  vtkGetMacro(Orders, int);
  /// Number of wavelengths: 3 = 680, 550, 440 nm; else WavelengthSet::uniform(N) (default 3).
  vtkSetClampMacro(Wavelengths, int, 1, umbra::atmosphere::kMaxWavelengths);
  vtkGetMacro(Wavelengths, int);
  vtkSetVector2Macro(TransmittanceSize, int);  ///< x_mu x x_r (default: kDefaultTableSizes)
  vtkGetVector2Macro(TransmittanceSize, int);
  vtkSetVector4Macro(ScatteringSize, int);     ///< R, MU, MU_S, NU (default: kDefaultTableSizes)
  vtkGetVector4Macro(ScatteringSize, int);
  vtkSetVector2Macro(IrradianceSize, int);     ///< x_mu_s x x_r (default: kDefaultTableSizes)
  vtkGetVector2Macro(IrradianceSize, int);
  /// The lowest Sun the scattering tables hold, as the cosine of its zenith angle
  /// (PrecomputeOptions::muSMin; default cos 102 deg, in [-1, 0]): air that sees the Sun
  /// lower is dark in them. Lower for a twilight sky (pipeline::configureAtmosphereTables).
  vtkSetClampMacro(MuSMin, double, -1.0, 0.0);
  vtkGetMacro(MuSMin, double);
  /// At least this many polar directions in the scattering density's quadrature
  /// (PrecomputeOptions::sphereSamples, times twice as many azimuths), or more where the
  /// phase functions need more (densityDirectionsFor); 0 (default): what they need.
  vtkSetClampMacro(MinimumDensityDirections, int, 0, 256);
  vtkGetMacro(MinimumDensityDirections, int);
  /// Exactly this many polar directions in the scattering density's quadrature, fewer than
  /// the phase functions need if so asked (a quick sky); 0 (default): as
  /// MinimumDensityDirections says.
  vtkSetClampMacro(DensityDirections, int, 0, 256);
  vtkGetMacro(DensityDirections, int);
  /// Intervals of the single- and multiple-scattering view rays and directions of the
  /// indirect irradiance (PrecomputeOptions::singleScatteringSamples,
  /// multipleScatteringSamples, irradianceSamples; default 50, 50, 32).
  vtkSetVector3Macro(QuadratureSamples, int);
  vtkGetVector3Macro(QuadratureSamples, int);
  /// Integrate along refracted rays (PrecomputeOptions::refraction, step RefractionStepM).
  vtkSetMacro(RefractedPaths, bool);
  vtkGetMacro(RefractedPaths, bool);
  vtkBooleanMacro(RefractedPaths, bool);
  /// OpenMP threads (0: the default); does not change the values.
  vtkSetClampMacro(Threads, int, 0, 1024);
  vtkGetMacro(Threads, int);
  /// Wavelengths computed together (PrecomputeOptions::wavelengthBatch; 0, the default: all):
  /// fewer hold less memory (the orders' working tables are that many channels wide) and
  /// take more time (the work common to the wavelengths is redone per batch). The tables
  /// are the same to the bit, so it is not part of the cache key.
  vtkSetClampMacro(WavelengthBatch, int, 0, umbra::atmosphere::kMaxWavelengths);
  vtkGetMacro(WavelengthBatch, int);
  /// With FileBacked: the 4D tables but J_k through a temporary file in $TMPDIR, a few r
  /// slices of each in memory at a time (PrecomputeOptions::spillTables): a batch's tables
  /// take less than half the memory, for a little more time. The same tables to the bit;
  /// not in the cache key. Off by default.
  vtkSetMacro(SpillTables, bool);
  vtkGetMacro(SpillTables, bool);
  /// Under mpirun: the Bruneton tables' wavelength batches shared by the ranks (batch b of
  /// rank b mod N; a batch of ceil(wavelengths / N) unless WavelengthBatch says); every
  /// rank must update the source. In arrays, the channels are gathered on every rank and
  /// the tables stored by rank 0 (filters::spreadChannelsOrCached). With FileBacked, each
  /// rank's batches are sent to rank 0 alone, which writes the files: no rank holds a whole
  /// 4D table, and the blocks are of use on rank 0 only. The same tables to the bit; not in
  /// the cache key. Off by default. Run directly: no change.
  vtkSetMacro(SpreadOverRanks, bool);
  vtkGetMacro(SpreadOverRanks, bool);

  /// The Bruneton tables as files, not arrays: each block holds its size and parameters
  /// but no values, and its parameter "file" names its EXR file in ScratchDirectory (named
  /// as umbra::tables::TableCache names it there). A precomputation writes each batch of
  /// wavelengths (WavelengthBatch) to the files as it is made, so that no table is held
  /// for every wavelength at once: the memory of one batch, for writing tables out (umbra
  /// atmosphere precompute). With the cache, tables are read from it one at a time and
  /// copied to ScratchDirectory, and computed ones copied into it. Off by default.
  vtkSetMacro(FileBacked, bool);
  vtkGetMacro(FileBacked, bool);
  /// Where FileBacked puts the files (an existing directory; required with FileBacked).
  vtkSetStdStringFromCharMacro(ScratchDirectory);
  vtkGetCharFromStdStringMacro(ScratchDirectory);

  // ---- the refraction table ----
  vtkSetClampMacro(RefractionWidth, int, 2, umbra::atmosphere::kMaxTableSide);
  vtkGetMacro(RefractionWidth, int);
  vtkSetClampMacro(RefractionHeight, int, 2, umbra::atmosphere::kMaxTableSide);
  vtkGetMacro(RefractionHeight, int);
  /// RK4 step along the rays [m] (default 10 km); also the step of the refracted paths.
  vtkSetClampMacro(RefractionStepM, double, 1.0, 1e6);
  vtkGetMacro(RefractionStepM, double);

  /// Cache directory; empty = umbra::tables::TableCache::defaultDirectory().
  vtkSetStdStringFromCharMacro(CacheDirectory);
  vtkGetCharFromStdStringMacro(CacheDirectory);
  vtkSetMacro(UseCache, bool);
  vtkGetMacro(UseCache, bool);
  vtkBooleanMacro(UseCache, bool);

  /// After an update: the tables (blocks) read from the cache, computed, and the error (if any).
  int GetLastCacheHits() const { return this->CacheHits; }
  int GetLastComputed() const { return this->Computed; }
  /// Number of precompute() calls made by the last update (0 or 1).
  int GetLastPrecomputeCalls() const { return this->PrecomputeCalls; }
  const std::string& GetLastError() const { return this->Error; }
  /// Why the tables computed by the last update could not be stored (a read-only cache):
  /// not an error, they are given all the same; empty when they were.
  const std::string& GetLastCacheWarning() const { return this->CacheWarning; }

protected:
  vtkAtmosphereTablesSource();
  ~vtkAtmosphereTablesSource() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkAtmosphereTablesSource(const vtkAtmosphereTablesSource&) = delete;
  void operator=(const vtkAtmosphereTablesSource&) = delete;

  /// The precomputation's options from the knobs, for `atm` (its density directions),
  /// validated (std::invalid_argument otherwise).
  umbra::atmosphere::PrecomputeOptions PrecomputeOptionsFor(const umbra::atmosphere::Atmosphere& atm) const;
  /// The Bruneton tables of Tables, from `cache` or computed together, as blocks of
  /// `output` from `block` on.
  void AddBrunetonBlocks(const umbra::atmosphere::Atmosphere& atm, const umbra::tables::TableCache& cache,
                         vtkMultiBlockDataSet* output, unsigned& block);
  /// The refraction table, the same way.
  void AddRefractionBlock(const umbra::atmosphere::Atmosphere& atm, const umbra::tables::TableCache& cache,
                          vtkMultiBlockDataSet* output, unsigned& block);
  void Count(const umbra::tables::CacheOutcome& outcome);

  std::string Atmosphere = "earth";
  mutable umbra::atmosphere::AtmosphereModelPtr Model;  // the one Atmosphere names, once read
  int Tables = Bruneton;
  int Orders = umbra::atmosphere::kDefaultTableSizes.orders;
  int Wavelengths = 3;
  int TransmittanceSize[2] = {umbra::atmosphere::kDefaultTableSizes.transmittance[0],
                              umbra::atmosphere::kDefaultTableSizes.transmittance[1]};
  int ScatteringSize[4] = {umbra::atmosphere::kDefaultTableSizes.scattering[0], umbra::atmosphere::kDefaultTableSizes.scattering[1],
                           umbra::atmosphere::kDefaultTableSizes.scattering[2], umbra::atmosphere::kDefaultTableSizes.scattering[3]};
  int IrradianceSize[2] = {umbra::atmosphere::kDefaultTableSizes.irradiance[0],
                           umbra::atmosphere::kDefaultTableSizes.irradiance[1]};
  double MuSMin = umbra::atmosphere::PrecomputeOptions().muSMin;
  int MinimumDensityDirections = 0;
  int DensityDirections = 0;
  int QuadratureSamples[3] = {umbra::atmosphere::PrecomputeOptions().singleScatteringSamples,
                              umbra::atmosphere::PrecomputeOptions().multipleScatteringSamples,
                              umbra::atmosphere::PrecomputeOptions().irradianceSamples};
  bool RefractedPaths = false;
  int Threads = 0;
  int WavelengthBatch = 0;
  bool SpillTables = false;
  bool SpreadOverRanks = false;
  bool FileBacked = false;
  std::string ScratchDirectory;
  int RefractionWidth = umbra::atmosphere::kDefaultTableSizes.refraction[0];
  int RefractionHeight = umbra::atmosphere::kDefaultTableSizes.refraction[1];
  double RefractionStepM = 10e3;
  std::string CacheDirectory;
  bool UseCache = true;

  int CacheHits = 0;
  int Computed = 0;
  int PrecomputeCalls = 0;
  std::string Error;
  std::string CacheWarning;
};
