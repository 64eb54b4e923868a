// The reading of atmosphere files: JSON -> validated Atmosphere (format:
// docs/atmosphere-format.md), and AtmosphereModel, the carrier that reads a file once.
#include "JsonErrors.hpp"
#include "Atmosphere.hpp"
#include "AtmosphereModel.hpp"
#include "Fields.hpp"
#include "Humidity.hpp"
#include "Mie.hpp"
#include "MieCache.hpp"
#include "Spectrum.hpp"

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

using json = nlohmann::ordered_json;

std::string number(double x) {
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

std::string got(const json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return "got " + text;
}

std::string join(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& s : items) list += (list.empty() ? "" : ", ") + s;
  return list;
}

bool looksLikePath(const std::string& s) {
  return s.find('/') != std::string::npos ||
         (s.size() > 5 && s.compare(s.size() - 5, 5, ".json") == 0);
}

/// Reads typed values out of the JSON tree; every failure names the file and the field.
class Reader {
public:
  Reader(std::string file, const std::vector<double>& wavelengthsNm)
      : file_(std::move(file)), wavelengths_(wavelengthsNm) {}

  const std::vector<double>& wavelengths() const { return wavelengths_; }
  /// The air's relative humidity (the document's "relativeHumidity"; 0 until it is read).
  double relativeHumidity() const { return relativeHumidity_; }
  Reader withHumidity(double relativeHumidity) const {
    Reader r = *this;
    r.relativeHumidity_ = relativeHumidity;
    return r;
  }
  Reader withWavelengths(const std::vector<double>& wavelengthsNm) const {
    Reader r = *this;
    r.wavelengths_ = wavelengthsNm;
    return r;
  }
  /// The top of the boundary (mixing) layer, the document's "boundaryLayerHeightM".
  double boundaryLayerHeightM() const { return boundaryLayerHeightM_; }
  Reader withBoundaryLayer(double heightM) const {
    Reader r = *this;
    r.boundaryLayerHeightM_ = heightM;
    return r;
  }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw AtmosphereError(file_ + ": " + (field.empty() ? "" : field + ": ") + message);
  }

  /// Fails on a key that is not listed: a value's own form (a spectrum's object), not an
  /// object of the field table.
  void object(const json& value, const std::string& field, std::initializer_list<const char*> keys) const {
    if (!value.is_object()) fail(field, "expected an object, " + got(value));
    if (const auto unknown = atmosphere::firstUnknownKey(value, keys))
      fail(field.empty() ? unknown->key : field + "." + unknown->key, unknown->message);
  }

  /// Fails on a key that the field table (Fields.hpp, fieldKeys) does not describe for an
  /// object at `where` whose selector value is `type` ("" for none).
  void object(const json& value, const std::string& field, const char* where, const std::string& type = "") const {
    if (!value.is_object()) fail(field, "expected an object, " + got(value));
    if (const auto unknown = atmosphere::firstUnknownKey(value, fieldKeys(where, type)))
      fail(field.empty() ? unknown->key : field + "." + unknown->key, unknown->message);
  }

  const json& require(const json& object, const char* key, const std::string& field) const {
    if (!object.contains(key)) fail(field, std::string("missing required key '") + key + "'");
    return object[key];
  }

  static std::string join(const std::string& field, const std::string& key) {
    return field.empty() ? key : field + "." + key;
  }

  std::string string(const json& value, const std::string& field) const {
    if (!value.is_string() || value.get<std::string>().empty())
      fail(field, "expected a non-empty string, " + got(value));
    return value.get<std::string>();
  }

  /// A finite number that passes `ok`; `expected` says what passes.
  double number(const json& value, const std::string& field, const std::string& expected,
                const std::function<bool(double)>& ok) const {
    if (!value.is_number()) fail(field, "expected " + expected + ", " + got(value));
    const double x = value.get<double>();
    if (!std::isfinite(x) || !ok(x)) fail(field, "expected " + expected + ", " + got(value));
    return x;
  }

  double positive(const json& value, const std::string& field, const std::string& what) const {
    return number(value, field, "a positive " + what, [](double x) { return x > 0.0; });
  }

  std::vector<double> numbers(const json& value, const std::string& field) const {
    if (!value.is_array()) fail(field, "expected an array of numbers, " + got(value));
    std::vector<double> out;
    for (std::size_t i = 0; i < value.size(); ++i)
      out.push_back(number(value[i], field + "[" + std::to_string(i) + "]", "a finite number",
                           [](double) { return true; }));
    return out;
  }

  /// A number (the same at every wavelength) or {"wavelengthsNm": [...], "values": [...]}
  /// (linear in between, the end values beyond), evaluated at the load's wavelengths; each
  /// value must pass `ok`.
  std::vector<double> spectrum(const json& value, const std::string& field, const std::string& expected,
                               const std::function<bool(double)>& ok) const {
    if (value.is_number()) {
      const double x = number(value, field, expected, ok);
      return std::vector<double>(wavelengths_.size(), x);
    }
    if (!value.is_object())
      fail(field, "expected " + expected + " or {\"wavelengthsNm\": [...], \"values\": [...]}, " + got(value));
    object(value, field, {"wavelengthsNm", "values"});
    WavelengthTable table;
    table.wavelengthsNm = numbers(require(value, "wavelengthsNm", field), field + ".wavelengthsNm");
    table.values = numbers(require(value, "values", field), field + ".values");
    const std::string problem = table.validate(/*allowNegative=*/true);
    if (!problem.empty()) failWithKey(field, problem);
    for (std::size_t i = 0; i < table.values.size(); ++i)
      if (!ok(table.values[i]))
        fail(field + ".values[" + std::to_string(i) + "]",
             "expected " + expected + ", got " + atmosphere::number(table.values[i]));
    return table.at(wavelengths_);
  }

  /// "key: message" (from a validate()) -> fail(field.key, message).
  [[noreturn]] void failWithKey(const std::string& field, const std::string& problem) const {
    const std::size_t colon = problem.find(": ");
    if (colon == std::string::npos) fail(field, problem);
    fail(join(field, problem.substr(0, colon)), problem.substr(colon + 2));
  }

