#pragma once
// Helpers for the atmosphere-model tests (test_model_*.cpp): independent adaptive
// quadrature, the wavelength sets the tests use, and preset loading.
#include "Atmosphere.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <vector>

namespace umbra::test {

inline constexpr double kPi = 3.14159265358979323846;

/// int_a^b f, adaptive Gauss-Kronrod (61 points), relative tolerance 1e-13.
template <class F>
double integrate(F f, double a, double b) {
  double error = 0.0;
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, a, b, 20, 1e-13, &error);
}

/// Integral over the sphere of a function of cos theta: 2 pi int_{-1}^{1} f(mu) dmu.
template <class F>
double integrateSphere(F f) {
  return 2.0 * kPi * integrate(f, -1.0, 1.0);
}

/// Same for a phase function (or its moments: p(mu) * weight(mu)); a tabulated one is
/// integrated piece by piece between its samples, where it is linear.
template <class P, class W>
double integrateSphere(const P& phase, W weight) {
  const auto f = [&](double mu) { return phase(mu) * weight(mu); };
  if (phase.kind() != P::Kind::Tabulated) return integrateSphere(f);
  const std::vector<double>& mu = phase.cosThetaSamples();
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < mu.size(); ++i)
    sum += boost::math::quadrature::gauss_kronrod<double, 15>::integrate(f, mu[i], mu[i + 1], 0, 0.0);
  return 2.0 * kPi * sum;
}

inline std::vector<double> threeWavelengthsNm() { return {680.0, 550.0, 440.0}; }

/// 15 wavelengths evenly from 360 to 830 nm (Bruneton's and CosmoScout's spectral sets).
inline std::vector<double> fifteenWavelengthsNm() {
  std::vector<double> w;
  for (int i = 0; i < 15; ++i) w.push_back(360.0 + (830.0 - 360.0) * i / 14.0);
  return w;
}

}  // namespace umbra::test
