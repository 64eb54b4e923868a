#pragma once
// What the `precompute shadow` and `profile shadow` commands share: choosing the
// occluder and building (or loading from the cache) its shadow LuT.
#include "Commands.hpp"
#include "AtmosphereModel.hpp"
#include "ShadowLut.hpp"
#include "scene/Units.hpp"
#include "scene/ReceiverShadow.hpp"

#include <vtkSmartPointer.h>

#include <string>

class vtkEclipseAtmosphereSource;
class vtkEclipseShadowLutSource;
class vtkImageData;
class vtkTable;

namespace umbra::cli {

struct OccluderChoice {
  std::string name;             ///< canonical preset name
  double radiusM = 0.0;
  double sunDistanceM = 0.0;    ///< mean distance from the Sun (a moon: its planet's)
  bool hasAtmosphere = false;
};

/// The preset called `name`; throws CommandError listing the known bodies otherwise, or
/// when it is the Sun. `radius` / `sunDistance` (length strings, may be empty) override.
OccluderChoice chooseOccluder(const std::string& name, const std::string& radius, const std::string& sunDistance);

/// The shadow that the camera's target of a scene file is in (at --time, if not empty);
/// throws naming the file when there is none.
struct SceneShadow {
  OccluderChoice occluder;
  scene::ReceiverShadow geometry;
  int lutSize = 256;  ///< the scene's shadow.lutSize
};
SceneShadow sceneShadow(const std::string& scenePath, const std::string& time);

/// Parse a length option ("384400km"); throws CommandError naming the option.
double lengthOption(const std::string& option, const std::string& text);
/// lengthOption within [minM, maxM]; otherwise CommandError "<option>: expected a length
/// from <min> to <max>, got <text>" (the physical limits: radii 1 m..1e12 m, distances up
/// to 1e15 m, a hundred times Neptune's).
double lengthOption(const std::string& option, const std::string& text, double minM, double maxM);
/// --observer LAT,LON[,ALT]: an observer on the Earth (geodetic degrees north and east, an
/// altitude with units, a bare number in metres); throws CommandError naming the option.
scene::Observer parseObserver(const std::string& text);

using scene::kMaxDistanceM;
using scene::kMaxRadiusM;

/// --distance-range MIN:MAX ("9000km:9800km"): the LuT's ranges for receivers at those
/// distances from the occluder's centre (eclipse::lutRangeForDistances; `darkUmbra` for an
/// airless occluder). Throws CommandError naming the option.
eclipse::LutRange distanceRangeOption(const std::string& text, const OccluderChoice& occluder, bool darkUmbra,
                                      int size);
/// `--distance-range` on a command (help text shared by precompute shadow / eclipse).
void addDistanceRangeOption(CLI::App* command, std::string& text);

/// The occluder's atmosphere for the eclipse tables: --atmosphere PRESET|FILE, the limb
/// views' size and the precomputation's (--draft-tables: small tables for quick looks).
struct EclipseAtmosphereChoice {
  std::string atmosphere;  ///< empty: airless
  int limbSize = 256;
  int scatteringCells = 16;  ///< of the shadow LuT's limb views (the limb-luminance LuT keeps 32)
  int orders = 4;
  bool draftTables = false;
  int scatteringNu = 0;  ///< cells in nu (view-sun cosine) of the scattering tables; 0: the tables' default
  /// A cloud deck on the limb for the directly computed profiles (eclipse::screenByClouds);
  /// not an option of every command: cover 0, none.
  double cloudTopM = 0.0, cloudCover = 0.0;
  void addTo(CLI::App* command);
  /// The model `atmosphere` names, read once (a CommandError naming --atmosphere); null
  /// for none.
  atmosphere::AtmosphereModelPtr model() const;
  /// Checks the atmosphere file (one-line error) and returns its bottom radius [m].
  double bottomRadiusM() const;
  mutable atmosphere::AtmosphereModelPtr read;  ///< what model() read
  void configure(vtkEclipseAtmosphereSource* source, const OccluderChoice& occluder) const;
};

/// Update an eclipse-table source with progress on stderr, cache reporting, and a
/// CommandError when it fails.
void updateEclipseSource(vtkEclipseAtmosphereSource* source, const std::string& what, const CacheOptions& cache);

/// Build the LuT through the filter, with progress on stderr and cache reporting. The
/// occluder, if given, is recorded in the LuT's parameters (an airless LuT's values do
/// not depend on it). With an atmosphere (not empty), the atmospheric LuT; with `range`,
/// a scene-limited LuT over those ranges, `width` columns (0: size).
vtkSmartPointer<vtkEclipseShadowLutSource> updateShadowLut(int size, double limbDarkening, const CacheOptions& cache,
                                                           const OccluderChoice* occluder = nullptr,
                                                           const EclipseAtmosphereChoice* atmosphere = nullptr,
                                                           const eclipse::LutRange* range = nullptr, int width = 0);

/// The shadow's cross-section through an atmosphere computed directly at every sample
/// (no LuT; limb views of atmosphere.limbSize rows): the columns of vtkShadowProfileFilter.
/// maxOffsetM 0: 1.25 x the penumbra's radius.
vtkSmartPointer<vtkTable> atmosphericProfile(const EclipseAtmosphereChoice& atmosphere, const OccluderChoice& occluder,
                                             double distanceM, double maxOffsetM, int samples, double limbDarkening);
/// The same cross-section as samples (offset, R G B, luminance).
std::vector<eclipse::ProfileSample> atmosphericProfileSamples(const EclipseAtmosphereChoice& atmosphere,
                                                              const OccluderChoice& occluder, double distanceM,
                                                              double maxOffsetM, int samples, double limbDarkening);

/// `umbra precompute eclipse` (PrecomputeCommand.cpp).
void addPrecomputeEclipseCommand(CLI::App& precompute, Action& action);

/// A shadow LuT written by `umbra precompute shadow`; throws naming the file if it is not one.
vtkSmartPointer<vtkImageData> readShadowLut(const std::string& path);

} // namespace umbra::cli