private:
  std::string file_;
  std::vector<double> wavelengths_;
  double relativeHumidity_ = 0.0;
  double boundaryLayerHeightM_ = kDefaultBoundaryLayerHeightM;
};

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

/// The "mie" model's phase table: every 0.5 degrees (the forward peak of micron-sized
/// dust is ~3 degrees wide at 440 nm), and the size quadrature's tolerances (relative
/// change of one halving; Mie.hpp): bulk coefficients to ~1e-4, phase samples to ~1e-2.
/// Martian dust (r_eff 1.5 um, v_eff 0.3) then takes 1000-2000 radius nodes a wavelength
/// instead of 5000-14000 (docs/accuracy-vs-speed/atmosphere-tables.md, "Mars' dust by Lorenz-Mie").
constexpr int kMiePhaseSamples = 361;
constexpr double kMieBulkTolerance = 1e-4, kMiePhaseTolerance = 1e-2;

struct Optics {
  std::vector<double> scattering, absorption;
  /// The phase the model implies (Rayleigh; Lorenz-Mie's table), used when the component
  /// names none; empty: none.
  std::vector<PhaseFunction> defaultPhase;
};

/// The refractive-index part of a "rayleigh" model: n - 1 per wavelength and the number
/// density it holds at.
std::pair<std::vector<double>, double> parseRefractiveIndex(const Reader& in, const json& value,
                                                            const std::string& field) {
  const auto positiveN = [](double x) { return x > 0.0; };
  if (!value.is_object()) in.fail(field, "expected an object, " + got(value));
  std::vector<double> refractivity;
  double atN = kStandardNumberDensityPerM3;
  in.object(value, field, "components.*.optics.refractiveIndex");
  if (value.contains("formula") && value.contains("refractivity"))
    in.fail(field, "expected one of 'formula' and 'refractivity', not both");
  if (value.contains("formula")) {
    const std::string formula = in.string(value["formula"], field + ".formula");
    double lo = 0.0, hi = 0.0;
    std::function<double(double)> f;
    if (formula == "peck-reeder-1972") {
      lo = 230.0, hi = 1690.0, f = airRefractivityPeckReeder;
    } else if (formula == "bideau-mehu-1973-co2") {
      lo = 180.0, hi = 1700.0, f = co2RefractivityBideauMehu;
    } else {
      in.fail(field + ".formula", "expected one of: peck-reeder-1972, bideau-mehu-1973-co2, " +
                                      got(value["formula"]));
    }
    for (double lambda : in.wavelengths()) {
      if (lambda < lo || lambda > hi)
        in.fail(field + ".formula", "wavelength " + number(lambda) + " nm is outside the formula's range (" +
                                        number(lo) + "-" + number(hi) + " nm)");
      refractivity.push_back(f(lambda));
    }
    if (value.contains("atNumberDensityPerM3"))
      atN = in.positive(value["atNumberDensityPerM3"], field + ".atNumberDensityPerM3", "number density in 1/m^3");
  } else {
    refractivity = in.spectrum(in.require(value, "refractivity", field), field + ".refractivity",
                               "n - 1, a positive number below 1", [](double r) { return r > 0.0 && r < 1.0; });
    atN = in.number(in.require(value, "atNumberDensityPerM3", field), field + ".atNumberDensityPerM3",
                    "a positive number density in 1/m^3", positiveN);
  }
  return {refractivity, atN};
}

