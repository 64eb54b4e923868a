#include "scene/DeltaT.hpp"

#include <erfa.h>

#include <cmath>

namespace umbra::scene {
namespace {

/// Espenak & Meeus (2006), "Polynomial expressions for Delta T", as NASA's Five Millennium
/// Canons of Solar and Lunar Eclipses use them (seconds).
double espenakMeeus(double y) {
  if (y < -500.0) {
    const double u = (y - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u;
  }
  if (y < 500.0) {
    const double u = y / 100.0;
    return 10583.6 + u * (-1014.41 + u * (33.78311 + u * (-5.952053 + u * (-0.1798452 + u * (0.022174192 + u * 0.0090316521)))));
  }
  if (y < 1600.0) {
    const double u = (y - 1000.0) / 100.0;
    return 1574.2 + u * (-556.01 + u * (71.23472 + u * (0.319781 + u * (-0.8503463 + u * (-0.005050998 + u * 0.0083572073)))));
  }
  if (y < 1700.0) {
    const double t = y - 1600.0;
    return 120.0 + t * (-0.9808 + t * (-0.01532 + t / 7129.0));
  }
  if (y < 1800.0) {
    const double t = y - 1700.0;
    return 8.83 + t * (0.1603 + t * (-0.0059285 + t * (0.00013336 - t / 1174000.0)));
  }
  if (y < 1860.0) {
    const double t = y - 1800.0;
    return 13.72 + t * (-0.332447 + t * (0.0068612 + t * (0.0041116 + t * (-0.00037436 + t * (0.0000121272 + t * (-0.0000001699 + t * 0.000000000875))))));
  }
  if (y < 1900.0) {
    const double t = y - 1860.0;
    return 7.62 + t * (0.5737 + t * (-0.251754 + t * (0.01680668 + t * (-0.0004473624 + t / 233174.0))));
  }
  if (y < 1920.0) {
    const double t = y - 1900.0;
    return -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - t * 0.000197)));
  }
  if (y < 1941.0) {
    const double t = y - 1920.0;
    return 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
  }
  if (y < 1961.0) {
    const double t = y - 1950.0;
    return 29.07 + t * (0.407 + t * (-1.0 / 233.0 + t / 2547.0));
  }
  if (y < 1986.0) {
    const double t = y - 1975.0;
    return 45.45 + t * (1.067 + t * (-1.0 / 260.0 - t / 718.0));
  }
  if (y < 2005.0) {
    const double t = y - 2000.0;
    return 63.86 + t * (0.3345 + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))));
  }
  if (y < 2050.0) {
    const double t = y - 2000.0;
    return 62.92 + t * (0.32217 + t * 0.005589);
  }
  const double u = (y - 1820.0) / 100.0;
  if (y < 2150.0) return -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y);
  return -20.0 + 32.0 * u * u;
}

}  // namespace

double decimalYear(double jd) { return 2000.0 + (jd - 2451544.5) / 365.2425; }

DeltaT deltaTAtYear(double year) {
  DeltaT d;
  d.wellKnown = year >= 1600.0 && year < 2200.0;
  if (year >= 1972.0 && year < kDeltaTLeapSecondsEndYear) {
    // TT - UTC = 32.184 s + TAI - UTC; the date's TAI - UTC from ERFA's leap-second table.
    const int iy = static_cast<int>(std::floor(year));
    const double dayOfYear = (year - iy) * 365.2425;
    double jd0 = 0.0, jd1 = 0.0;
    eraCal2jd(iy, 1, 1, &jd0, &jd1);
    int y = 0, m = 0, day = 0;
    double fraction = 0.0, dat = 0.0;
    if (eraJd2cal(jd0, jd1 + dayOfYear, &y, &m, &day, &fraction) == 0 && eraDat(y, m, day, fraction, &dat) >= 0) {
      d.seconds = 32.184 + dat;
      d.source = "leap seconds";
      return d;
    }
  }
  d.seconds = espenakMeeus(year);
  d.source = "Espenak-Meeus 2006";
  return d;
}

double ttFromUt1(double ut1Jd) {
  // Delta T changes by < 1 s a year: one step from the UT1 year is exact to microseconds.
  return ut1Jd + deltaTAtYear(decimalYear(ut1Jd)).seconds / 86400.0;
}

double ttFromUt1(double ut1Jd, const std::optional<double>& deltaTSeconds) {
  return deltaTSeconds ? ut1Jd + *deltaTSeconds / 86400.0 : ttFromUt1(ut1Jd);
}

double ut1FromTt(double ttJd, double deltaTSeconds) { return ttJd - deltaTSeconds / 86400.0; }

}  // namespace umbra::scene
