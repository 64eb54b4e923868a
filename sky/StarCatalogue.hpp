#pragma once
// A star catalogue: J2000 (ICRS) places with proper motions and parallaxes, V magnitudes and
// B-V colours. Reads the Hipparcos/Tycho catalogue that KStars ships (Debian's kstars-data,
// /usr/share/kstars/stars.dat: fixed-column text, 125 982 stars to V 8.99, brightest first),
// and as a fallback the Yale Bright Star Catalogue that xplanet ships (Debian's xplanet,
// /usr/share/xplanet/stars/BSC: 9 096 stars to V 7.96 with places and magnitudes only).
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace umbra::sky {

/// Where Debian's kstars-data puts the catalogue.
inline constexpr const char* kKStarsCatalogue = "/usr/share/kstars/stars.dat";
/// Where Debian's xplanet puts the Yale Bright Star Catalogue (5th revised ed.).
inline constexpr const char* kXplanetCatalogue = "/usr/share/xplanet/stars/BSC";
/// The B-V given to a star its catalogue has no colour for (the Yale catalogue of xplanet):
/// the Sun's, drawn white.
inline constexpr double kColourlessBMinusV = 0.65;

struct CatalogueStar {
  double raRad = 0.0, decRad = 0.0;      ///< J2000, ICRS
  double pmRaCosDecMasPerYear = 0.0;     ///< proper motion in RA times cos(Dec)
  double pmDecMasPerYear = 0.0;
  double parallaxMas = 0.0;
  double vMag = 0.0;
  double bMinusV = 0.0;
  std::string name;  ///< the common name ("Sirius"), else the Bayer name ("alp CMa"), else ""
};

/// A catalogue file that cannot be read: what() is "<path>:<line>: <what>" or "<path>: <what>".
struct StarCatalogueError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One line of stars.dat: nullopt for a comment ('#') or a blank line. Throws
/// std::invalid_argument naming the column that is not what the format says.
std::optional<CatalogueStar> parseKStarsLine(const std::string& line);

/// Every star of the file down to `faintestVMag` (the file is sorted by magnitude, so the
/// reading stops at the first fainter star).
std::vector<CatalogueStar> readKStarsCatalogue(const std::string& path, double faintestVMag = 99.0);

/// One line of xplanet's BSC: "Dec[deg] RA[h] V \"name\" BSN HD SAO"; nullopt for a comment
/// ('#') or a blank line. No proper motion, parallax nor colour (kColourlessBMinusV). Throws
/// std::invalid_argument naming the field that is not a number or out of range.
std::optional<CatalogueStar> parseXplanetLine(const std::string& line);

/// Either format, told by the first star line (xplanet's quote their names), as
/// readKStarsCatalogue does.
std::vector<CatalogueStar> readCatalogue(const std::string& path, double faintestVMag = 99.0);

/// Reads a whole catalogue (readCatalogue, or a faster copy of it).
using CatalogueReader = std::function<std::vector<CatalogueStar>(const std::string& path)>;

/// The whole catalogue at `path` through `read` (default readCatalogue), read once per
/// process and kept while the file's size and modification time stay the same. Thread-safe.
/// Throws what `read` throws.
std::shared_ptr<const std::vector<CatalogueStar>> cachedCatalogue(const std::string& path,
                                                                  const CatalogueReader& read = {});

}  // namespace umbra::sky
