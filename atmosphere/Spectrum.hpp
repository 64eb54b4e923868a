#pragma once
// Spectra and colour: the wavelengths the atmosphere is computed at, the top-of-atmosphere
// solar spectrum, and the conversion of spectral radiance to CIE XYZ, luminance and
// linear sRGB through the CIE 1931 2-degree colour-matching functions.
//
// Units: wavelengths in nm (as the tables are), spectral radiance in W m^-2 sr^-1 nm^-1,
// spectral irradiance in W m^-2 nm^-1, luminance (and X, Y, Z) in cd m^-2.
//
// How a set of samples becomes a colour (WavelengthSet::uniform, ::rgb, ::sampled)
// --------------------------------------------------------------------------------
// The atmosphere is computed at a few wavelengths only (15, or 3), so turning its samples
// L_i into a colour needs a rule for the spectrum between them. Everything umbra renders is
// sunlight changed by smooth factors (Rayleigh ~ lambda^-4, ozone, aerosols, transmittance
// along a ray), while the solar spectrum itself has structure between the samples (the dark
// 380-400 nm bins, the jump at 400 nm, the G band at 430 nm). So the *ratio* to sunlight is
// interpolated, not the radiance:
//
//     L(lambda) = E(lambda) r(lambda),   r piecewise linear through r_i = L_i / E(lambda_i),
//
// held constant from the first and last sample out to the band edges [minNm, maxNm], and
// zero outside the band. E is the solar spectrum below (solarIrradianceWm2PerNm). Then
// X = 683 lm/W * integral L xbar dlambda (likewise Y, Z) is linear in the samples:
// XYZ = sum_i L_i xyzWeightLmNmPerW[i], with the weights integrated once, exactly (Simpson
// on the pieces where xbar, E and the interpolation are all linear). The rule is exact for
// the Sun itself at any number of samples, and for any spectrum E times a piecewise-linear
// factor; reconstructed spectra are never negative when the samples are not.
//
// In the 3-wavelength mode (rgb(): 680, 550, 440 nm, in R, G, B order) each of R, G, B is
// a combination of all three samples (a 3x3 matrix). For a Rayleigh sky (sunlight times
// lambda^-4) that colour is off by 0.003 in x and 0.010 in y (too green: the chord of
// lambda^-4 between 440 and 550 nm lies above it); with 15 samples by less than 5e-4
// (tests/atmosphere/test_spectrum.cpp). Bruneton's precomputed_atmospheric_scattering
// (atmosphere/model.cc, ComputeSpectralRadianceToLuminanceFactors; Bruneton 2016, "A
// Qualitative and Quantitative Evaluation of 8 Clear Sky Models", Sect. 14.3) instead
// treats the three samples as linear sRGB directly, each scaled by its own "spectral
// radiance to luminance" factor k_c = 683 integral cbar(lambda) E(lambda)/E(lambda_c)
// (lambda/lambda_c)^p dlambda (cbar: the sRGB colour-matching function; p = 0 for the Sun,
// p = -3 for the sky): each channel assumes the whole spectrum has the shape
// E(lambda) (lambda/lambda_c)^p. Both are exact for the bare Sun (Bruneton's with p = 0).
// On the Rayleigh sky above, his p = -3 factors do better (sRGB R and G relative to B off by
// -5 % and -1 %, ours +3 % and +10 %), but they need the right exponent per use; ours gives
// sky and Sun the same matrix and is the same rule as with 15 samples.
// With more than 3 samples Bruneton multiplies each sample by the colour-matching functions
// at that wavelength and the bin width (the point rule below).
//
// A set built by hand (xyzWeightLmNmPerW left empty) uses the point rule instead: each
// sample is a line of width binWidthNm[i], XYZ = 683 sum_i binWidthNm[i] L_i cmf(lambda_i).
// That is right for a monochromatic line, or for a fine (1-5 nm) grid.
#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace umbra::atmosphere {

/// Luminous efficacy of 555 nm (540 THz) radiation, the SI definition of the candela [lm/W].
inline constexpr double kMaxLuminousEfficacyLmPerW = 683.0;
/// Range of the colour-matching function tables [nm].
inline constexpr double kCmfMinNm = 360.0;
inline constexpr double kCmfMaxNm = 830.0;

