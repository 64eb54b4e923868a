#pragma once
// Length units for scene files: "384400km", "1.5 au", "2e8m", "2e8" (metres).
#include <string>

namespace umbra::scene {

/// The astronomical unit in metres (IAU 2012 Resolution B2, exact).
inline constexpr double kAuM = 149597870700.0;

/// The physical limits every length read from the user keeps to: radii (and grid
/// spacings) from 1 m to 1e12 m, positions and distances up to 1e15 m (a hundred times
/// Neptune's distance).
inline constexpr double kMinRadiusM = 1.0;
inline constexpr double kMaxRadiusM = 1.0e12;
inline constexpr double kMaxDistanceM = 1.0e15;

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
