#include "Components.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <stdexcept>

namespace umbra::atmosphere {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string number(double x) {
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

/// K(w) = 1/2 + e^{-w}/w + (e^{-w} - 1)/w^2 (van de Hulst's ADA kernel). Its series,
/// sum_{n>=3} (-1)^{n-1} (n-1)/n! w^{n-2} = w/3 - w^2/8 + w^3/30 - w^4/144 + ..., for
/// small |w|.
std::complex<double> adaKernel(std::complex<double> w) {
  if (std::abs(w) < 0.1) {
    std::complex<double> sum = 0.0, power = w;  // w^{n-2}
    double factorial = 6.0;                    // n!
    for (int n = 3; n <= 12; ++n) {
      const double sign = (n % 2 == 1) ? 1.0 : -1.0;
      sum += sign * (n - 1) / factorial * power;
      power *= w;
      factorial *= n + 1;
    }
    return sum;
  }
  const std::complex<double> e = std::exp(-w);
  return 0.5 + e / w + (e - 1.0) / (w * w);
}

void requirePositive(double x, const char* what) {
  if (!std::isfinite(x) || !(x > 0.0))
    throw std::invalid_argument(std::string(what) + ": expected a positive number, got " + number(x));
}

}  // namespace

// ---- WavelengthTable --------------------------------------------------------------------

WavelengthTable WavelengthTable::constant(double value) {
  WavelengthTable t;
  t.wavelengthsNm = {550.0};
  t.values = {value};
  return t;
}

double WavelengthTable::at(double wavelengthNm) const {
  if (values.empty()) return 0.0;
  if (values.size() == 1 || wavelengthNm <= wavelengthsNm.front()) return values.front();
  if (wavelengthNm >= wavelengthsNm.back()) return values.back();
  const auto upper = std::upper_bound(wavelengthsNm.begin(), wavelengthsNm.end(), wavelengthNm);
  const std::size_t i = static_cast<std::size_t>(upper - wavelengthsNm.begin());
  const double f = (wavelengthNm - wavelengthsNm[i - 1]) / (wavelengthsNm[i] - wavelengthsNm[i - 1]);
  return values[i - 1] + f * (values[i] - values[i - 1]);
}

std::vector<double> WavelengthTable::at(const std::vector<double>& lambdasNm) const {
  std::vector<double> out;
  out.reserve(lambdasNm.size());
  for (double l : lambdasNm) out.push_back(at(l));
  return out;
}

std::string WavelengthTable::validate(bool allowNegative) const {
  if (values.empty()) return "values: expected at least one value";
  if (wavelengthsNm.size() != values.size())
    return "values: expected as many values as wavelengths (" + std::to_string(wavelengthsNm.size()) +
           "), got " + std::to_string(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(wavelengthsNm[i]) || !(wavelengthsNm[i] > 0.0))
      return "wavelengthsNm[" + std::to_string(i) + "]: expected a positive wavelength in nm, got " +
             number(wavelengthsNm[i]);
    if (i > 0 && !(wavelengthsNm[i] > wavelengthsNm[i - 1]))
      return "wavelengthsNm[" + std::to_string(i) + "]: expected strictly increasing wavelengths, got " +
             number(wavelengthsNm[i]) + " after " + number(wavelengthsNm[i - 1]);
    if (!std::isfinite(values[i]) || (!allowNegative && values[i] < 0.0))
      return "values[" + std::to_string(i) + "]: expected a finite number" +
             std::string(allowNegative ? "" : " >= 0") + ", got " + number(values[i]);
  }
  return {};
}

// ---- molecules --------------------------------------------------------------------------

double airRefractivityPeckReeder(double wavelengthNm) {
  const double s2 = std::pow(1000.0 / wavelengthNm, 2);  // (1/um)^2
  return (8060.51 + 2480990.0 / (132.274 - s2) + 17455.7 / (39.32957 - s2)) * 1e-8;
}

double co2RefractivityBideauMehu(double wavelengthNm) {
  const double nu2 = std::pow(1e7 / wavelengthNm, 2);  // (1/cm)^2
  const double sum = 5799.25 / (128908.9 * 128908.9 - nu2) + 120.05 / (89223.8 * 89223.8 - nu2) +
                     5.3334 / (75037.5 * 75037.5 - nu2) - 4.3244 / (67837.7 * 67837.7 - nu2) +
                     0.1218145e-4 / (2418.136 * 2418.136 - nu2);
  return 1.1427e3 * sum;
}

const char* dispersionName(Dispersion dispersion) {
  switch (dispersion) {
    case Dispersion::None: return "none";
    case Dispersion::PeckReeder1972Air: return "peck-reeder-1972";
    case Dispersion::BideauMehu1973CO2: return "bideau-mehu-1973-co2";
  }
  return "?";
}

double dispersionRatio(Dispersion dispersion, double wavelengthNm, double referenceWavelengthNm) {
  switch (dispersion) {
    case Dispersion::None: return 1.0;
    case Dispersion::PeckReeder1972Air:
      return airRefractivityPeckReeder(wavelengthNm) / airRefractivityPeckReeder(referenceWavelengthNm);
    case Dispersion::BideauMehu1973CO2:
      return co2RefractivityBideauMehu(wavelengthNm) / co2RefractivityBideauMehu(referenceWavelengthNm);
  }
  return 1.0;
}

double kingFactor(double depolarisation) {
  return (6.0 + 3.0 * depolarisation) / (6.0 - 7.0 * depolarisation);
}

double rayleighScatteringPerM(double refractivity, double numberDensityPerM3, double wavelengthNm,
                              double depolarisation) {
  const double lambdaM = wavelengthNm * 1e-9;
  const double n2m1 = refractivity * (2.0 + refractivity);  // n^2 - 1 without cancellation
  return 8.0 * kPi * kPi * kPi * n2m1 * n2m1 /
         (3.0 * numberDensityPerM3 * std::pow(lambdaM, 4)) * kingFactor(depolarisation);
}

