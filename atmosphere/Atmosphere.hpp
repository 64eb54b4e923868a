#pragma once
// The atmosphere parameter model: a spherical shell with a list of components (molecules,
// aerosols, absorbers), each a density profile with per-wavelength scattering and
// absorption coefficients and phase functions (Costa et al., sections 4.1-4.3), plus the
// refractive index that the refraction code bends rays with (eclipse paper, section 4.1:
// n - 1 follows the molecular density). Loaded from JSON presets or files, validated on
// load; the format is docs/atmosphere-format.md.
#include "Components.hpp"
#include "Phase.hpp"
#include "Profiles.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace umbra::atmosphere {

/// A file that cannot be used, in one line: "<file>: <field path>: expected ..., got ...".
/// The radii an atmosphere may have (bottomRadiusM, topRadiusM): from 1 m to 1e12 m (seven
/// times the Sun's), the top at least 1 m above the bottom. Outside them the tables' texture
/// coordinates overflow or lose every digit.
inline constexpr double kMinRadiusM = 1.0;
inline constexpr double kMaxRadiusM = 1.0e12;
/// The top of a "boundary-layer" density when the file names no boundaryLayerHeightM:
/// OPAC's mixing layer (Hess, Koepke & Schult 1998) for continental and maritime air.
inline constexpr double kDefaultBoundaryLayerHeightM = 2000.0;

class AtmosphereError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct Atmosphere {
  std::string name;
  std::string source;  ///< the file it came from
  double bottomRadiusM = 0.0;
  double topRadiusM = 0.0;
  std::vector<double> wavelengthsNm;
  std::vector<Component> components;
  std::vector<double> groundAlbedo;  ///< per wavelength, in [0, 1]

  /// n - 1 at the bottom (altitude 0) for refractivityReferenceWavelengthNm.
  double seaLevelRefractivity = 0.0;
  /// Why the refractivity profile traps rays round the body (ducting: n falls faster than
  /// 1/r somewhere), or empty. validate() includes it.
  std::string ductingProblem() const;
  double refractivityReferenceWavelengthNm = 550.0;
  Dispersion dispersion = Dispersion::None;
  /// The component whose relative density n - 1 follows (empty: constant with altitude).
  std::string refractivityFollows = "molecules";

  /// n - 1 = seaLevelRefractivity * D(lambda) / D(lambda_ref) * rho(h), with D the
  /// dispersion formula (Components.hpp) and rho the followed component's relative density.
  double refractivity(double altitudeM, double wavelengthNm) const;

  /// Sums over the components at an altitude, one value per wavelength [1/m].
  std::vector<double> scatteringPerM(double altitudeM) const;
  std::vector<double> absorptionPerM(double altitudeM) const;
  std::vector<double> extinctionPerM(double altitudeM) const;

  /// Vertical optical depth between two altitudes, per wavelength (exact: each component's
  /// extinction times its profile's closed-form integral).
  std::vector<double> verticalOpticalDepth(double fromAltitudeM, double toAltitudeM) const;
  /// Same for one component.
  std::vector<double> verticalOpticalDepth(const Component& component, double fromAltitudeM,
                                           double toAltitudeM) const;

  double thicknessM() const { return topRadiusM - bottomRadiusM; }
  const Component* find(const std::string& componentName) const;  ///< nullptr if absent
  const Component& component(const std::string& componentName) const;  ///< throws if absent

  /// Empty when consistent (radii, sizes per wavelength, finite coefficients >= 0).
  std::string validate() const;
};

/// The shipped presets (file names in UMBRA_ATMOSPHERE_PRESET_DIR without ".json"), sorted.
std::vector<std::string> presetNames();
/// Where the presets are: $UMBRA_ATMOSPHERE_PRESET_DIR if set, else the source folder.
std::string presetDirectory();

/// `presetNameOrPath` is a preset name ("earth", "mars", "earth-2015-calbuco") or the
/// path of a JSON file (anything with a '/' or ending in ".json"). The coefficients are
/// evaluated at `wavelengthsNm`. Throws AtmosphereError with a one-line message.
Atmosphere loadAtmosphere(const std::string& presetNameOrPath, const std::vector<double>& wavelengthsNm);

/// The same from JSON text; `sourceName` is what messages call the file, `baseDirectory`
/// is where a relative "extends" path is looked for.
Atmosphere parseAtmosphere(const std::string& jsonText, const std::string& sourceName,
                           const std::vector<double>& wavelengthsNm, const std::string& baseDirectory = ".");

/// The JSON document of a preset or file with its "extends" resolved (comments dropped),
/// as text: what an editor shows and writes back. Throws AtmosphereError like loadAtmosphere
/// (it does not check the fields: loadAtmosphere and parseAtmosphere do).
std::string resolvedAtmosphereJson(const std::string& presetNameOrPath);

}  // namespace umbra::atmosphere
