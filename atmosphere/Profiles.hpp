#pragma once
// Vertical density profiles of atmospheric components: the relative density (1 at the
// reference altitude, usually the ground) as a function of altitude, and its exact
// integral between two altitudes (for vertical optical depths and tests).
//   Exponential        exp(-h / H)            hydrostatic concentration (Costa Eq. 11, 14, 17)
//   DoubleExponential  exp(1 - e^{h / H})     1 at h = 0, falls off faster than exponential
//   Tent               max(0, 1 - |h - c| / w) the ozone layer (eclipse paper, Fig. 13;
//                                             Bruneton 2017: c = 25 km, w = 15 km)
//   Tabulated          linear interpolation of (altitudeM, value) pairs, 0 outside
//   BoundaryLayer      an aerosol's two tropospheric layers (OPAC, Hess, Koepke & Schult
//                      1998): exp(-h / H) in the mixing layer below the boundary layer's
//                      top B, then f exp(-(h - B) / H_ft) in the free troposphere up to
//                      its top T (f below B), 0 above; each step blended over a zone w wide centred
//                      on it (the entrainment zone; smoothstep, so the density and its
//                      slope are continuous; w = 0: steps)
#include <string>
#include <vector>

namespace umbra::atmosphere {

struct DensityProfile {
  enum class Kind { Exponential, DoubleExponential, Tent, Tabulated, BoundaryLayer };

  Kind kind = Kind::Exponential;
  double scaleHeightM = 8000.0;  ///< Exponential, DoubleExponential, BoundaryLayer: H
  double centreM = 0.0;          ///< Tent: altitude of the peak
  double halfWidthM = 0.0;       ///< Tent: distance from the peak to each zero
  std::vector<double> altitudesM;  ///< Tabulated: strictly increasing
  std::vector<double> values;      ///< Tabulated: relative densities, >= 0
  double boundaryLayerTopM = 2000.0;        ///< BoundaryLayer: B, the mixing layer's top
  double freeTroposphereDensity = 0.0;      ///< BoundaryLayer: f, relative density just above B
  double freeTroposphereScaleHeightM = 8000.0;  ///< BoundaryLayer: H_ft
  double freeTroposphereTopM = 12000.0;     ///< BoundaryLayer: T (>= B)
  double transitionM = 0.0;                 ///< BoundaryLayer: w, < 2 B and <= T - B (when T > B)

  static DensityProfile exponential(double scaleHeightM);
  static DensityProfile doubleExponential(double scaleHeightM);
  static DensityProfile tent(double centreM, double halfWidthM);
  static DensityProfile tabulated(std::vector<double> altitudesM, std::vector<double> values);
  static DensityProfile boundaryLayer(double topM, double scaleHeightM, double freeDensity,
                                      double freeScaleHeightM, double freeTopM, double transitionM = 0.0);

  /// Altitudes where the profile or its derivative jumps (the tent's corners, the
  /// tabulated points, the layers' tops): integrations split there.
  std::vector<double> kinksM() const;

  /// Relative density at an altitude above the bottom radius.
  double at(double altitudeM) const;

  /// Integral of `at` over [fromM, toM] in metres (negative when toM < fromM). Closed form
  /// for every kind (DoubleExponential through the exponential integral E1) but across the
  /// boundary layer's blending zones (Gauss-Legendre, 24 points: to rounding).
  double integral(double fromM, double toM) const;

  /// Empty when the parameters are valid, else what is wrong ("halfWidthM: expected a
  /// positive length, got 0"); the loader prefixes the file and field.
  std::string validate() const;

  /// Throws std::invalid_argument with `validate()`'s message when invalid.
  void check() const;
};

const char* kindName(DensityProfile::Kind kind);

}  // namespace umbra::atmosphere