/// The size distribution of a "mie" model: one radius (effectiveRadiusM: <r^3>/<r^2>, or
/// medianRadiusM: the number distribution's median, OPAC's mode radius) and at most one
/// width (effectiveVariance, or geometricStdDev sigma_g; none: one radius), cut to
/// radiusRangeM [min, max] when given, N from numberDensityPerM3.
LogNormalSizes parseMieSizes(const Reader& in, const json& value, const std::string& field) {
  auto key = [&](const char* k) { return Reader::join(field, k); };
  const bool byMedian = value.contains("medianRadiusM");
  if (byMedian == value.contains("effectiveRadiusM"))
    in.fail(field, "expected exactly one of 'effectiveRadiusM' and 'medianRadiusM'");
  if (value.contains("effectiveVariance") && value.contains("geometricStdDev"))
    in.fail(field, "expected at most one of 'effectiveVariance' and 'geometricStdDev'");
  const char* radiusKey = byMedian ? "medianRadiusM" : "effectiveRadiusM";
  const double r = in.number(value[radiusKey], key(radiusKey),
                             byMedian ? "a median radius in (0, 2e-5] m" : "an effective radius in (0, 2e-5] m",
                             [](double x) { return x > 0.0 && x <= 2e-5; });
  // The width as given: v_eff, or sigma_g (v_eff = exp(ln^2 sigma_g) - 1; Mie.hpp).
  double vEff = 0.0, sigma = 1.0;
  if (value.contains("effectiveVariance")) {
    vEff = in.number(value["effectiveVariance"], key("effectiveVariance"), "an effective variance in [0, 2]",
                     [](double x) { return x >= 0.0 && x <= 2.0; });
    sigma = std::exp(std::sqrt(std::log1p(vEff)));
  }
  if (value.contains("geometricStdDev")) {
    sigma = in.number(value["geometricStdDev"], key("geometricStdDev"), "a geometric standard deviation in [1, 5]",
                      [](double x) { return x >= 1.0 && x <= 5.0; });
    vEff = std::expm1(std::log(sigma) * std::log(sigma));
  }
  const double N = in.number(in.require(value, "numberDensityPerM3", field), key("numberDensityPerM3"),
                             "a number density above 0, at most 1e35 in 1/m^3",
                             [](double x) { return x > 0.0 && x <= 1e35; });
  LogNormalSizes sizes = byMedian ? LogNormalSizes{r, sigma, N} : logNormalFromEffective(r, vEff, N);
  if (value.contains("radiusRangeM")) {
    const std::vector<double> range = in.numbers(value["radiusRangeM"], key("radiusRangeM"));
    if (range.size() != 2 || !(range[0] >= 0.0) || !(range[1] > range[0]) || !(range[1] <= 1e-3))
      in.fail(key("radiusRangeM"), "expected [min, max] radii in m, 0 <= min < max <= 1e-3");
    sizes.minRadiusM = range[0], sizes.maxRadiusM = range[1];
  }
  return sizes;
}

/// r_wet / r_dry of a "mie" model's "hygroscopicGrowth" rows at the air's relative humidity.
double parseGrowth(const Reader& in, const json& value, const std::string& field) {
  in.object(value, field, "components.*.optics.hygroscopicGrowth");
  const std::vector<double> humidity = in.numbers(in.require(value, "relativeHumidity", field),
                                                  Reader::join(field, "relativeHumidity"));
  const std::vector<double> factor = in.numbers(in.require(value, "radiusFactor", field),
                                                Reader::join(field, "radiusFactor"));
  try {
    return growthFactor(humidity, factor, in.relativeHumidity());
  } catch (const std::invalid_argument& e) {
    in.failWithKey(field, e.what());
  }
}

