#pragma once
// Body presets: radii (IAU WGCCRE 2015, Archinal et al. 2018), mean orbital distances,
// atmosphere flag, geometric albedo, a colour, the photometric law and an albedo map.
#include "Photometry.hpp"

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace umbra::scene {

struct BodyPreset {
  std::string name;
  double equatorialRadiusM;
  double polarRadiusM;
  double meanRadiusM;
  std::string parent;             ///< body it orbits ("" for the Sun)
  double meanDistanceFromParentM; ///< mean orbital distance (semi-major axis)
  bool hasAtmosphere;
  double geometricAlbedo;
  std::array<double, 3> color;    ///< relative reflectance at 680, 550, 440 nm (the Moon's: its reddish hue)
  sky::Photometry photometry;     ///< Lambert's law, or Hapke's for the dusty airless bodies
  std::string albedoMap;          ///< a named map (findNamedAlbedoMap) used when installed; "" for none
  std::string normalMap;          ///< a named normal map (findNamedNormalMap) used when installed; "" for none
};

/// A named map (albedo or normals) and the Debian package that installs it.
struct NamedAlbedoMap {
  std::string name;     ///< "clementine"
  std::string package;  ///< "marble-qt-data"
  std::string file;     ///< where the package puts it
  bool reflectance = false;  ///< an albedo map whose sRGB colour is the surface's reflectance
};
/// The maps a scene can name: "clementine", the Clementine UVVIS mosaic of the Moon
/// (2700x1350, in marble-qt-data: $UMBRA_MARBLE_DATA_DIR, default /usr/share/marble/data,
/// then maps/moon/clementine/clementine.jpg); "bluemarble", NASA's Blue Marble colour map of
/// the Earth (2700x1350, maps/earth/bluemarble/bluemarble.jpg there), a reflectance map.
/// Nothing for another name.
std::optional<NamedAlbedoMap> findNamedAlbedoMap(std::string_view name);
/// "clementine, bluemarble" for messages.
std::string namedAlbedoMapList();
/// The normal maps a scene can name: "stellarium", the Moon's relief that stellarium-data
/// installs ($UMBRA_STELLARIUM_DATA_DIR, default /usr/share/stellarium, then
/// textures/moon_normals.png; sky/NormalMap.hpp says how it lies). Nothing for another name.
std::optional<NamedAlbedoMap> findNamedNormalMap(std::string_view name);
/// "stellarium" for messages (the normal maps' and the Milky Way maps' names).
std::string namedNormalMapList();
/// The Milky Way maps a scene can name: "stellarium", the panorama that stellarium-data
/// installs (textures/milkyway.png there; sky/MilkyWay.hpp says how it lies).
std::optional<NamedAlbedoMap> findNamedMilkyWayMap(std::string_view name);

/// The preset with this name (case-insensitive), or nullptr.
const BodyPreset* findPreset(std::string_view name);

/// The preset names in a stable order: Sun, Earth, Moon, Mars, Phobos, Deimos.
std::vector<std::string> presetNames();

/// Mean distance from the Sun: the body's own for a planet, its parent's for a moon,
/// 0 for the Sun.
double meanDistanceFromSunM(const BodyPreset& preset);

/// "Sun, Earth, Moon, ..." for error messages.
std::string presetNameList();

} // namespace umbra::scene
