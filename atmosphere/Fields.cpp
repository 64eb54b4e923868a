// The table of an atmosphere file's fields (Fields.hpp). The reader (AtmosphereReader.cpp)
// takes the keys it accepts from it; the ranges it states are the reader's checks, which
// tests/atmosphere/test_fields.cpp holds together with it.
#include "Fields.hpp"

#include <algorithm>
#include <stdexcept>

namespace umbra::atmosphere {

const std::vector<Field>& atmosphereFields() {
  static const std::vector<Field> fields{
      // where, type, key, unit, range, example value, required (default true), replaces
      {"", "", "name", "", "text", "\"edited\"", false},
      {"", "", "description", "", "text", "\"notes\"", false},
      {"", "", "bottomRadiusM", "m", "1 .. 1e12", "6371000"},
      {"", "", "topRadiusM", "m", ">= bottomRadiusM + 1, <= 1e12", "6471000"},
      {"", "", "groundAlbedo", "", "[0, 1], spectrum", "0.1"},
      {"", "", "relativeHumidity", "", "[0, 0.99]: hygroscopic particles grow (default 0)", "0.8", false},
      {"", "", "boundaryLayerHeightM", "m", "(0, 1e5]: the mixing layer's top in every boundary-layer density (default 2000)",
       "1000", false},
      {"", "", "aerosolOpticalDepth550", "", "[0, 10]: the \"aerosol\" components scaled to it", nullptr, false},
      {"", "", "refraction", "", "object", R"({"seaLevelRefractivity": 2.77e-4})", false},
      {"", "", "components", "", "object of named components", "{}"},

      {"refraction", "", "seaLevelRefractivity", "", "n - 1 at the ground, [0, 1)", "2.77e-4"},
      {"refraction", "", "referenceWavelengthNm", "nm", "> 0", "550", false},
      {"refraction", "", "dispersion", "", "none, peck-reeder-1972, bideau-mehu-1973-co2", "\"none\"", false},
      {"refraction", "", "followsComponent", "", "a component's name", "\"molecules\"", false},

      {"components.*", "", "description", "", "text", "\"notes\"", false},
      {"components.*", "", "aerosol", "", "true: scaled by aerosolOpticalDepth550", "true", false},
      {"components.*", "", "density", "", "profile", R"({"type": "exponential", "scaleHeightM": 8000})"},
      {"components.*", "", "densityScale", "", "> 0, multiplies every coefficient", "2", false},
      {"components.*", "", "optics", "", "object", R"({"model": "coefficients", "scatteringPerM": 4e-6})"},
      {"components.*", "", "phase", "", "object (default rayleigh for the rayleigh model)", R"({"type": "isotropic"})", false},

      {"components.*.density", "exponential", "type", "", "", "\"exponential\""},
      {"components.*.density", "exponential", "scaleHeightM", "m", "> 0", "8000"},
      {"components.*.density", "double-exponential", "type", "", "", "\"double-exponential\""},
      {"components.*.density", "double-exponential", "scaleHeightM", "m", "> 0", "8000"},
      {"components.*.density", "tent", "type", "", "", "\"tent\""},
      {"components.*.density", "tent", "centreM", "m", "finite", "25000"},
      {"components.*.density", "tent", "halfWidthM", "m", "> 0", "15000"},
      {"components.*.density", "boundary-layer", "type", "", "", "\"boundary-layer\""},
      {"components.*.density", "boundary-layer", "scaleHeightM", "m", "> 0, in the mixing layer", "8000"},
      {"components.*.density", "boundary-layer", "transitionM", "m",
       ">= 0, < 2 boundaryLayerHeightM: each step blended over this width (default 0: steps)", "500", false},
      {"components.*.density", "boundary-layer", "freeTroposphere", "", "object: the layer above the mixing layer",
       R"({"relativeDensity": 0.0626, "scaleHeightM": 8000, "topM": 12000})", false},
      {"components.*.density", "tabulated", "type", "", "", "\"tabulated\""},
      {"components.*.density", "tabulated", "altitudesM", "m", "strictly increasing, >= 2 samples", "[0, 10000]"},
      {"components.*.density", "tabulated", "values", "", ">= 0, one per altitude", "[1, 0]"},

      {"components.*.optics", "", "description", "", "text", "\"notes\"", false},
      {"components.*.optics", "rayleigh", "model", "", "", "\"rayleigh\""},
      {"components.*.optics", "rayleigh", "refractiveIndex", "", "formula or refractivity", R"({"formula": "peck-reeder-1972"})"},
      {"components.*.optics", "rayleigh", "numberDensityPerM3", "1/m^3", "> 0, <= 1e35", "2.546916e25"},
      {"components.*.optics", "rayleigh", "depolarisation", "", "[0, 0.5]", "0.0279"},
      {"components.*.optics", "absorber", "model", "", "", "\"absorber\""},
      {"components.*.optics", "absorber", "numberDensityPerM3", "1/m^3", "> 0, <= 1e35", "5.374e18"},
      {"components.*.optics", "absorber", "crossSectionM2", "m^2", ">= 0, spectrum", "1e-25"},
      {"components.*.optics", "coefficients", "model", "", "", "\"coefficients\""},
      {"components.*.optics", "coefficients", "scatteringPerM", "1/m", "0 .. 1, spectrum", "4e-6"},
      {"components.*.optics", "coefficients", "absorptionPerM", "1/m", "0 .. 1, spectrum", "1e-7", false},
      {"components.*.optics", "van-de-hulst", "model", "", "", "\"van-de-hulst\""},
      {"components.*.optics", "van-de-hulst", "turbidity", "", ">= 1", "2"},
      {"components.*.optics", "van-de-hulst", "jungeExponent", "", "[2, 6]", "4"},
      {"components.*.optics", "van-de-hulst", "K", "", ">= 0, spectrum", "0.68"},
      {"components.*.optics", "van-de-hulst", "absorptionPerM", "1/m", "0 .. 1, spectrum", "1e-7", false},
      {"components.*.optics", "anomalous-diffraction", "model", "", "", "\"anomalous-diffraction\""},
      {"components.*.optics", "anomalous-diffraction", "radiusM", "m", "(0, 0.01]", "1.6e-6"},
      {"components.*.optics", "anomalous-diffraction", "numberDensityPerM3", "1/m^3", "> 0, <= 1e35", "2.8e6"},
      {"components.*.optics", "anomalous-diffraction", "refractiveIndexReal", "", "> 1, spectrum", "1.52"},
      {"components.*.optics", "anomalous-diffraction", "refractiveIndexImag", "", ">= 0, spectrum", "0.006"},
      {"components.*.optics", "anomalous-diffraction", "vanDeHulst", "", "object: scattering from Costa Eq. 17", R"({"turbidity": 2, "jungeExponent": 4, "K": 0})", false},

      {"components.*.optics", "mie", "model", "", "", "\"mie\""},
      {"components.*.optics", "mie", "effectiveRadiusM", "m", "(0, 2e-5]", "1.5e-6"},
      {"components.*.optics", "mie", "effectiveVariance", "", "[0, 2] (0: one radius)", "0.3", false},
      {"components.*.optics", "mie", "medianRadiusM", "m", "(0, 2e-5], the number median (instead of effectiveRadiusM)",
       "0.0212e-6", false, "effectiveRadiusM"},
      {"components.*.optics", "mie", "geometricStdDev", "", "[1, 5] (instead of effectiveVariance)", "2.24", false,
       "effectiveVariance"},
      {"components.*.optics", "mie", "radiusRangeM", "m", "[min, max], 0 <= min < max <= 1e-3", "[5e-9, 2e-5]", false},
      {"components.*.optics", "mie", "hygroscopicGrowth", "", "object: the radius factor per relative humidity",
       R"({"relativeHumidity": [0, 0.8], "radiusFactor": [1, 1.443]})", false},
      {"components.*.optics", "mie", "numberDensityPerM3", "1/m^3", "> 0, <= 1e35", "5.8e6"},
      {"components.*.optics", "mie", "refractiveIndexReal", "", "> 0, spectrum", "1.52"},
      {"components.*.optics", "mie", "refractiveIndexImag", "", ">= 0, spectrum", "0.006"},

      {"components.*.density.freeTroposphere", "", "relativeDensity", "", ">= 0, just above the mixing layer", "0.0626"},
      {"components.*.density.freeTroposphere", "", "scaleHeightM", "m", "> 0", "8000"},
      {"components.*.density.freeTroposphere", "", "topM", "m", ">= boundaryLayerHeightM", "12000"},
      {"components.*.optics.refractiveIndex", "", "formula", "", "peck-reeder-1972, bideau-mehu-1973-co2", "\"peck-reeder-1972\"", false},
      {"components.*.optics.refractiveIndex", "", "refractivity", "", "n - 1 in (0, 1), spectrum (instead of formula; needs atNumberDensityPerM3)", nullptr, false},
      {"components.*.optics", "mixture", "model", "", "", "\"mixture\""},
      {"components.*.optics", "mixture", "of", "", "object of named optics, each with its own phase (mie, rayleigh)",
       R"({"dust": {"model": "mie", "effectiveRadiusM": 1e-7, "numberDensityPerM3": 1e9, "refractiveIndexReal": 1.5, "refractiveIndexImag": 0}})"},

      {"components.*.optics.refractiveIndex", "", "atNumberDensityPerM3", "1/m^3", "> 0", "2.545e25", false},
      {"components.*.optics.hygroscopicGrowth", "", "relativeHumidity", "", "increasing in [0, 1)", "[0, 0.8]"},
      {"components.*.optics.hygroscopicGrowth", "", "radiusFactor", "", "in [1, 100], one per relative humidity",
       "[1, 1.443]"},
      {"components.*.optics.vanDeHulst", "", "turbidity", "", ">= 1", "2"},
      {"components.*.optics.vanDeHulst", "", "jungeExponent", "", "[2, 6]", "4"},
      {"components.*.optics.vanDeHulst", "", "K", "", ">= 0, spectrum", "0"},

      {"components.*.phase", "isotropic", "type", "", "", "\"isotropic\""},
      {"components.*.phase", "rayleigh", "type", "", "", "\"rayleigh\""},
      {"components.*.phase", "penndorf", "type", "", "", "\"penndorf\""},
      {"components.*.phase", "henyey-greenstein", "type", "", "", "\"henyey-greenstein\""},
      {"components.*.phase", "henyey-greenstein", "g", "", "[-0.999999, 0.999999], spectrum", "0.8"},
      {"components.*.phase", "double-henyey-greenstein", "type", "", "", "\"double-henyey-greenstein\""},
      {"components.*.phase", "double-henyey-greenstein", "g1", "", "[-0.999999, 0.999999], spectrum", "0.8"},
      {"components.*.phase", "double-henyey-greenstein", "g2", "", "[-0.999999, 0.999999], spectrum", "-0.2"},
      {"components.*.phase", "double-henyey-greenstein", "alpha", "", "[0, 1], spectrum", "0.9"},
      {"components.*.phase", "cornette-shanks", "type", "", "", "\"cornette-shanks\""},
      {"components.*.phase", "cornette-shanks", "g", "", "[-0.999999, 0.999999], spectrum", "0.8"},
      {"components.*.phase", "tabulated", "type", "", "", "\"tabulated\""},
      {"components.*.phase", "tabulated", "cosTheta", "", "-1 to 1, strictly monotonic", "[-1, 1]"},
      {"components.*.phase", "tabulated", "anglesDeg", "deg", "0 to 180, strictly monotonic (instead of cosTheta)",
       "[0, 180]", false, "cosTheta"},
      {"components.*.phase", "tabulated", "values", "", ">= 0, one per sample (normalised on load)", "[1, 1]"},
      {"components.*.phase", "tabulated", "wavelengthsNm", "nm", "increasing; then one values array per wavelength",
       nullptr, false},
  };
  return fields;
}

std::string fieldPattern(const std::string& objectPath) {
  const std::string prefix = "components.";
  if (objectPath.rfind(prefix, 0) != 0) return objectPath;
  const std::size_t end = objectPath.find('.', prefix.size());
  std::string pattern = prefix + "*" + (end == std::string::npos ? std::string() : objectPath.substr(end));
  // A mixture's part ("optics.of.<name>") is an optics object.
  const std::string part = ".optics.of.";
  for (std::size_t at; (at = pattern.find(part)) != std::string::npos;) {
    const std::size_t nameEnd = pattern.find('.', at + part.size());
    pattern.replace(at, (nameEnd == std::string::npos ? pattern.size() : nameEnd) - at, ".optics");
  }
  return pattern;
}

std::string selectorKey(const std::string& where) {
  for (const Field& f : atmosphereFields())
    if (where == f.where && *f.type != '\0') return f.key;  // the first line of a type is its selector
  return {};
}

std::vector<std::string> fieldTypes(const std::string& where) {
  const std::string selector = selectorKey(where);
  std::vector<std::string> types;
  for (const Field& f : atmosphereFields())
    if (where == f.where && *f.type != '\0' && selector == f.key) types.emplace_back(f.type);
  return types;
}

std::vector<std::string> fieldKeys(const std::string& where, const std::string& type) {
  std::vector<std::string> keys;
  for (const Field& f : atmosphereFields())
    if (where == f.where && (*f.type == '\0' || type == f.type)) keys.emplace_back(f.key);
  return keys;
}

const Field* findField(const std::string& where, const std::string& type, const std::string& key) {
  for (const Field& f : atmosphereFields())
    if (where == f.where && key == f.key && (*f.type == '\0' || type == f.type)) return &f;
  return nullptr;
}

nlohmann::ordered_json withFieldType(const nlohmann::ordered_json& object, const std::string& where,
                                     const std::string& type) {
  const std::string selector = selectorKey(where);
  const std::vector<std::string> types = fieldTypes(where);
  if (selector.empty() || std::find(types.begin(), types.end(), type) == types.end())
    throw std::invalid_argument(where + ": no type '" + type + "' in the field table");
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  out[selector] = type;
  for (const Field& f : atmosphereFields()) {
    if (where != f.where || (*f.type != '\0' && type != f.type) || selector == f.key) continue;
    if (object.is_object() && object.contains(f.key)) out[f.key] = object[f.key];
    else if (f.required && f.exampleJson != nullptr) out[f.key] = nlohmann::ordered_json::parse(f.exampleJson);
  }
  return out;
}

}  // namespace umbra::atmosphere
