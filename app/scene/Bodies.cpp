#include "scene/Bodies.hpp"

#include "scene/Units.hpp"

#include "SolarDisc.hpp"  // kSunRadiusM

#include <cctype>

namespace umbra::scene {

namespace {

constexpr double kKm = 1000.0;

// Radii: IAU WGCCRE 2015 (Archinal et al. 2018, Celest. Mech. Dyn. Astr. 130:22).
// The Sun's radius is the 696342 km (SOHO/MDI, Emilio et al. 2012) used by the
// eclipse literature. Distances are mean orbital distances (semi-major axes).
// Phobos and Deimos are triaxial; their mean radius stands for all three here.
const std::array<BodyPreset, 6> kPresets = {{
    {"Sun", eclipse::kSunRadiusM, eclipse::kSunRadiusM, eclipse::kSunRadiusM, "", 0.0, false, 0.0,
     {1.0, 1.0, 1.0}},
    {"Earth", 6378.1366 * kKm, 6356.7519 * kKm, 6371.0084 * kKm, "Sun", kAuM, true,
     0.367, {0.30, 0.45, 0.70}},
    {"Moon", 1737.4 * kKm, 1737.4 * kKm, 1737.4 * kKm, "Earth", 384400 * kKm, false, 0.12,
     {0.60, 0.58, 0.55}},
    {"Mars", 3396.19 * kKm, 3376.20 * kKm, 3389.50 * kKm, "Sun", 227939200 * kKm, true,
     0.170, {0.80, 0.47, 0.32}},
    {"Phobos", 11.08 * kKm, 11.08 * kKm, 11.08 * kKm, "Mars", 9376 * kKm, false, 0.071,
     {0.45, 0.42, 0.40}},
    {"Deimos", 6.2 * kKm, 6.2 * kKm, 6.2 * kKm, "Mars", 23463.2 * kKm, false, 0.068,
     {0.50, 0.47, 0.44}},
}};

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

} // namespace

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
