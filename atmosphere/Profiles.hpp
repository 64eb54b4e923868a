#pragma once
// Vertical density profiles of atmospheric components: the relative density (1 at the
// reference altitude, usually the ground) as a function of altitude, and its exact
// integral between two altitudes (for vertical optical depths and tests).
//   Exponential        exp(-h / H)            hydrostatic concentration (Costa Eq. 11, 14, 17)
//   DoubleExponential  exp(1 - e^{h / H})     1 at h = 0, falls off faster than exponential
//   Tent               max(0, 1 - |h - c| / w) the ozone layer (eclipse paper, Fig. 13;
//                                             Bruneton 2017: c = 25 km, w = 15 km)
//   Tabulated          linear interpolation of (altitudeM, value) pairs, 0 outside
#include <string>
#include <vector>

namespace umbra::atmosphere {

struct DensityProfile {
  enum class Kind { Exponential, DoubleExponential, Tent, Tabulated };

  Kind kind = Kind::Exponential;
  double scaleHeightM = 8000.0;  ///< Exponential, DoubleExponential: H
  double centreM = 0.0;          ///< Tent: altitude of the peak
  double halfWidthM = 0.0;       ///< Tent: distance from the peak to each zero
  std::vector<double> altitudesM;  ///< Tabulated: strictly increasing
  std::vector<double> values;      ///< Tabulated: relative densities, >= 0

  static DensityProfile exponential(double scaleHeightM);
  static DensityProfile doubleExponential(double scaleHeightM);
  static DensityProfile tent(double centreM, double halfWidthM);
  static DensityProfile tabulated(std::vector<double> altitudesM, std::vector<double> values);

  /// Relative density at an altitude above the bottom radius.
  double at(double altitudeM) const;

  /// Integral of `at` over [fromM, toM] in metres (negative when toM < fromM). Closed form
  /// for every kind (DoubleExponential through the exponential integral E1).
  double integral(double fromM, double toM) const;

  /// Empty when the parameters are valid, else what is wrong ("halfWidthM: expected a
  /// positive length, got 0"); the loader prefixes the file and field.
  std::string validate() const;

  /// Throws std::invalid_argument with `validate()`'s message when invalid.
  void check() const;
};

const char* kindName(DensityProfile::Kind kind);

}  // namespace umbra::atmosphere