struct WavelengthSet {
  /// Sample wavelengths: ascending for uniform() and sampled(), R, G, B for rgb().
  std::vector<double> nm;
  /// Quadrature weights: integral f dlambda over the band ~ sum_i binWidthNm[i] f(nm[i]).
  /// For the factory sets, the integral of the linear interpolant of the samples (held
  /// constant out to the band edges), so they sum to the band's width.
  std::vector<double> binWidthNm;
  /// X, Y, Z [cd m^-2] produced by a unit spectral radiance (1 W m^-2 sr^-1 nm^-1) at
  /// sample i, i.e. [lm nm / W]; the solar-ratio rule in the header comment. Empty in a
  /// set built by hand: then the point rule is used.
  std::vector<glm::dvec3> xyzWeightLmNmPerW;

  std::size_t size() const { return nm.size(); }

  /// count samples at the centres of equal bins of [minNm, maxNm] (as Bruneton's
  /// 15-wavelength mode places them); every binWidthNm is (maxNm - minNm) / count.
  static WavelengthSet uniform(int count = 15, double minNm = 360.0, double maxNm = 830.0);
  /// 680, 550, 440 nm, in that (R, G, B) order, over the band 360-830 nm; bin widths
  /// 215, 120, 135 nm. Colour from the solar-ratio rule (header comment).
  static WavelengthSet rgb();
  /// Any distinct wavelengths inside [minNm, maxNm], kept in the order given.
  static WavelengthSet sampled(std::vector<double> nm, double minNm = kCmfMinNm,
                               double maxNm = kCmfMaxNm);
};

/// Top-of-atmosphere solar spectral irradiance at 1 au [W m^-2 nm^-1]: the ASTM G173-03
/// extraterrestrial spectrum in 10 nm bin means (360-840 nm; the whole spectrum integrates
/// to 1366.1 W m^-2), linearly interpolated between the bin centres (365, 375, ..., 835 nm),
/// the end bins' values held out to 360 and 840 nm, and 0 outside (no data).
double solarIrradianceWm2PerNm(double wavelengthNm);

/// CIE 1931 2-degree colour-matching functions (xbar, ybar, zbar) from the 1 nm CIE table,
/// linearly interpolated; 0 outside 360-830 nm.
glm::dvec3 cie1931(double wavelengthNm);

/// X, Y, Z of a spectrum given by its samples at set.nm, with Y the luminance [cd m^-2]
/// (683 lm/W). Throws std::invalid_argument when the sizes differ.
glm::dvec3 spectralRadianceToXyz(const WavelengthSet& set, const std::vector<double>& radianceWm2SrNm);

/// Linear sRGB (IEC 61966-2-1, D65 white, its 4-decimal matrix): XYZ (0.9505, 1, 1.089)
/// maps to (1, 1, 1). Out-of-gamut colours give negative components; nothing is clamped.
glm::dvec3 xyzToLinearSrgb(const glm::dvec3& xyz);

/// Its converse, the standard's own 4-decimal matrix (so the two round-trip to about 1e-4).
glm::dvec3 linearSrgbToXyz(const glm::dvec3& linearSrgb);

/// The sRGB transfer function undone (IEC 61966-2-1): an encoded component in [0, 1] to its
/// linear value (c / 12.92 up to 0.04045, ((c + 0.055) / 1.055)^2.4 above).
double srgbToLinear(double encoded);

/// Luminance [cd m^-2] of the sampled spectrum: the Y of spectralRadianceToXyz.
double luminanceCdM2(const WavelengthSet& set, const std::vector<double>& radianceWm2SrNm);

/// xyzToLinearSrgb(spectralRadianceToXyz(set, radiance)).
glm::dvec3 spectralRadianceToLinearSrgb(const WavelengthSet& set,
                                        const std::vector<double>& radianceWm2SrNm);

namespace detail {
// The tables (SpectralData.cpp).
inline constexpr int kCieCount = 471;      // 360..830 nm, 1 nm
inline constexpr int kCieZbarCount = 291;  // 360..650 nm; zbar is 0 from 650 nm on
extern const double kCieXbar[kCieCount];
extern const double kCieYbar[kCieCount];
extern const double kCieZbar[kCieZbarCount];
inline constexpr int kSolarBinCount = 48;  // [360, 370), ..., [830, 840) nm
extern const double kSolarBinMeanWm2PerNm[kSolarBinCount];
} // namespace detail

} // namespace umbra::atmosphere