Optics parseOptics(const Reader& in, const json& value, const std::string& field) {
  if (!value.is_object()) in.fail(field, "expected an object, " + got(value));
  if (value.contains("description")) {  // free text, as a component's
    in.string(value["description"], field + ".description");
    json rest = value;
    rest.erase("description");
    return parseOptics(in, rest, field);
  }
  const std::string model = in.string(in.require(value, "model", field), field + ".model");
  const std::vector<double>& lambdas = in.wavelengths();
  const std::size_t n = lambdas.size();
  const auto nonNegative = [](double x) { return x >= 0.0; };
  const auto positive = [](double x) { return x > 0.0; };
  // Coefficients at most 1 per metre and number densities at most 1e35 per cubic metre
  // (air at sea level: 1e-5 /m, 2.5e25 /m^3): beyond them the tables overflow.
  const std::string coefficient = "a coefficient from 0 to 1 in 1/m";
  const auto coefficientRange = [](double x) { return x >= 0.0 && x <= 1.0; };
  auto key = [&](const char* k) { return Reader::join(field, k); };
  auto density = [&](const char* k) {
    return in.number(in.require(value, k, field), key(k), "a number density above 0, at most 1e35 in 1/m^3",
                     [](double x) { return x > 0.0 && x <= 1e35; });
  };
  auto optionalSpectrum = [&](const char* k) {
    return value.contains(k) ? in.spectrum(value[k], key(k), coefficient, coefficientRange) : std::vector<double>(n, 0.0);
  };
  auto vanDeHulst = [&](const json& v, const std::string& f) {
    const double turbidity = in.number(in.require(v, "turbidity", f), Reader::join(f, "turbidity"),
                                       "a turbidity >= 1", [](double t) { return t >= 1.0; });
    const double nu = in.number(in.require(v, "jungeExponent", f), Reader::join(f, "jungeExponent"),
                                "a Junge exponent in [2, 6]", [](double x) { return x >= 2.0 && x <= 6.0; });
    const std::vector<double> K = in.spectrum(in.require(v, "K", f), Reader::join(f, "K"), "a number >= 0", nonNegative);
    std::vector<double> beta(n);
    for (std::size_t i = 0; i < n; ++i) beta[i] = vanDeHulstScatteringPerM(turbidity, nu, K[i], lambdas[i]);
    return beta;
  };

  Optics o;
  if (model == "rayleigh") {
    in.object(value, field, "components.*.optics", model);
    const auto [refractivity, atN] = parseRefractiveIndex(in, in.require(value, "refractiveIndex", field), key("refractiveIndex"));
    const double N = density("numberDensityPerM3");
    const double delta = in.number(in.require(value, "depolarisation", field), key("depolarisation"),
                                   "a depolarisation factor in [0, 0.5]", [](double d) { return d >= 0.0 && d <= 0.5; });
    for (std::size_t i = 0; i < n; ++i)
      o.scattering.push_back(rayleighCrossSectionM2(refractivity[i], atN, lambdas[i], delta) * N);
    o.absorption.assign(n, 0.0);
    o.defaultPhase.assign(n, PhaseFunction::rayleigh());
  } else if (model == "absorber") {
    in.object(value, field, "components.*.optics", model);
    const double N = density("numberDensityPerM3");
    const std::vector<double> sigma =
        in.spectrum(in.require(value, "crossSectionM2", field), key("crossSectionM2"), "a cross-section >= 0 in m^2", nonNegative);
    o.scattering.assign(n, 0.0);
    for (double s : sigma) o.absorption.push_back(N * s);
  } else if (model == "coefficients") {
    in.object(value, field, "components.*.optics", model);
    o.scattering = in.spectrum(in.require(value, "scatteringPerM", field), key("scatteringPerM"), coefficient, coefficientRange);
    o.absorption = optionalSpectrum("absorptionPerM");
  } else if (model == "van-de-hulst") {
    in.object(value, field, "components.*.optics", model);
    o.scattering = vanDeHulst(value, field);
    o.absorption = optionalSpectrum("absorptionPerM");
  } else if (model == "anomalous-diffraction") {
    in.object(value, field, "components.*.optics", model);
    const double r = in.number(in.require(value, "radiusM", field), key("radiusM"),
                               "a particle radius in (0, 0.01] m", [](double x) { return x > 0.0 && x <= 0.01; });
    const double N = density("numberDensityPerM3");
    const std::vector<double> m = in.spectrum(in.require(value, "refractiveIndexReal", field), key("refractiveIndexReal"),
                                              "a real refractive index > 1", [](double x) { return x > 1.0; });
    const std::vector<double> k =
        in.spectrum(in.require(value, "refractiveIndexImag", field), key("refractiveIndexImag"),
                    "an imaginary refractive index >= 0", nonNegative);
    std::vector<double> extinction(n);
    for (std::size_t i = 0; i < n; ++i)
      extinction[i] = anomalousDiffractionExtinctionPerM(r, m[i], k[i], N, lambdas[i]);
    if (value.contains("vanDeHulst")) {
      // Costa's combination: scattering from Eq. 17, extinction from Eq. 20.
      const std::string f = key("vanDeHulst");
      in.object(value["vanDeHulst"], f, "components.*.optics.vanDeHulst");
      o.scattering = vanDeHulst(value["vanDeHulst"], f);
      for (std::size_t i = 0; i < n; ++i) {
        if (o.scattering[i] > extinction[i] * (1.0 + 1e-12))
          in.fail(f, "at " + number(lambdas[i]) + " nm the Eq. 17 scattering " + number(o.scattering[i]) +
                         " 1/m exceeds the Eq. 20 extinction " + number(extinction[i]) + " 1/m");
        o.absorption.push_back(std::max(0.0, extinction[i] - o.scattering[i]));
      }
    } else {
      constexpr double kPi = 3.14159265358979323846;
      for (std::size_t i = 0; i < n; ++i) {
        const double absorption = kPi * r * r * anomalousDiffractionAbsorptionEfficiency(r, k[i], lambdas[i]) * N;
        o.absorption.push_back(std::min(absorption, extinction[i]));
        o.scattering.push_back(extinction[i] - o.absorption.back());
      }
    }
  } else if (model == "mie") {
    in.object(value, field, "components.*.optics", model);
    LogNormalSizes sizes = parseMieSizes(in, value, field);
    const std::vector<double> m = in.spectrum(in.require(value, "refractiveIndexReal", field), key("refractiveIndexReal"),
                                              "a real refractive index > 0", positive);
    const std::vector<double> k =
        in.spectrum(in.require(value, "refractiveIndexImag", field), key("refractiveIndexImag"),
                    "an imaginary refractive index >= 0", nonNegative);
    // In humid air a hygroscopic particle grows and its index moves towards water's.
    const double growth = value.contains("hygroscopicGrowth")
                              ? parseGrowth(in, value["hygroscopicGrowth"], key("hygroscopicGrowth"))
                              : 1.0;
    sizes.medianRadiusM *= growth, sizes.minRadiusM *= growth, sizes.maxRadiusM *= growth;
    // The wavelengths in parallel, each through the Lorenz-Mie cache (MieCache.hpp).
    // The first wavelength's error, as a loop in order would give it.
    std::vector<MieAerosol> optics(n);
    std::vector<std::exception_ptr> failures(n);
#pragma omp parallel for schedule(dynamic)
    for (std::size_t i = 0; i < n; ++i) {
      try {
        const std::complex<double> index =
            humidRefractiveIndex({m[i], k[i]}, waterRefractiveIndexReal(lambdas[i]), growth);
        optics[i] = cachedMieLogNormal(lambdas[i] * 1e-9, index, sizes, kMiePhaseSamples, 0, kMieBulkTolerance,
                                       kMiePhaseTolerance);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
    for (const std::exception_ptr& failure : failures)
      if (failure) std::rethrow_exception(failure);
    for (const MieAerosol& a : optics) {
      o.scattering.push_back(a.scatteringPerM);
      o.absorption.push_back(a.absorptionPerM);
      o.defaultPhase.push_back(PhaseFunction::tabulated(a.cosTheta, a.phase));
    }
  } else if (model == "mixture") {
    // Populations sharing one density profile (an OPAC aerosol type): their coefficients
    // add, their phase functions mix weighted by their scattering.
    in.object(value, field, "components.*.optics", model);
    const json& of = in.require(value, "of", field);
    if (!of.is_object() || of.empty()) in.fail(key("of"), "expected a non-empty object of named optics, " + got(of));
    std::vector<Optics> parts;
    for (const auto& item : of.items()) {
      const std::string f = key("of") + "." + item.key();
      parts.push_back(parseOptics(in, item.value(), f));
      const Optics& part = parts.back();
      if (part.defaultPhase.empty() && std::any_of(part.scattering.begin(), part.scattering.end(), positive))
        in.fail(f, "expected a model with its own phase function in a mixture (rayleigh, mie), got '" +
                       in.string(item.value()["model"], f + ".model") + "'");
    }
    o.scattering.assign(n, 0.0), o.absorption.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<PhaseFunction> phases;
      std::vector<double> weights;
      for (const Optics& part : parts) {
        o.scattering[i] += part.scattering[i], o.absorption[i] += part.absorption[i];
        if (part.defaultPhase.empty()) continue;
        phases.push_back(part.defaultPhase[i]);
        weights.push_back(part.scattering[i]);
      }
      o.defaultPhase.push_back(o.scattering[i] > 0.0 ? PhaseFunction::mixture(phases, weights)
                                                     : PhaseFunction::isotropic());
    }
  } else {
    in.fail(key("model"), "expected one of: rayleigh, absorber, coefficients, van-de-hulst, anomalous-diffraction, mie, "
                          "mixture, " + got(value["model"]));
  }
  return o;
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
