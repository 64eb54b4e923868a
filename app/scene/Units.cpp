#include "scene/Units.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <stdexcept>

namespace umbra::scene {

namespace {

bool isSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

/// A plain decimal number and its unit (trimmed); false for anything else.
bool splitQuantity(const std::string& text, double& value, std::string& unit) {
  std::size_t begin = 0;
  while (begin < text.size() && isSpace(text[begin])) ++begin;
  // strtod accepts "inf", "nan" and hex floats: insist on a plain decimal number.
  if (begin == text.size()) return false;
  const char first = text[begin];
  if (!(std::isdigit(static_cast<unsigned char>(first)) || first == '+' || first == '-' ||
        first == '.'))
    return false;
  for (std::size_t i = begin; i < text.size(); ++i)
    if (text[i] == 'x' || text[i] == 'X') return false;

  const char* start = text.c_str() + begin;
  char* end = nullptr;
  value = std::strtod(start, &end);
  if (end == start || !std::isfinite(value)) return false;

  unit = end;
  while (!unit.empty() && isSpace(unit.front())) unit.erase(unit.begin());
  while (!unit.empty() && isSpace(unit.back())) unit.pop_back();
  return true;
}

} // namespace

struct UnitFactor {
  const char* unit;  ///< "" for a bare number
  double factor;
};

double parseQuantity(const std::string& text, std::initializer_list<UnitFactor> units, const char* what,
                     const char* expected) {
  double value = 0.0;
  std::string unit;
  if (splitQuantity(text, value, unit)) {
    for (const UnitFactor& u : units)
      if (unit == u.unit) return value * u.factor;
  }
  throw std::invalid_argument(std::string("invalid ") + what + " '" + text + "': expected a number with unit " +
                              expected);
}

double parseLengthM(const std::string& text) {
  return parseQuantity(text, {{"", 1.0}, {"m", 1.0}, {"km", 1000.0}, {"au", kAuM}}, "length", "m, km or au");
}

double parseDurationS(const std::string& text) {
  // A unit is required: "15" could be seconds, minutes or days.
  return parseQuantity(text, {{"s", 1.0}, {"min", 60.0}, {"h", 3600.0}, {"d", 86400.0}}, "duration", "s, min, h or d");
}

} // namespace umbra::scene
