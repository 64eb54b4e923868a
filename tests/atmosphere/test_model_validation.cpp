// Validation on load: every mistake is one line naming the file and the field.
#include "Atmosphere.hpp"
#include "ModelTestSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

using namespace umbra::atmosphere;

namespace {

/// A small valid atmosphere in which `replace` swaps one piece of text.
std::string document(const std::string& from = "", const std::string& to = "") {
  std::string text = R"({
  "name": "test",
  "bottomRadiusM": 6371000,
  "topRadiusM": 6471000,
  "refraction": {"seaLevelRefractivity": 2.77e-4},
  "components": {
    "molecules": {
      "density": {"type": "exponential", "scaleHeightM": 8000},
      "optics": {"model": "rayleigh", "refractiveIndex": {"formula": "peck-reeder-1972"},
                 "numberDensityPerM3": 2.547e25, "depolarisation": 0.0279}
    },
    "aerosols": {
      "density": {"type": "exponential", "scaleHeightM": 1200},
      "optics": {"model": "coefficients", "scatteringPerM": 3.996e-6, "absorptionPerM": 4.44e-7},
      "phase": {"type": "henyey-greenstein", "g": 0.8}
    },
    "ozone": {
      "density": {"type": "tent", "centreM": 25000, "halfWidthM": 15000},
      "optics": {"model": "absorber", "numberDensityPerM3": 5.374e18,
                 "crossSectionM2": {"wavelengthsNm": [500, 600], "values": [1.48e-25, 5.019e-25]}}
    },
    "layer": {
      "density": {"type": "tabulated", "altitudesM": [0, 1000, 2000], "values": [1, 0.5, 0]},
      "optics": {"model": "coefficients", "scatteringPerM": 1e-6},
      "phase": {"type": "isotropic"}
    }
  }
})";
  if (!from.empty()) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

