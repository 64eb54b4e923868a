#include "Spectrum.hpp"
#include "Colour.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace umbra::atmosphere {
namespace {

constexpr double kSolarFirstCentreNm = 365.0;  // centre of the [360, 370) bin
constexpr double kSolarBinNm = 10.0;
constexpr double kSolarMinNm = 360.0;
constexpr double kSolarMaxNm = 840.0;

double cieZbarAt(int i) { return i < detail::kCieZbarCount ? detail::kCieZbar[i] : 0.0; }

/// The solar spectrum as the shape that samples are divided by: the table with its end
/// values held beyond its range, so that it is positive at every wavelength.
double solarShape(double wavelengthNm) {
  return solarIrradianceWm2PerNm(std::clamp(wavelengthNm, kSolarMinNm, kSolarMaxNm));
}

/// The hat function of sorted node j at wavelength p: the weight of sample j in the linear
/// interpolant, held constant beyond the first and the last node.
double hat(const std::vector<double>& x, std::size_t j, double p) {
  const std::size_t n = x.size();
  if (n == 1) return 1.0;
  if (j == 0 && p <= x[0]) return 1.0;
  if (j == n - 1 && p >= x[n - 1]) return 1.0;
  if (j > 0 && p >= x[j - 1] && p <= x[j]) return (p - x[j - 1]) / (x[j] - x[j - 1]);
  if (j + 1 < n && p >= x[j] && p <= x[j + 1]) return (x[j + 1] - p) / (x[j + 1] - x[j]);
  return 0.0;
}

} // namespace

double solarIrradianceWm2PerNm(double wavelengthNm) {
  if (!(wavelengthNm >= kSolarMinNm && wavelengthNm <= kSolarMaxNm)) return 0.0;
  const double* v = detail::kSolarBinMeanWm2PerNm;
  constexpr int last = detail::kSolarBinCount - 1;
  const double u = (wavelengthNm - kSolarFirstCentreNm) / kSolarBinNm;
  if (u <= 0.0) return v[0];
  if (u >= last) return v[last];
  const int k = std::min(static_cast<int>(u), last - 1);
  const double t = u - k;
  return v[k] * (1.0 - t) + v[k + 1] * t;
}

glm::dvec3 cie1931(double wavelengthNm) {
  if (!(wavelengthNm >= kCmfMinNm && wavelengthNm <= kCmfMaxNm)) return glm::dvec3(0.0);
  const double u = wavelengthNm - kCmfMinNm;  // the table is at 1 nm steps
  const int i = std::min(static_cast<int>(u), detail::kCieCount - 2);
  const double t = u - i;
  return glm::dvec3(detail::kCieXbar[i] * (1.0 - t) + detail::kCieXbar[i + 1] * t,
                    detail::kCieYbar[i] * (1.0 - t) + detail::kCieYbar[i + 1] * t,
                    cieZbarAt(i) * (1.0 - t) + cieZbarAt(i + 1) * t);
}

WavelengthSet WavelengthSet::sampled(std::vector<double> nm, double minNm, double maxNm) {
  if (nm.empty()) throw std::invalid_argument("WavelengthSet: no wavelengths");
  if (!(std::isfinite(minNm) && std::isfinite(maxNm) && minNm < maxNm))
    throw std::invalid_argument("WavelengthSet: the band needs minNm < maxNm");
  for (double w : nm) {
    if (!(w >= minNm && w <= maxNm))
      throw std::invalid_argument("WavelengthSet: " + std::to_string(w) + " nm lies outside [" +
                                  std::to_string(minNm) + ", " + std::to_string(maxNm) + "] nm");
  }
  const std::size_t n = nm.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return nm[a] < nm[b]; });
  std::vector<double> x(n);
  for (std::size_t j = 0; j < n; ++j) x[j] = nm[order[j]];
  for (std::size_t j = 1; j < n; ++j) {
    if (!(x[j] > x[j - 1])) throw std::invalid_argument("WavelengthSet: repeated wavelength");
  }

  WavelengthSet set;
  set.nm = std::move(nm);
  set.binWidthNm.assign(n, 0.0);
  set.xyzWeightLmNmPerW.assign(n, glm::dvec3(0.0));

  // Bin widths: the integral of each hat over the band.
  for (std::size_t j = 0; j < n; ++j) {
    double w = 0.0;
    w += j == 0 ? x[0] - minNm : 0.5 * (x[j] - x[j - 1]);
    w += j == n - 1 ? maxNm - x[n - 1] : 0.5 * (x[j + 1] - x[j]);
    set.binWidthNm[order[j]] = n == 1 ? maxNm - minNm : w;
  }

  // Colour weights: 683 * integral cmf(l) E(l) / E(x_j) hat_j(l) dl over the band. Between
  // consecutive knots (whole nm for the CMF table, the solar bin centres, the samples)
  // every factor is linear, the product cubic, and Simpson's rule exact.
  const double lo = std::max(minNm, kCmfMinNm);
  const double hi = std::min(maxNm, kCmfMaxNm);
  if (lo < hi) {
    std::vector<double> knots{lo, hi};
    for (double w = std::ceil(lo); w < hi; w += 1.0) knots.push_back(w);
    for (int k = 0; k < detail::kSolarBinCount; ++k) knots.push_back(kSolarFirstCentreNm + kSolarBinNm * k);
    knots.insert(knots.end(), x.begin(), x.end());
    knots.erase(std::remove_if(knots.begin(), knots.end(), [&](double w) { return w < lo || w > hi; }),
                knots.end());
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());

    std::vector<double> sampleShape(n);
    for (std::size_t j = 0; j < n; ++j) sampleShape[j] = solarShape(x[j]);
    std::vector<glm::dvec3> sorted(n, glm::dvec3(0.0));
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
      const double a = knots[k], b = knots[k + 1];
      const double points[3] = {a, 0.5 * (a + b), b};
      const double simpson[3] = {(b - a) / 6.0, 4.0 * (b - a) / 6.0, (b - a) / 6.0};
      for (int q = 0; q < 3; ++q) {
        const double p = points[q];
        const glm::dvec3 g = kMaxLuminousEfficacyLmPerW * simpson[q] * solarShape(p) * cie1931(p);
        for (std::size_t j = 0; j < n; ++j) {
          const double h = hat(x, j, p);
          if (h != 0.0) sorted[j] += g * (h / sampleShape[j]);
        }
      }
    }
    for (std::size_t j = 0; j < n; ++j) set.xyzWeightLmNmPerW[order[j]] = sorted[j];
  }
  return set;
}

