#pragma once
// UTC instants as ERFA two-part quasi Julian dates, and conversion to TT.
#include <string>

namespace umbra::scene {

/// A UTC instant as ERFA's two-part quasi Julian date (jd1 + jd2; see eraDtf2d).
struct UtcTime {
  double jd1 = 2451545.0; ///< usually the Julian day number part
  double jd2 = 0.0;       ///< the fraction
};

/// Parses ISO 8601 UTC: "2015-09-28T01:45:00Z", "2015-09-28T01:45:00.5Z",
/// "2015-09-28T01:45Z", "2015-09-28 01:45:00" (the Z is optional; UTC is assumed).
/// Throws std::invalid_argument quoting the text.
UtcTime parseUtc(const std::string& text);

/// "2015-09-28T01:45:00Z" (seconds rounded to the nearest whole second).
std::string formatUtc(UtcTime time);

/// The instant `seconds` SI seconds later (leap seconds counted, via TAI).
UtcTime addSeconds(UtcTime time, double seconds);

/// Terrestrial Time as a two-part Julian date (eraUtctai, eraTaitt).
void toTt(UtcTime time, double& tt1, double& tt2);
/// The UTC instant of a Terrestrial Time (TT, Meeus's TD) two-part Julian date.
UtcTime fromTt(double tt1, double tt2);

/// Seconds from a to b (b - a), leap seconds counted.
double secondsBetween(UtcTime a, UtcTime b);

} // namespace umbra::scene