double rayleighCrossSectionM2(double referenceRefractivity, double referenceNumberDensityPerM3,
                              double wavelengthNm, double depolarisation) {
  return rayleighScatteringPerM(referenceRefractivity, referenceNumberDensityPerM3, wavelengthNm,
                                depolarisation) /
         referenceNumberDensityPerM3;
}

// ---- aerosols ---------------------------------------------------------------------------

double vanDeHulstScatteringPerM(double turbidity, double jungeExponent, double K, double wavelengthNm) {
  const double lambdaM = wavelengthNm * 1e-9;
  const double concentration = (0.65 * turbidity - 0.65) * 1e-16;  // C(T)
  return 0.434 * concentration * kPi * std::pow(2.0 * kPi / lambdaM, jungeExponent - 2.0) * K;
}

double anomalousDiffractionExtinctionEfficiency(double radiusM, double realIndex, double imagIndex,
                                                double wavelengthNm) {
  requirePositive(radiusM, "radiusM");
  requirePositive(wavelengthNm, "wavelengthNm");
  if (!std::isfinite(realIndex) || !(realIndex > 1.0))
    throw std::invalid_argument("real refractive index: expected a number > 1, got " + number(realIndex));
  if (!std::isfinite(imagIndex) || imagIndex < 0.0)
    throw std::invalid_argument("imaginary refractive index: expected a number >= 0, got " +
                                number(imagIndex));
  const double lambdaM = wavelengthNm * 1e-9;
  const double rho = 4.0 * kPi * radiusM * (realIndex - 1.0) / lambdaM;
  const double tanB = imagIndex / (realIndex - 1.0);
  const std::complex<double> w(rho * tanB, rho);  // rho (tan b + i)
  if (std::abs(w) < 0.1) return 4.0 * adaKernel(w).real();
  // Eq. 19 as printed.
  const double b = std::atan(tanB);
  const double c = std::cos(b) / rho;
  const double damp = std::exp(-rho * tanB);
  return 2.0 - 4.0 * damp * c * std::sin(rho - b) - 4.0 * damp * c * c * std::cos(rho - 2.0 * b) +
         4.0 * c * c * std::cos(2.0 * b);
}

double anomalousDiffractionAbsorptionEfficiency(double radiusM, double imagIndex, double wavelengthNm) {
  requirePositive(radiusM, "radiusM");
  requirePositive(wavelengthNm, "wavelengthNm");
  if (!std::isfinite(imagIndex) || imagIndex < 0.0)
    throw std::invalid_argument("imaginary refractive index: expected a number >= 0, got " +
                                number(imagIndex));
  const double w = 8.0 * kPi * radiusM * imagIndex / (wavelengthNm * 1e-9);  // 4 x k
  return 2.0 * adaKernel(std::complex<double>(w, 0.0)).real();
}

double anomalousDiffractionExtinctionPerM(double radiusM, double realIndex, double imagIndex,
                                          double numberDensityPerM3, double wavelengthNm) {
  return kPi * radiusM * radiusM *
         anomalousDiffractionExtinctionEfficiency(radiusM, realIndex, imagIndex, wavelengthNm) *
         numberDensityPerM3;
}

// ---- components -------------------------------------------------------------------------

bool Component::scatters() const {
  return std::any_of(scatteringPerM.begin(), scatteringPerM.end(), [](double b) { return b > 0.0; });
}

std::string Component::validate(std::size_t wavelengthCount) const {
  if (scatteringPerM.size() != wavelengthCount)
    return "scatteringPerM: expected " + std::to_string(wavelengthCount) + " values, got " +
           std::to_string(scatteringPerM.size());
  if (absorptionPerM.size() != wavelengthCount)
    return "absorptionPerM: expected " + std::to_string(wavelengthCount) + " values, got " +
           std::to_string(absorptionPerM.size());
  if (phases.size() != wavelengthCount)
    return "phase: expected " + std::to_string(wavelengthCount) + " phase functions, got " +
           std::to_string(phases.size());
  // At most 1 per metre: air at sea level scatters 1e-5, a Martian dust storm 1e-3; past 1
  // the optical depths of a whole path overflow the tables' exponentials.
  for (std::size_t i = 0; i < wavelengthCount; ++i) {
    if (!(scatteringPerM[i] >= 0.0 && scatteringPerM[i] <= 1.0))
      return "scatteringPerM[" + std::to_string(i) + "]: expected a coefficient from 0 to 1 in 1/m, got " +
             number(scatteringPerM[i]);
    if (!(absorptionPerM[i] >= 0.0 && absorptionPerM[i] <= 1.0))
      return "absorptionPerM[" + std::to_string(i) + "]: expected a coefficient from 0 to 1 in 1/m, got " +
             number(absorptionPerM[i]);
  }
  const std::string profile = density.validate();
  if (!profile.empty()) return "density." + profile;
  return {};
}

Component tabulatedComponent(std::string name, DensityProfile density, std::vector<double> scatteringPerM,
                             std::vector<double> absorptionPerM, std::vector<PhaseFunction> phases) {
  Component c;
  c.name = std::move(name);
  c.density = std::move(density);
  c.scatteringPerM = std::move(scatteringPerM);
  c.absorptionPerM = std::move(absorptionPerM);
  c.phases = std::move(phases);
  const std::string problem = c.validate(c.scatteringPerM.size());
  if (!problem.empty()) throw std::invalid_argument(c.name + ": " + problem);
  return c;
}

}  // namespace umbra::atmosphere
