#pragma once
// Delta T = TT - UT1: the Earth's rotation against the ephemerides' uniform time.
#include <optional>
#include <string>

namespace umbra::scene {

/// Delta T and where it comes from.
struct DeltaT {
  double seconds = 0.0;
  /// "leap seconds" (1972 up to kDeltaTLeapSecondsEndYear: 32.184 s + TAI-UTC from ERFA's table,
  /// UT1 - UTC taken as 0, which it is to within 0.9 s) or "Espenak-Meeus 2006" (their
  /// polynomials, as NASA's Five Millennium Canons use them: fits to the historical record,
  /// and a published extrapolation after it).
  const char* source = "";
  /// False outside 1600-2200: there Delta T is known to minutes at best (hours in antiquity).
  bool wellKnown = true;
};

/// The end (decimal year, exclusive) of the span where Delta T is taken from the leap
/// seconds: the last year for which ERFA's table stands.
inline constexpr double kDeltaTLeapSecondsEndYear = 2027.0;

/// Delta T at a decimal year (2017.5 is mid-2017).
DeltaT deltaTAtYear(double year);

/// The decimal year of a Julian date (any time scale: a day is 3e-3 of a year).
double decimalYear(double jd);

/// Terrestrial Time of a UT1 Julian date, Delta T from deltaTAtYear.
double ttFromUt1(double ut1Jd);
/// The same with `deltaTSeconds` when one is given (a user's --delta-t), else deltaTAtYear's.
double ttFromUt1(double ut1Jd, const std::optional<double>& deltaTSeconds);
/// UT1 of a TT Julian date for `deltaTSeconds` (an eclipse's Delta T).
double ut1FromTt(double ttJd, double deltaTSeconds);

}  // namespace umbra::scene
