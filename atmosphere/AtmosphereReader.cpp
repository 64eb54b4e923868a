// The reading of atmosphere files: JSON -> validated Atmosphere (format:
// docs/atmosphere-format.md), and AtmosphereModel, the carrier that reads a file once.
#include "JsonErrors.hpp"
#include "Atmosphere.hpp"
#include "AtmosphereModel.hpp"
#include "Spectrum.hpp"
#include "reader/Reader.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <mutex>
#include <sstream>

#ifndef UMBRA_ATMOSPHERE_PRESET_DIR
#define UMBRA_ATMOSPHERE_PRESET_DIR "atmosphere/presets"
#endif

namespace umbra::atmosphere {

namespace fs = std::filesystem;

// ---- presets ----------------------------------------------------------------------------

std::string presetDirectory() {
  if (const char* dir = std::getenv("UMBRA_ATMOSPHERE_PRESET_DIR"); dir != nullptr && *dir != '\0')
    return dir;
  return UMBRA_ATMOSPHERE_PRESET_DIR;
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(presetDirectory(), ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

// ---- loading ----------------------------------------------------------------------------

namespace {

using reader::got;
using reader::join;
using reader::json;
using reader::number;
using reader::Optics;
using reader::parseOptics;
using reader::Reader;

bool looksLikePath(const std::string& s) {
  return s.find('/') != std::string::npos ||
         (s.size() > 5 && s.compare(s.size() - 5, 5, ".json") == 0);
}


json parseJson(const std::string& text, const std::string& file) {
  ParsedJson<json> parsed = parseJsonFile<json>(text, file);
  if (!parsed.error.empty()) throw AtmosphereError(parsed.error);
  return std::move(parsed.value);
}

std::string readFile(const std::string& path) {
  FileText f = readJsonFileText(path);
  if (!f.error.empty()) throw AtmosphereError(f.error);
  return std::move(f.text);
}

std::string unknownPresetMessage(const std::string& name) {
  return "unknown atmosphere preset '" + name + "' (known: " + join(presetNames()) + ")";
}

/// Fails on a removal (a null) in `patch` of a key that `base` does not have at that place:
/// a typo would otherwise change nothing and say nothing. Names the keys that are there.
void checkRemovals(const Reader& in, const json& base, const json& patch, const std::string& field,
                   const std::string& baseName) {
  for (const auto& [key, value] : patch.items()) {
    const std::string at = Reader::join(field, key);
    const bool there = base.is_object() && base.contains(key);
    if (value.is_null() && !there) {
      std::vector<std::string> keys;
      if (base.is_object())
        for (const auto& kv : base.items()) keys.push_back(kv.key());
      in.fail(at, "null removes '" + key + "', which '" + baseName + "' does not have" +
                      (field.empty() ? "" : " in '" + field + "'") + " (it has: " + join(keys) + ")");
    }
    if (value.is_object() && there && base[key].is_object()) checkRemovals(in, base[key], value, at, baseName);
  }
}

/// The document with "extends" resolved: the base (a preset name or a path relative to
/// `directory`) merge-patched (RFC 7386) with the rest of this one. A null removes what the
/// base has; a null for what it does not have is an error.
json resolveExtends(json doc, const std::string& file, const std::string& directory, int depth) {
  if (!doc.is_object() || !doc.contains("extends")) return doc;
  const Reader in(file, {});
  if (depth > 8) in.fail("extends", "expected at most 8 levels of 'extends' (a cycle?)");
  const std::string base = in.string(doc["extends"], "extends");
  std::string basePath;
  if (looksLikePath(base)) {
    basePath = fs::path(base).is_absolute() ? base : (fs::path(directory) / base).string();
  } else {
    basePath = (fs::path(presetDirectory()) / (base + ".json")).string();
    if (!fs::exists(basePath)) in.fail("extends", unknownPresetMessage(base));
  }
  if (!fs::exists(basePath)) in.fail("extends", "no such file '" + basePath + "'");
  json merged = resolveExtends(parseJson(readFile(basePath), basePath), basePath,
                               fs::path(basePath).parent_path().string(), depth + 1);
  doc.erase("extends");
  checkRemovals(in, merged, doc, "", base);
  merged.merge_patch(doc);
  return merged;
}

// ---- parts of the document --------------------------------------------------------------

DensityProfile parseProfile(const Reader& in, const json& value, const std::string& field) {
  if (!value.is_object()) in.fail(field, "expected an object, " + got(value));
  const std::string type = in.string(in.require(value, "type", field), field + ".type");
  auto finite = [&](const char* key) {
    return in.number(in.require(value, key, field), Reader::join(field, key), "a finite number in metres",
                     [](double) { return true; });
  };
  DensityProfile p;
  if (type == "exponential" || type == "double-exponential") {
    in.object(value, field, "components.*.density", type);
    p.kind = type == "exponential" ? DensityProfile::Kind::Exponential : DensityProfile::Kind::DoubleExponential;
    p.scaleHeightM = finite("scaleHeightM");
  } else if (type == "tent") {
    in.object(value, field, "components.*.density", type);
    p.kind = DensityProfile::Kind::Tent;
    p.centreM = finite("centreM");
    p.halfWidthM = finite("halfWidthM");
  } else if (type == "boundary-layer") {
    // OPAC's tropospheric layers: the mixing layer up to the document's boundaryLayerHeightM,
    // then (when given) the free troposphere above it.
    in.object(value, field, "components.*.density", type);
    p.kind = DensityProfile::Kind::BoundaryLayer;
    p.scaleHeightM = finite("scaleHeightM");
    if (value.contains("transitionM")) p.transitionM = finite("transitionM");
    p.boundaryLayerTopM = in.boundaryLayerHeightM();
    p.freeTroposphereTopM = p.boundaryLayerTopM;
    if (value.contains("freeTroposphere")) {
      const std::string f = field + ".freeTroposphere";
      const json& ft = value["freeTroposphere"];
      if (!ft.is_object()) in.fail(f, "expected an object, " + got(ft));
      in.object(ft, f, "components.*.density.freeTroposphere");
      p.freeTroposphereDensity = in.number(in.require(ft, "relativeDensity", f), f + ".relativeDensity",
                                           "a relative density >= 0", [](double x) { return x >= 0.0; });
      p.freeTroposphereScaleHeightM = in.number(in.require(ft, "scaleHeightM", f), f + ".scaleHeightM",
                                                "a finite number in metres", [](double) { return true; });
      p.freeTroposphereTopM = in.number(in.require(ft, "topM", f), f + ".topM", "a finite number in metres",
                                        [](double) { return true; });
    }
  } else if (type == "tabulated") {
    in.object(value, field, "components.*.density", type);
    p.kind = DensityProfile::Kind::Tabulated;
    p.altitudesM = in.numbers(in.require(value, "altitudesM", field), field + ".altitudesM");
    p.values = in.numbers(in.require(value, "values", field), field + ".values");
  } else {
    in.fail(field + ".type",
            "expected one of: exponential, double-exponential, tent, boundary-layer, tabulated, " +
                got(value["type"]));
  }
  const std::string problem = p.validate();
  if (!problem.empty()) in.failWithKey(field, problem);
  return p;
}

std::vector<PhaseFunction> parsePhase(const Reader& in, const json& value, const std::string& field) {
  if (!value.is_object()) in.fail(field, "expected an object, " + got(value));
  const std::string type = in.string(in.require(value, "type", field), field + ".type");
  const std::size_t n = in.wavelengths().size();
  const auto inOpen = [](double g) { return std::abs(g) <= 1.0 - 1e-6; };  // PhaseFunction's own limit
  const auto unit = [](double a) { return a >= 0.0 && a <= 1.0; };
  auto g = [&](const char* key) {
    return in.spectrum(in.require(value, key, field), Reader::join(field, key), "a number in [-0.999999, 0.999999]", inOpen);
  };
  std::vector<PhaseFunction> phases;
  if (type == "isotropic" || type == "rayleigh" || type == "penndorf") {
    in.object(value, field, "components.*.phase", type);
    const PhaseFunction p = type == "isotropic" ? PhaseFunction::isotropic()
                            : type == "rayleigh" ? PhaseFunction::rayleigh()
                                                 : PhaseFunction::penndorf();
    phases.assign(n, p);
  } else if (type == "henyey-greenstein" || type == "cornette-shanks") {
    in.object(value, field, "components.*.phase", type);
    for (double gi : g("g"))
      phases.push_back(type == "henyey-greenstein" ? PhaseFunction::henyeyGreenstein(gi)
                                                   : PhaseFunction::cornetteShanks(gi));
  } else if (type == "double-henyey-greenstein") {
    in.object(value, field, "components.*.phase", type);
    const std::vector<double> g1 = g("g1"), g2 = g("g2");
    const std::vector<double> alpha =
        in.spectrum(in.require(value, "alpha", field), field + ".alpha", "a number in [0, 1]", unit);
    for (std::size_t i = 0; i < n; ++i) phases.push_back(PhaseFunction::doubleHenyeyGreenstein(g1[i], g2[i], alpha[i]));
  } else if (type == "tabulated") {
    in.object(value, field, "components.*.phase", type);
    const bool byAngle = value.contains("anglesDeg");
    if (byAngle == value.contains("cosTheta")) in.fail(field, "expected exactly one of 'cosTheta' and 'anglesDeg'");
    const std::string axisKey = byAngle ? "anglesDeg" : "cosTheta";
    const std::vector<double> axis = in.numbers(value[axisKey], field + "." + axisKey);
    const json& values = in.require(value, "values", field);
    auto make = [&](const std::vector<double>& v, const std::string& valuesField) {
      try {
        return byAngle ? PhaseFunction::tabulatedDegrees(axis, v) : PhaseFunction::tabulated(axis, v);
      } catch (const std::invalid_argument& e) {
        in.fail(valuesField, e.what());
      }
    };
    if (!value.contains("wavelengthsNm")) {
      phases.assign(n, make(in.numbers(values, field + ".values"), field));
    } else {
      // one table per wavelength; between them the normalised tables are mixed linearly
      const std::vector<double> lambdas = in.numbers(value["wavelengthsNm"], field + ".wavelengthsNm");
      if (!values.is_array() || values.size() != lambdas.size())
        in.fail(field + ".values", "expected one array of values per wavelength (" +
                                       std::to_string(lambdas.size()) + "), " + got(values));
      std::vector<PhaseFunction> tables;
      for (std::size_t j = 0; j < lambdas.size(); ++j) {
        const std::string fj = field + ".values[" + std::to_string(j) + "]";
        if (!(lambdas[j] > 0.0) || (j > 0 && !(lambdas[j] > lambdas[j - 1])))
          in.fail(field + ".wavelengthsNm[" + std::to_string(j) + "]",
                  "expected strictly increasing positive wavelengths, got " + number(lambdas[j]));
        tables.push_back(make(in.numbers(values[j], fj), fj));
      }
      for (double lambda : in.wavelengths()) {
        WavelengthTable weight;
        weight.wavelengthsNm = lambdas;
        std::vector<double> w;
        for (std::size_t j = 0; j < tables.size(); ++j) {
          weight.values.assign(lambdas.size(), 0.0);
          weight.values[j] = 1.0;
          w.push_back(weight.at(lambda));
        }
        phases.push_back(PhaseFunction::mixture(tables, w));
      }
    }
  } else {
    in.fail(field + ".type",
            "expected one of: isotropic, rayleigh, penndorf, henyey-greenstein, double-henyey-greenstein, "
            "cornette-shanks, tabulated, " +
                got(value["type"]));
  }
  return phases;
}

Component parseComponent(const Reader& in, const std::string& name, const json& value, const std::string& field) {
  in.object(value, field, "components.*");
  if (value.contains("aerosol") && !value["aerosol"].is_boolean())
    in.fail(field + ".aerosol", "expected true or false, " + got(value["aerosol"]));
  Component c;
  c.name = name;
  c.density = parseProfile(in, in.require(value, "density", field), field + ".density");
  const double scale = value.contains("densityScale")
                           ? in.positive(value["densityScale"], field + ".densityScale", "factor")
                           : 1.0;
  Optics o = parseOptics(in, in.require(value, "optics", field), field + ".optics");
  for (double& b : o.scattering) b *= scale;
  for (double& b : o.absorption) b *= scale;
  c.scatteringPerM = std::move(o.scattering);
  c.absorptionPerM = std::move(o.absorption);
  if (value.contains("phase")) {
    c.phases = parsePhase(in, value["phase"], field + ".phase");
  } else if (!o.defaultPhase.empty()) {
    c.phases = std::move(o.defaultPhase);
  } else if (c.scatters()) {
    in.fail(field, "missing required key 'phase' (the component scatters)");
  } else {
    c.phases.assign(in.wavelengths().size(), PhaseFunction::isotropic());
  }
  const std::string problem = c.validate(in.wavelengths().size());
  if (!problem.empty()) in.failWithKey(field, problem);
  return c;
}

/// "aerosolOpticalDepth550": the components marked "aerosol" scaled together (their ratios
/// kept) so that their vertical extinction optical depth from the ground to the top at
/// 550 nm is the document's (each computed at 550 nm as well, whatever the run's
/// wavelengths).
void scaleAerosols(const Reader& in, const json& doc, Atmosphere& a) {
  const double target = in.number(doc["aerosolOpticalDepth550"], "aerosolOpticalDepth550",
                                  "an optical depth in [0, 10]", [](double x) { return x >= 0.0 && x <= 10.0; });
  // At 550 nm: the load's own coefficients when it has that wavelength, else the component
  // read once more there.
  const auto own = std::find(a.wavelengthsNm.begin(), a.wavelengthsNm.end(), 550.0);
  const Reader at550 = in.withWavelengths({550.0});
  Atmosphere probe;
  probe.bottomRadiusM = a.bottomRadiusM, probe.topRadiusM = a.topRadiusM, probe.wavelengthsNm = {550.0};
  double tau = 0.0;
  std::vector<Component*> aerosols;
  for (const auto& item : doc["components"].items()) {
    if (!item.value().value("aerosol", false)) continue;
    for (Component& mine : a.components)
      if (mine.name == item.key()) aerosols.push_back(&mine);
    if (own != a.wavelengthsNm.end()) {
      tau += a.verticalOpticalDepth(*aerosols.back(), 0.0, a.thicknessM())[own - a.wavelengthsNm.begin()];
      continue;
    }
    const Component c = parseComponent(at550, item.key(), item.value(), "components." + item.key());
    tau += probe.verticalOpticalDepth(c, 0.0, probe.thicknessM()).front();
  }
  if (aerosols.empty()) in.fail("aerosolOpticalDepth550", "no component has \"aerosol\": true to scale");
  if (!(tau > 0.0)) in.fail("aerosolOpticalDepth550", "the \"aerosol\" components have no extinction at 550 nm");
  const double f = target / tau;
  for (Component* c : aerosols) {
    for (double& b : c->scatteringPerM) b *= f;
    for (double& b : c->absorptionPerM) b *= f;
  }
}

Atmosphere build(const Reader& in, const json& doc, const std::string& defaultName) {
  in.object(doc, "", "");
  Atmosphere a;
  a.wavelengthsNm = in.wavelengths();
  a.name = doc.contains("name") ? in.string(doc["name"], "name") : defaultName;
  if (doc.contains("description")) in.string(doc["description"], "description");
  a.bottomRadiusM = in.number(in.require(doc, "bottomRadiusM", ""), "bottomRadiusM", "a radius from 1 m to 1e12 m",
                              [](double x) { return x >= kMinRadiusM && x <= kMaxRadiusM; });
  const json& top = in.require(doc, "topRadiusM", "");
  a.topRadiusM = in.number(top, "topRadiusM", "a radius from 1 m to 1e12 m", [](double x) {
    return x >= kMinRadiusM && x <= kMaxRadiusM;
  });
  if (!(a.topRadiusM >= a.bottomRadiusM + 1.0))
    in.fail("topRadiusM", "expected a radius at least 1 m above bottomRadiusM (" + number(a.bottomRadiusM) + "), " +
                              got(top));
  a.groundAlbedo = doc.contains("groundAlbedo")
                       ? in.spectrum(doc["groundAlbedo"], "groundAlbedo", "an albedo in [0, 1]",
                                     [](double x) { return x >= 0.0 && x <= 1.0; })
                       : std::vector<double>(a.wavelengthsNm.size(), 0.1);

  const json& components = in.require(doc, "components", "");
  if (!components.is_object() || components.empty())
    in.fail("components", "expected a non-empty object of named components, " + got(components));
  const Reader air = in.withHumidity(doc.contains("relativeHumidity")
                                         ? in.number(doc["relativeHumidity"], "relativeHumidity",
                                                     "a relative humidity in [0, 0.99]",
                                                     [](double x) { return x >= 0.0 && x <= 0.99; })
                                         : 0.0)
                        .withBoundaryLayer(doc.contains("boundaryLayerHeightM")
                                               ? in.number(doc["boundaryLayerHeightM"], "boundaryLayerHeightM",
                                                           "a height in (0, 100000] m",
                                                           [](double x) { return x > 0.0 && x <= 1e5; })
                                               : kDefaultBoundaryLayerHeightM);
  for (const auto& item : components.items()) {
    if (item.key().empty()) in.fail("components", "expected non-empty component names");
    a.components.push_back(parseComponent(air, item.key(), item.value(), "components." + item.key()));
  }
  if (doc.contains("aerosolOpticalDepth550")) scaleAerosols(air, doc, a);

  a.refractivityFollows.clear();
  if (doc.contains("refraction")) {
    const json& r = doc["refraction"];
    in.object(r, "refraction", "refraction");
    a.seaLevelRefractivity = in.number(in.require(r, "seaLevelRefractivity", "refraction"), "refraction.seaLevelRefractivity",
                                       "n - 1, a number in [0, 1)", [](double x) { return x >= 0.0 && x < 1.0; });
    if (r.contains("referenceWavelengthNm"))
      a.refractivityReferenceWavelengthNm =
          in.positive(r["referenceWavelengthNm"], "refraction.referenceWavelengthNm", "wavelength in nm");
    if (r.contains("dispersion")) {
      const std::string d = in.string(r["dispersion"], "refraction.dispersion");
      if (d == "none") a.dispersion = Dispersion::None;
      else if (d == "peck-reeder-1972") a.dispersion = Dispersion::PeckReeder1972Air;
      else if (d == "bideau-mehu-1973-co2") a.dispersion = Dispersion::BideauMehu1973CO2;
      else in.fail("refraction.dispersion", "expected one of: none, peck-reeder-1972, bideau-mehu-1973-co2, " + got(r["dispersion"]));
    }
    a.refractivityFollows = r.contains("followsComponent") ? in.string(r["followsComponent"], "refraction.followsComponent")
                                                           : std::string("molecules");
    if (a.find(a.refractivityFollows) == nullptr) {
      std::vector<std::string> names;
      for (const Component& c : a.components) names.push_back(c.name);
      in.fail("refraction.followsComponent",
              "expected the name of a component (" + join(names) + "), got '" + a.refractivityFollows + "'");
    }
  }
  const std::string problem = a.validate();
  if (!problem.empty()) in.failWithKey("", problem);
  return a;
}

void checkWavelengths(const std::vector<double>& wavelengthsNm, const std::string& file) {
  if (wavelengthsNm.empty()) throw AtmosphereError(file + ": wavelengthsNm: expected at least one wavelength");
  for (std::size_t i = 0; i < wavelengthsNm.size(); ++i)
    if (!std::isfinite(wavelengthsNm[i]) || !(wavelengthsNm[i] > 0.0))
      throw AtmosphereError(file + ": wavelengthsNm[" + std::to_string(i) + "]: expected a positive wavelength in nm, got " +
                            number(wavelengthsNm[i]));
}


std::atomic<long> gDocumentsRead{0};

// The resolved document of JSON text (counted: AtmosphereModel::documentsRead).
json readDocument(const std::string& jsonText, const std::string& sourceName, const std::string& baseDirectory) {
  ++gDocumentsRead;
  return resolveExtends(parseJson(jsonText, sourceName), sourceName, baseDirectory, 0);
}

Atmosphere buildFrom(const json& doc, const std::string& sourceName, const std::vector<double>& wavelengthsNm) {
  checkWavelengths(wavelengthsNm, sourceName);
  const Reader in(sourceName, wavelengthsNm);
  Atmosphere a = build(in, doc, fs::path(sourceName).stem().string());
  a.source = sourceName;
  return a;
}

std::string atmospherePath(const std::string& presetNameOrPath) {
  if (looksLikePath(presetNameOrPath)) return presetNameOrPath;
  const std::string path = (fs::path(presetDirectory()) / (presetNameOrPath + ".json")).string();
  if (presetNameOrPath.empty() || !fs::exists(path)) throw AtmosphereError(unknownPresetMessage(presetNameOrPath));
  return path;
}

}  // namespace

Atmosphere parseAtmosphere(const std::string& jsonText, const std::string& sourceName,
                           const std::vector<double>& wavelengthsNm, const std::string& baseDirectory) {
  checkWavelengths(wavelengthsNm, sourceName);
  return buildFrom(readDocument(jsonText, sourceName, baseDirectory), sourceName, wavelengthsNm);
}

Atmosphere loadAtmosphere(const std::string& presetNameOrPath, const std::vector<double>& wavelengthsNm) {
  const std::string path = atmospherePath(presetNameOrPath);
  return parseAtmosphere(readFile(path), path, wavelengthsNm, fs::path(path).parent_path().string());
}

std::string resolvedAtmosphereJson(const std::string& presetNameOrPath) {
  const std::string path = atmospherePath(presetNameOrPath);
  return readDocument(readFile(path), path, fs::path(path).parent_path().string()).dump(2);
}

// ---- the carrier ------------------------------------------------------------------------

struct AtmosphereModel::Document {
  json doc;
  std::string source;  // the file (or the editor's source name)
};

AtmosphereModel::AtmosphereModel(std::string name, std::shared_ptr<const Document> doc)
    : name_(std::move(name)), doc_(std::move(doc)) {}

std::shared_ptr<const AtmosphereModel> AtmosphereModel::load(const std::string& presetNameOrPath) {
  const std::string path = atmospherePath(presetNameOrPath);
  auto doc = std::make_shared<Document>();
  doc->doc = readDocument(readFile(path), path, fs::path(path).parent_path().string());
  doc->source = path;
  auto model = std::make_shared<const AtmosphereModel>(presetNameOrPath, std::move(doc));
  model->rgb();  // checked where it is named
  return model;
}

std::shared_ptr<const AtmosphereModel> AtmosphereModel::fromText(const std::string& jsonText,
                                                                 const std::string& sourceName,
                                                                 const std::string& baseDirectory) {
  auto doc = std::make_shared<Document>();
  doc->doc = readDocument(jsonText, sourceName, baseDirectory);
  doc->source = sourceName;
  auto model = std::make_shared<const AtmosphereModel>(sourceName, std::move(doc));
  model->rgb();
  return model;
}

const Atmosphere& AtmosphereModel::at(const std::vector<double>& wavelengthsNm) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = built_[wavelengthsNm];
  if (!slot) slot = std::make_unique<const Atmosphere>(buildFrom(doc_->doc, doc_->source, wavelengthsNm));
  return *slot;
}

const Atmosphere& AtmosphereModel::rgb() const { return at(WavelengthSet::rgb().nm); }

std::string AtmosphereModel::resolvedJson() const { return doc_->doc.dump(2); }

AtmosphereModelPtr modelNamed(const std::string& name, AtmosphereModelPtr& kept) {
  if (name.empty()) return nullptr;
  if (!kept || kept->name() != name) kept = AtmosphereModel::load(name);
  return kept;
}

long AtmosphereModel::documentsRead() { return gDocumentsRead.load(); }

}  // namespace umbra::atmosphere
