#pragma once
// Inside the atmosphere library, not a public header: the reading of an atmosphere file's
// JSON. The Reader checks each value and names the file and the field in its errors;
// AtmosphereReader.cpp reads the document with it, reader/Optics.cpp the optics.
#include "Atmosphere.hpp"
#include "Components.hpp"
#include "Fields.hpp"
#include "JsonErrors.hpp"
#include "Phase.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

namespace umbra::atmosphere::reader {

using json = nlohmann::ordered_json;

inline std::string number(double x) {
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

inline std::string got(const json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return "got " + text;
}

inline std::string join(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& s : items) list += (list.empty() ? "" : ", ") + s;
  return list;
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
             "expected " + expected + ", got " + reader::number(table.values[i]));
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

/// An "optics" object's coefficients at the load's wavelengths.
struct Optics {
  std::vector<double> scattering, absorption;
  /// The phase the model implies (Rayleigh; Lorenz-Mie's table), used when the component
  /// names none; empty: none.
  std::vector<PhaseFunction> defaultPhase;
};

/// An "optics" object (at `field`): one of the models of docs/atmosphere-format.md.
Optics parseOptics(const Reader& in, const json& value, const std::string& field);

}  // namespace umbra::atmosphere::reader