std::string errorOf(const std::string& text, const std::vector<double>& wl = {440.0, 550.0, 680.0}) {
  try {
    parseAtmosphere(text, "bad.json", wl);
  } catch (const AtmosphereError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(ModelValidation, TheTestDocumentIsValid) {
  const Atmosphere a = parseAtmosphere(document(), "good.json", {440.0, 550.0, 680.0});
  EXPECT_EQ(a.components.size(), 4u);
  EXPECT_EQ(a.components[0].name, "molecules");  // file order is kept
  EXPECT_EQ(a.components[3].name, "layer");
  EXPECT_EQ(a.groundAlbedo, std::vector<double>(3, 0.1));
}

TEST(ModelValidation, UnknownKey) {
  EXPECT_EQ(errorOf(document("\"scatteringPerM\": 3.996e-6", "\"scaterringPerM\": 3.996e-6")),
            "bad.json: components.aerosols.optics.scaterringPerM: unknown key (expected one of: description, model, "
            "scatteringPerM, absorptionPerM)");
  EXPECT_EQ(errorOf(document("\"name\": \"test\"", "\"nmae\": \"test\"")),
            "bad.json: nmae: unknown key (expected one of: name, description, bottomRadiusM, topRadiusM, "
            "groundAlbedo, relativeHumidity, boundaryLayerHeightM, aerosolOpticalDepth550, refraction, components)");
  // A refractive index is a formula or a refractivity, not both.
  EXPECT_EQ(errorOf(document("{\"formula\": \"peck-reeder-1972\"}",
                             "{\"formula\": \"peck-reeder-1972\", \"refractivity\": 2.9e-4}")),
            "bad.json: components.molecules.optics.refractiveIndex: expected one of 'formula' and 'refractivity', not both");
}

TEST(ModelValidation, NegativeOrMissingCoefficient) {
  EXPECT_EQ(errorOf(document("\"scatteringPerM\": 3.996e-6", "\"scatteringPerM\": -3.996e-6")),
            "bad.json: components.aerosols.optics.scatteringPerM: expected a coefficient from 0 to 1 in 1/m, got -3.996e-06");
  EXPECT_EQ(errorOf(document("\"scatteringPerM\": 3.996e-6", "\"scatteringPerM\": null")),
            "bad.json: components.aerosols.optics.scatteringPerM: expected a coefficient from 0 to 1 in 1/m or "
            "{\"wavelengthsNm\": [...], \"values\": [...]}, got null");
  EXPECT_EQ(errorOf(document("\"values\": [1.48e-25, 5.019e-25]", "\"values\": [1.48e-25, -5.019e-25]")),
            "bad.json: components.ozone.optics.crossSectionM2.values[1]: expected a cross-section >= 0 in m^2, "
            "got -5.019e-25");
  EXPECT_EQ(errorOf(document("\"model\": \"absorber\", \"numberDensityPerM3\": 5.374e18,", "\"model\": \"absorber\",")),
            "bad.json: components.ozone.optics: missing required key 'numberDensityPerM3'");
}

TEST(ModelValidation, TopRadiusNotAboveTheBottom) {
  EXPECT_EQ(errorOf(document("\"topRadiusM\": 6471000", "\"topRadiusM\": 6371000")),
            "bad.json: topRadiusM: expected a radius at least 1 m above bottomRadiusM (6371000), got 6371000");
  EXPECT_EQ(errorOf(document("\"bottomRadiusM\": 6371000", "\"bottomRadiusM\": -1")),
            "bad.json: bottomRadiusM: expected a radius from 1 m to 1e12 m, got -1");
  // Absurd but finite radii (they reached an index through NaN in the tables' lookups).
  EXPECT_EQ(errorOf(document("\"topRadiusM\": 6471000", "\"topRadiusM\": 1e308")),
            "bad.json: topRadiusM: expected a radius from 1 m to 1e12 m, got 1e+308");
  EXPECT_EQ(errorOf(document("\"bottomRadiusM\": 6371000", "\"bottomRadiusM\": 1e-300")),
            "bad.json: bottomRadiusM: expected a radius from 1 m to 1e12 m, got 1e-300");
}

TEST(ModelValidation, TentWithoutWidth) {
  EXPECT_EQ(errorOf(document("\"halfWidthM\": 15000", "\"halfWidthM\": 0")),
            "bad.json: components.ozone.density.halfWidthM: expected a positive length in metres, got 0");
  EXPECT_EQ(errorOf(document("\"halfWidthM\": 15000", "\"halfWidthM\": -15000")),
            "bad.json: components.ozone.density.halfWidthM: expected a positive length in metres, got -15000");
}

TEST(ModelValidation, TabulatedProfileWithUnsortedAltitudes) {
  EXPECT_EQ(errorOf(document("[0, 1000, 2000]", "[0, 2000, 1000]")),
            "bad.json: components.layer.density.altitudesM[2]: expected strictly increasing altitudes, got 1000 "
            "after 2000");
  EXPECT_EQ(errorOf(document("\"type\": \"tent\"", "\"type\": \"triangle\"")),
            "bad.json: components.ozone.density.type: expected one of: exponential, double-exponential, tent, "
            "boundary-layer, tabulated, got \"triangle\"");
}

TEST(ModelValidation, PhaseAsymmetryOutsideMinusOneToOne) {
  EXPECT_EQ(errorOf(document("\"g\": 0.8", "\"g\": 1.0")),
            "bad.json: components.aerosols.phase.g: expected a number in [-0.999999, 0.999999], got 1.0");
  EXPECT_EQ(errorOf(document("\"g\": 0.8", "\"g\": {\"wavelengthsNm\": [440, 680], \"values\": [0.8, -1.2]}")),
            "bad.json: components.aerosols.phase.g.values[1]: expected a number in [-0.999999, 0.999999], got -1.2");
  EXPECT_EQ(errorOf(document(",\n      \"phase\": {\"type\": \"henyey-greenstein\", \"g\": 0.8}", "")),
            "bad.json: components.aerosols: missing required key 'phase' (the component scatters)");
}

TEST(ModelValidation, UnknownPresetListsTheKnownOnes) {
  try {
    loadAtmosphere("venus", {550.0});
    FAIL() << "no error";
  } catch (const AtmosphereError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("unknown atmosphere preset 'venus' (known: ", 0), 0u) << message;
    for (const char* name : {"earth", "earth-2015-calbuco", "mars"})
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
  const std::string extends = errorOf(R"({"extends": "venus", "name": "x"})");
  EXPECT_EQ(extends.rfind("bad.json: extends: unknown atmosphere preset 'venus' (known: ", 0), 0u) << extends;
}

TEST(ModelValidation, MalformedJsonGivesLineAndColumn) {
  EXPECT_EQ(errorOf("{\n  \"name\": \"x\",\n  \"bottomRadiusM\" 6371000\n}"),
            "bad.json: invalid JSON at line 3, column 25: syntax error while parsing object separator - "
            "unexpected number literal; expected ':'");
}

// Hostile files: nesting that would exhaust the stack is refused while reading; a key
// given twice is named (JSON would keep the last silently).
TEST(ModelValidation, DeepNestingAndDuplicateKeys) {
  const std::string deep = errorOf(R"({"components": )" + std::string(50000, '[') + std::string(50000, ']') + "}");
  EXPECT_EQ(deep.rfind("bad.json: nested more than 64 levels deep (at components[0]", 0), 0u) << deep;
  EXPECT_EQ(errorOf(R"({"name": "x", "bottomRadiusM": 6371000, "bottomRadiusM": 6371000})"),
            "bad.json: bottomRadiusM: duplicate key");
}

TEST(ModelValidation, FilesWavelengthsAndFormulaRanges) {
  const std::string missing = "/nonexistent/atmosphere.json";
  try {
    loadAtmosphere(missing, {550.0});
    FAIL() << "no error";
  } catch (const AtmosphereError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/atmosphere.json: cannot open file: No such file or directory");
  }
  EXPECT_EQ(errorOf(document(), {550.0, -1.0}), "bad.json: wavelengthsNm[1]: expected a positive wavelength in nm, got -1");
  EXPECT_EQ(errorOf(document(), {550.0, std::nan("")}),
            "bad.json: wavelengthsNm[1]: expected a positive wavelength in nm, got nan");
  EXPECT_EQ(errorOf(document(), {550.0, 2000.0}),
            "bad.json: components.molecules.optics.refractiveIndex.formula: wavelength 2000 nm is outside the "
            "formula's range (230-1690 nm)");
  EXPECT_EQ(errorOf(document("\"seaLevelRefractivity\": 2.77e-4", "\"seaLevelRefractivity\": 2.77e-4, \"followsComponent\": \"air\"")),
            "bad.json: refraction.followsComponent: expected the name of a component (molecules, aerosols, ozone, "
            "layer), got 'air'");
}

// A null removes what the base has; one for what it does not have (a typo, or a component
// renamed since) is an error naming what there is.
TEST(ModelValidation, RemovingWhatTheBaseLacksNamesWhatItHas) {
  EXPECT_EQ(errorOf(R"({"extends": "earth", "components": {"aerosols": null}})"),
            "bad.json: components.aerosols: null removes 'aerosols', which 'earth' does not have in 'components' "
            "(it has: molecules, troposphere, stratosphere, ozone, oxygen)");
  const std::string top = errorOf(R"({"extends": "earth", "ozone": null})");
  EXPECT_EQ(top.rfind("bad.json: ozone: null removes 'ozone', which 'earth' does not have (it has: ", 0), 0u) << top;
  EXPECT_NE(top.find("components"), std::string::npos) << top;
  // What is there goes, and the rest reads as before.
  EXPECT_EQ(parseAtmosphere(R"({"extends": "earth", "components": {"stratosphere": null}})", "ok.json", {550.0})
                .find("stratosphere"),
            nullptr);
}

TEST(ModelValidation, ExtendsMergesAPresetWithOverrides) {
  // a file next to nothing: "extends" a preset by name, drops ozone, changes one number
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "umbra-atmosphere-model-test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "thin-earth.json";
  std::ofstream(file) << R"({"extends": "earth", "name": "thin", "components": {"ozone": null,
                            "molecules": {"density": {"scaleHeightM": 4000}}}})";
  const Atmosphere thin = loadAtmosphere(file.string(), {550.0});
  EXPECT_EQ(thin.name, "thin");
  EXPECT_EQ(thin.find("ozone"), nullptr);
  EXPECT_EQ(thin.component("molecules").density.scaleHeightM, 4000.0);
  EXPECT_EQ(thin.component("molecules").scatteringPerM, loadAtmosphere("earth", {550.0}).component("molecules").scatteringPerM);
  std::ofstream(file) << R"({"extends": "earth-bruneton", "components": {"aerosols": {"density": {"scaleHeightM": 0}}}})";
  try {
    loadAtmosphere(file.string(), {550.0});
    FAIL() << "no error";
  } catch (const AtmosphereError& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ": components.aerosols.density.scaleHeightM: expected a positive "
                                                      "length in metres, got 0");
  }
  std::filesystem::remove_all(dir);
}

