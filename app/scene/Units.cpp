#include "scene/Units.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace umbra::scene {

namespace {

[[noreturn]] void throwBadLength(const std::string& text) {
  throw std::invalid_argument("invalid length '" + text +
                              "': expected a number with unit m, km or au");
}

bool isSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

} // namespace

double parseLengthM(const std::string& text) {
  std::size_t begin = 0;
  while (begin < text.size() && isSpace(text[begin])) ++begin;
  // strtod accepts "inf", "nan" and hex floats: insist on a plain decimal number.
  if (begin == text.size()) throwBadLength(text);
  const char first = text[begin];
  if (!(std::isdigit(static_cast<unsigned char>(first)) || first == '+' || first == '-' ||
        first == '.'))
    throwBadLength(text);
  for (std::size_t i = begin; i < text.size(); ++i)
    if (text[i] == 'x' || text[i] == 'X') throwBadLength(text);

  const char* start = text.c_str() + begin;
  char* end = nullptr;
  const double value = std::strtod(start, &end);
  if (end == start || !std::isfinite(value)) throwBadLength(text);

  std::string unit(end);
  while (!unit.empty() && isSpace(unit.front())) unit.erase(unit.begin());
  while (!unit.empty() && isSpace(unit.back())) unit.pop_back();

  if (unit.empty() || unit == "m") return value;
  if (unit == "km") return value * 1000.0;
  if (unit == "au") return value * kAuM;
  throwBadLength(text);
}

} // namespace umbra::scene
