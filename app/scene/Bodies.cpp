#include "scene/Bodies.hpp"

#include "scene/Units.hpp"

#include "SolarDisc.hpp"  // kSunRadiusM

#include <cctype>
#include <cstdlib>

namespace umbra::scene {

namespace {

constexpr double kKm = 1000.0;

// Radii: IAU WGCCRE 2015 (Archinal et al. 2018, Celest. Mech. Dyn. Astr. 130:22).
// The Sun's radius is the 696342 km (SOHO/MDI, Emilio et al. 2012) used by the
// eclipse literature. Distances are mean orbital distances (semi-major axes).
// Phobos and Deimos are triaxial; their mean radius stands for all three here.
// Photometry: the Moon, Phobos and Deimos reflect by the Hapke–Lommel–Seeliger law with
// the Moon's parameters (sky::moonParameters), the planets by Lambert's. The Moon's colour
// is the day-and-night-sky paper's k_lambda = (0.92, 0.79, 0.64) at 680, 550, 440 nm
// (its reflectance spectrum, Sect. 2.2.2).
const sky::Photometry kLambert{};
const sky::Photometry kHapke{sky::Photometry::Law::Hapke, sky::moonParameters()};
const std::array<BodyPreset, 6> kPresets = {{
    {"Sun", eclipse::kSunRadiusM, eclipse::kSunRadiusM, eclipse::kSunRadiusM, "", 0.0, false, 0.0,
     {1.0, 1.0, 1.0}, kLambert, "", ""},
    {"Earth", 6378.1366 * kKm, 6356.7519 * kKm, 6371.0084 * kKm, "Sun", kAuM, true,
     0.367, {0.30, 0.45, 0.70}, kLambert, "", ""},
    {"Moon", 1737.4 * kKm, 1737.4 * kKm, 1737.4 * kKm, "Earth", 384400 * kKm, false, 0.12,
     {0.92, 0.79, 0.64}, kHapke, "clementine", "stellarium"},
    {"Mars", 3396.19 * kKm, 3376.20 * kKm, 3389.50 * kKm, "Sun", 227939200 * kKm, true,
     0.170, {0.80, 0.47, 0.32}, kLambert, "", ""},
    {"Phobos", 11.08 * kKm, 11.08 * kKm, 11.08 * kKm, "Mars", 9376 * kKm, false, 0.071,
     {0.45, 0.42, 0.40}, kHapke, "", ""},
    {"Deimos", 6.2 * kKm, 6.2 * kKm, 6.2 * kKm, "Mars", 23463.2 * kKm, false, 0.068,
     {0.50, 0.47, 0.44}, kHapke, "", ""},
}};

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

std::string marbleDataDir() {
  const char* dir = std::getenv("UMBRA_MARBLE_DATA_DIR");
  return dir && *dir ? dir : "/usr/share/marble/data";
}

} // namespace

std::optional<NamedAlbedoMap> findNamedAlbedoMap(std::string_view name) {
  if (equalsIgnoreCase(name, "clementine"))
    return NamedAlbedoMap{"clementine", "marble-qt-data", marbleDataDir() + "/maps/moon/clementine/clementine.jpg"};
  if (equalsIgnoreCase(name, "bluemarble"))
    return NamedAlbedoMap{"bluemarble", "marble-qt-data", marbleDataDir() + "/maps/earth/bluemarble/bluemarble.jpg",
                          true};
  return std::nullopt;
}

std::string namedAlbedoMapList() { return "clementine, bluemarble"; }

namespace {

std::optional<NamedAlbedoMap> stellariumTexture(std::string_view name, const char* file) {
  if (!equalsIgnoreCase(name, "stellarium")) return std::nullopt;
  const char* dir = std::getenv("UMBRA_STELLARIUM_DATA_DIR");
  const std::string root = dir && *dir ? dir : "/usr/share/stellarium";
  return NamedAlbedoMap{"stellarium", "stellarium-data", root + "/textures/" + file};
}

}  // namespace

std::optional<NamedAlbedoMap> findNamedNormalMap(std::string_view name) {
  return stellariumTexture(name, "moon_normals.png");
}

std::string namedNormalMapList() { return "stellarium"; }

std::optional<NamedAlbedoMap> findNamedMilkyWayMap(std::string_view name) {
  return stellariumTexture(name, "milkyway.png");
}

const BodyPreset* findPreset(std::string_view name) {
  for (const BodyPreset& preset : kPresets)
    if (equalsIgnoreCase(preset.name, name)) return &preset;
  return nullptr;
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const BodyPreset& preset : kPresets) names.push_back(preset.name);
  return names;
}

std::string presetNameList() {
  std::string list;
  for (const BodyPreset& preset : kPresets) {
    if (!list.empty()) list += ", ";
    list += preset.name;
  }
  return list;
}

double meanDistanceFromSunM(const BodyPreset& preset) {
  if (preset.parent.empty()) return 0.0;
  const BodyPreset* parent = findPreset(preset.parent);
  if (parent == nullptr || parent->parent.empty()) return preset.meanDistanceFromParentM;
  return meanDistanceFromSunM(*parent);
}

} // namespace umbra::scene
