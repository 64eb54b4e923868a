#pragma once
// The optics of atmospheric components (Costa et al., "Interactive visualization of
// atmospheric effects for celestial bodies", sections 4.1-4.3):
//   molecules  Rayleigh scattering from the refractive index, the number density and the
//              King factor of the depolarisation (Eq. 11), with standard dispersion
//              formulas for air (Peck & Reeder 1972) and CO2 (Bideau-Mehu et al. 1973);
//   absorbers  number density x absorption cross-section (Eq. 13, 15), used for O3 and O2;
//   aerosols   van de Hulst's scattering (Eq. 17) and the anomalous-diffraction extinction
//              of absorbing spheres (Eq. 19-20); the tabulated hook for Lorenz-Mie results.
// A Component bundles a density profile with per-wavelength coefficients (at relative
// density 1) and per-wavelength phase functions.
#include "Phase.hpp"
#include "Profiles.hpp"

#include <string>
#include <vector>

namespace umbra::atmosphere {

inline constexpr double kBoltzmannJPerK = 1.380649e-23;  ///< exact (SI 2019)
/// Number density of an ideal gas at 288.15 K and 101325 Pa [1/m^3] = 2.546899e25: the
/// conditions of the Peck & Reeder and Bideau-Mehu formulas and of the US Standard
/// Atmosphere 1976 sea level.
inline constexpr double kStandardNumberDensityPerM3 = 101325.0 / (kBoltzmannJPerK * 288.15);

/// A quantity tabulated against wavelength: linear interpolation between the samples,
/// the end values beyond them (documented in docs/atmosphere-format.md). One sample is a
/// constant.
struct WavelengthTable {
  std::vector<double> wavelengthsNm;  ///< strictly increasing, positive
  std::vector<double> values;

