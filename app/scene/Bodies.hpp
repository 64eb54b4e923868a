#pragma once
// Body presets: radii (IAU WGCCRE 2015, Archinal et al. 2018), mean orbital distances,
// atmosphere flag, geometric albedo and a display colour.
#include <array>
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
  std::array<double, 3> color;    ///< linear RGB display tint in [0, 1] (not physics)
};

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
