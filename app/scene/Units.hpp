#pragma once
// Length units for scene files: "384400km", "1.5 au", "2e8m", "2e8" (metres).
#include <string>

namespace umbra::scene {

/// The astronomical unit in metres (IAU 2012 Resolution B2, exact).
inline constexpr double kAuM = 149597870700.0;

/// Parses a length with an optional unit (m, km, au; a bare number is metres) and
/// returns it in metres. Spaces around the number and the unit are allowed.
/// Negative values are accepted (callers check their ranges).
/// Throws std::invalid_argument quoting the text on anything else (empty text,
/// NaN/inf, unknown unit, trailing garbage).
double parseLengthM(const std::string& text);

/// The same for a duration in seconds: unit s, min, h or d (86400 s), required (a bare
/// number is an error: seconds, minutes or days?).
double parseDurationS(const std::string& text);

} // namespace umbra::scene
