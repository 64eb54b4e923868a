#include "Humidity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace umbra::atmosphere {

double waterRefractiveIndexReal(double wavelengthNm) {
  // Hale & Querry 1973, Table 1 (25 C), every 50 nm to 800 nm, then 900 and 1000 nm.
  static constexpr std::array<std::pair<double, double>, 13> kRows{{{300.0, 1.349},
                                                                    {350.0, 1.343},
                                                                    {400.0, 1.339},
                                                                    {450.0, 1.337},
                                                                    {500.0, 1.335},
                                                                    {550.0, 1.333},
                                                                    {600.0, 1.332},
                                                                    {650.0, 1.331},
                                                                    {700.0, 1.331},
                                                                    {750.0, 1.330},
                                                                    {800.0, 1.329},
                                                                    {900.0, 1.328},
                                                                    {1000.0, 1.327}}};
  if (!(wavelengthNm > kRows.front().first)) return kRows.front().second;
  if (!(wavelengthNm < kRows.back().first)) return kRows.back().second;
  std::size_t i = 1;
  while (kRows[i].first < wavelengthNm) ++i;
  const auto& [x0, y0] = kRows[i - 1];
  const auto& [x1, y1] = kRows[i];
  return y0 + (y1 - y0) * (wavelengthNm - x0) / (x1 - x0);
}

double growthFactor(const std::vector<double>& relativeHumidity, const std::vector<double>& radiusFactor,
                    double humidity) {
  if (relativeHumidity.empty() || relativeHumidity.size() != radiusFactor.size())
    throw std::invalid_argument("expected as many radius factors as relative humidities, at least one");
  for (std::size_t i = 0; i < relativeHumidity.size(); ++i) {
    const double h = relativeHumidity[i], f = radiusFactor[i];
    if (!(h >= 0.0 && h < 1.0) || (i > 0 && !(h > relativeHumidity[i - 1])))
      throw std::invalid_argument("relativeHumidity[" + std::to_string(i) + "]: expected increasing values in [0, 1)");
    if (!(f >= 1.0 && f <= 100.0))
      throw std::invalid_argument("radiusFactor[" + std::to_string(i) + "]: expected a factor in [1, 100]");
  }
  if (!(humidity > relativeHumidity.front())) return radiusFactor.front();
  if (!(humidity < relativeHumidity.back())) return radiusFactor.back();
  std::size_t i = 1;
  while (relativeHumidity[i] < humidity) ++i;
  const double t = (humidity - relativeHumidity[i - 1]) / (relativeHumidity[i] - relativeHumidity[i - 1]);
  return radiusFactor[i - 1] + t * (radiusFactor[i] - radiusFactor[i - 1]);
}

std::complex<double> humidRefractiveIndex(std::complex<double> dry, double waterReal, double factor) {
  const double dryShare = 1.0 / (factor * factor * factor);
  return std::complex<double>(waterReal, 0.0) + (dry - std::complex<double>(waterReal, 0.0)) * dryShare;
}

}  // namespace umbra::atmosphere