WavelengthSet WavelengthSet::uniform(int count, double minNm, double maxNm) {
  if (count < 1) throw std::invalid_argument("WavelengthSet::uniform: count must be >= 1");
  if (!(minNm < maxNm)) throw std::invalid_argument("WavelengthSet::uniform: needs minNm < maxNm");
  std::vector<double> nm(static_cast<std::size_t>(count));
  const double width = (maxNm - minNm) / count;
  for (int i = 0; i < count; ++i) nm[static_cast<std::size_t>(i)] = minNm + (i + 0.5) * width;
  WavelengthSet set = sampled(std::move(nm), minNm, maxNm);
  set.binWidthNm.assign(set.nm.size(), width);  // the same values, without rounding
  return set;
}

WavelengthSet WavelengthSet::rgb() { return sampled({680.0, 550.0, 440.0}, kCmfMinNm, kCmfMaxNm); }

glm::dvec3 spectralRadianceToXyz(const WavelengthSet& set, const std::vector<double>& radiance) {
  const std::size_t n = set.nm.size();
  if (radiance.size() != n)
    throw std::invalid_argument("spectralRadianceToXyz: " + std::to_string(radiance.size()) +
                                " radiances for " + std::to_string(n) + " wavelengths");
  glm::dvec3 xyz(0.0);
  if (!set.xyzWeightLmNmPerW.empty()) {
    if (set.xyzWeightLmNmPerW.size() != n)
      throw std::invalid_argument("spectralRadianceToXyz: colour weights do not match the wavelengths");
    for (std::size_t i = 0; i < n; ++i) xyz += radiance[i] * set.xyzWeightLmNmPerW[i];
    return xyz;
  }
  if (set.binWidthNm.size() != n)
    throw std::invalid_argument("spectralRadianceToXyz: bin widths do not match the wavelengths");
  for (std::size_t i = 0; i < n; ++i) xyz += (radiance[i] * set.binWidthNm[i]) * cie1931(set.nm[i]);
  return kMaxLuminousEfficacyLmPerW * xyz;
}

glm::dvec3 xyzToLinearSrgb(const glm::dvec3& c) {
  // IEC 61966-2-1:1999, XYZ (D65) to linear sRGB.
  return glm::dvec3(3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
                    -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
                    0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z);
}

glm::dvec3 linearSrgbToXyz(const glm::dvec3& c) {
  // IEC 61966-2-1:1999, linear sRGB to XYZ (D65).
  return glm::dvec3(0.4124 * c.r + 0.3576 * c.g + 0.1805 * c.b, colour::luminance(c),
                    0.0193 * c.r + 0.1192 * c.g + 0.9505 * c.b);
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double luminanceCdM2(const WavelengthSet& set, const std::vector<double>& radiance) {
  return spectralRadianceToXyz(set, radiance).y;
}

glm::dvec3 spectralRadianceToLinearSrgb(const WavelengthSet& set, const std::vector<double>& radiance) {
  return xyzToLinearSrgb(spectralRadianceToXyz(set, radiance));
}

} // namespace umbra::atmosphere