TEST(ModelValidation, CostasParametricDustMustNotScatterMoreThanItExtinguishes) {
  // Eq. 17 with Costa's Mars K and T = 2 gives 1.9e-3 1/m of scattering; Eq. 20 with 2.8e6
  // particles of 1.6 um only 4.5e-5 1/m of extinction.
  const std::string dust = R"({"bottomRadiusM": 3389500, "topRadiusM": 3469500, "components": {"dust": {
      "density": {"type": "exponential", "scaleHeightM": 11100},
      "optics": {"model": "anomalous-diffraction", "radiusM": 1.6e-6, "numberDensityPerM3": 2.8e6,
                 "refractiveIndexReal": 1.52, "refractiveIndexImag": 0.006,
                 "vanDeHulst": {"turbidity": 2, "jungeExponent": 4, "K": 0.16}},
      "phase": {"type": "henyey-greenstein", "g": 0.5}}}})";
  const std::string message = errorOf(dust, {550.0});
  EXPECT_EQ(message.rfind("bad.json: components.dust.optics.vanDeHulst: at 550 nm the Eq. 17 scattering 0.00185", 0), 0u)
      << message;
}

// An atmosphere whose refractivity falls faster than 1/r traps rays round the body
// (ducting): the tables traced them for minutes and then read NaN. Refused when read,
// naming where; the presets are far from it (Earth: 0.23 of the limit at the ground).
TEST(ModelValidation, DuctingRefractivityIsRefused) {
  const std::string e = errorOf(R"({"extends": "earth", "name": "thin", "components": {"molecules": {"density":
      {"type": "double-exponential", "scaleHeightM": 100}}}})");
  EXPECT_NE(e.find("refraction: the refractivity falls faster than 1/r at 0 m above the ground (along "
                   "components.molecules.density)"), std::string::npos) << e;
  for (const std::string& preset : presetNames())
    EXPECT_EQ(loadAtmosphere(preset, {440.0, 550.0, 680.0}).ductingProblem(), "") << preset;
}