  static WavelengthTable constant(double value);
  double at(double wavelengthNm) const;
  std::vector<double> at(const std::vector<double>& wavelengthsNm) const;
  /// Empty when valid: sizes agree, wavelengths positive and increasing, values finite
  /// (and >= 0 unless allowNegative).
  std::string validate(bool allowNegative = false) const;
};

// ---- molecules (Costa section 4.1) ------------------------------------------------------

/// n - 1 of dry standard air at 15 degC, 101325 Pa (0.03 % CO2), Peck & Reeder 1972,
/// J. Opt. Soc. Am. 62, 958, Eq. 2 (valid 230-1690 nm):
///   10^8 (n - 1) = 8060.51 + 2480990 / (132.274 - s^2) + 17455.7 / (39.32957 - s^2),
///   s = 1 / lambda in 1/um. Gives Costa Table 1's 1.00027598 (680 nm) and 1.00027783
///   (550 nm). Costa's third value, 1.00028276, is this formula at 400 nm, not 440 nm.
double airRefractivityPeckReeder(double wavelengthNm);

/// n - 1 of CO2 at 15 degC, 101325 Pa: Bideau-Mehu, Guern, Abjean & Johannin-Gilles 1973,
/// Opt. Commun. 9, 432, in the form of Sneep & Ubachs 2005 (JQSRT 92, 293), Eq. 13
/// (valid 180-1700 nm), nu the wavenumber in 1/cm:
///   n - 1 = 1.1427e3 (5799.25 / (128908.9^2 - nu^2) + 120.05 / (89223.8^2 - nu^2)
///           + 5.3334 / (75037.5^2 - nu^2) - 4.3244 / (67837.7^2 - nu^2)
///           + 0.1218145e-4 / (2418.136^2 - nu^2)).
/// Scaled to 0 degC it is within 0.5 % of Costa Table 1's CO2 indices (1.00044661,
/// 1.00045019, 1.00045558 at 680, 550, 440 nm; the rest is CO2's non-ideality at 1 atm).
double co2RefractivityBideauMehu(double wavelengthNm);

/// The dispersion formulas above (or none: a constant n - 1).
enum class Dispersion { None, PeckReeder1972Air, BideauMehu1973CO2 };
const char* dispersionName(Dispersion dispersion);
/// n - 1 at `wavelengthNm` divided by n - 1 at `referenceWavelengthNm` (1 for None).
double dispersionRatio(Dispersion dispersion, double wavelengthNm, double referenceWavelengthNm);

/// King correction factor f(delta) = (6 + 3 delta) / (6 - 7 delta) (Costa Eq. 11).
double kingFactor(double depolarisation);

/// Costa Eq. 11 at h = 0, literally: 8 pi^3 (n^2 - 1)^2 / (3 N lambda^4) f(delta) [1/m],
/// with n = 1 + refractivity the index of the gas *at number density N*.
double rayleighScatteringPerM(double refractivity, double numberDensityPerM3, double wavelengthNm,
                              double depolarisation);

/// Rayleigh cross-section per molecule [m^2] from the index n_ref measured at number
/// density N_ref: Eq. 11 divided by N, 8 pi^3 (n_ref^2 - 1)^2 / (3 N_ref^2 lambda^4) f(delta).
/// It does not depend on the density (n - 1 is proportional to N for a dilute gas), so
/// beta = sigma N at any density: the consistent way to use Eq. 11 away from the
/// conditions where n was measured (Mars, or Earth at altitude).
double rayleighCrossSectionM2(double referenceRefractivity, double referenceNumberDensityPerM3,
                              double wavelengthNm, double depolarisation);

// ---- aerosols (Costa section 4.3) -------------------------------------------------------

/// Costa Eq. 17 at h = 0 (after Preetham et al. 1999 and van de Hulst):
///   beta = 0.434 C(T) pi (2 pi / lambda)^(nu - 2) K [1/m], C(T) = (0.65 T - 0.65) 1e-16,
/// T the turbidity (>= 1), nu Junge's exponent (in [2, 6]), K the wavelength-dependent
/// fudge factor, lambda in metres.
double vanDeHulstScatteringPerM(double turbidity, double jungeExponent, double K, double wavelengthNm);

/// Costa Eq. 19: the anomalous-diffraction extinction efficiency of an absorbing sphere
/// of radius r and index m + ik (van de Hulst 1957, section 11.22), with
///   rho = 4 pi r (m - 1) / lambda, tan beta = k / (m - 1):
///   Q = 2 - 4 e^{-rho tan b} (cos b / rho) sin(rho - b)
///         - 4 e^{-rho tan b} (cos b / rho)^2 cos(rho - 2 b) + 4 (cos b / rho)^2 cos 2b.
/// Requires m > 1, k >= 0. For small |rho| (< 0.1) the equivalent series of
/// 4 Re K(rho (tan b + i)) is used, the closed form losing all digits there.
double anomalousDiffractionExtinctionEfficiency(double radiusM, double realIndex, double imagIndex,
                                                double wavelengthNm);

/// The absorption efficiency of the same approximation, Q_abs = 2 K(w) with
/// K(w) = 1/2 + e^{-w}/w + (e^{-w} - 1)/w^2 and w = 8 pi r k / lambda (van de Hulst 1957,
/// Eq. 11.22-(3)); Costa does not print it, we use it for the single-scattering albedo.
double anomalousDiffractionAbsorptionEfficiency(double radiusM, double imagIndex, double wavelengthNm);

/// Costa Eq. 20 at h = 0: pi r^2 Q_ext N [1/m], one particle size.
double anomalousDiffractionExtinctionPerM(double radiusM, double realIndex, double imagIndex,
                                          double numberDensityPerM3, double wavelengthNm);

// ---- components -------------------------------------------------------------------------

struct Component {
  std::string name;                     ///< "molecules", "aerosols", "ozone", ...
  DensityProfile density;               ///< relative density, 1 where the coefficients hold
  std::vector<double> scatteringPerM;   ///< at relative density 1, one per wavelength
  std::vector<double> absorptionPerM;   ///< at relative density 1, one per wavelength
  std::vector<PhaseFunction> phases;    ///< one per wavelength; unused where scattering is 0

  const PhaseFunction& phase(std::size_t wavelengthIndex) const { return phases.at(wavelengthIndex); }
  double extinctionPerM(std::size_t wavelengthIndex) const {
    return scatteringPerM[wavelengthIndex] + absorptionPerM[wavelengthIndex];
  }
  bool scatters() const;  ///< any scattering coefficient > 0

  /// Empty when valid for `wavelengthCount` wavelengths: sizes, coefficients finite and
  /// >= 0, a valid profile.
  std::string validate(std::size_t wavelengthCount) const;
};

/// The Lorenz-Mie hook: a component from precomputed per-wavelength coefficients (at
/// relative density 1) and tabulated phase functions (one per wavelength, see
/// PhaseFunction::tabulated). Throws std::invalid_argument when inconsistent.
Component tabulatedComponent(std::string name, DensityProfile density,
                             std::vector<double> scatteringPerM, std::vector<double> absorptionPerM,
                             std::vector<PhaseFunction> phases);

}  // namespace umbra::atmosphere
