#include "PlanetMagnitudes.hpp"

#include <cmath>
#include <stdexcept>

namespace umbra::sky {
namespace {

double distanceTerm(double rAu, double deltaAu) { return 5.0 * std::log10(rAu * deltaAu); }

/// c[0] + c[1] a + ... (Horner).
template <int N>
double polynomial(const double (&c)[N], double a) {
  double v = 0.0;
  for (int k = N - 1; k >= 0; --k) v = v * a + c[k];
  return v;
}

// Mallama 2007, tables 6 (rotation) and 8 (orbit): the correction every 10 degrees from
// -20 to 370 (the circle's ends repeated for the interpolation's differences), magnitudes.
constexpr double kMarsRotation[40] = {
    0.024,  0.034,  0.036,  0.045,  0.038,  0.023,  0.015,  0.011,  0.000,  -0.012,
    -0.018, -0.036, -0.044, -0.059, -0.060, -0.055, -0.043, -0.041, -0.041, -0.036,
    -0.036, -0.018, -0.038, -0.011, 0.002,  0.004,  0.018,  0.019,  0.035,  0.050,
    0.035,  0.027,  0.037,  0.048,  0.025,  0.022,  0.024,  0.034,  0.036,  0.045};
constexpr double kMarsOrbit[40] = {
    -0.030, -0.017, -0.029, -0.017, -0.014, -0.006, -0.018, -0.020, -0.014, -0.030,
    -0.008, -0.040, -0.024, -0.037, -0.036, -0.032, 0.010,  0.010,  -0.001, 0.044,
    0.025,  -0.004, -0.016, -0.008, 0.029,  -0.054, -0.033, 0.055,  0.017,  0.052,
    0.006,  0.087,  0.006,  0.064,  0.030,  0.019,  -0.030, -0.017, -0.029, -0.017};

/// Stirling's central-difference interpolation (to fourth differences) of a table every
/// 10 degrees (entry k at 10 (k - 2) degrees) at `angleDeg`, wrapped to [0, 360).
double stirling(const double (&table)[40], double angleDeg) {
  double a = std::fmod(angleDeg, 360.0);
  if (a < 0.0) a += 360.0;
  if (!(a < 360.0)) a = 0.0;  // -1e-17 wraps to 360
  const int node = static_cast<int>(a / 10.0);  // 0..35
  const double p = a / 10.0 - node;
  const double* f = &table[node + 2];  // f[-2] .. f[2]
  const double d1 = 0.5 * (f[1] - f[-1]);
  const double d2 = f[1] - 2.0 * f[0] + f[-1];
  const double d3 = 0.5 * ((f[2] - 3.0 * f[1] + 3.0 * f[0] - f[-1]) + (f[1] - 3.0 * f[0] + 3.0 * f[-1] - f[-2]));
  const double d4 = f[2] - 4.0 * f[1] + 6.0 * f[0] - 4.0 * f[-1] + f[-2];
  return f[0] + p * d1 + 0.5 * p * p * d2 + p * (p * p - 1.0) / 6.0 * d3 + p * p * (p * p - 1.0) / 24.0 * d4;
}

}  // namespace

double planetBMinusV(const std::string& planet) {
  static const std::pair<const char*, double> kColours[] = {
      {"Mercury", 0.97}, {"Venus", 0.81}, {"Mars", 1.43}, {"Jupiter", 0.87}, {"Saturn", 1.09}};
  for (const auto& [name, bv] : kColours)
    if (planet == name) return bv;
  throw std::invalid_argument("no colour index for '" + planet + "'");
}

double mercuryMagnitudeV(double r, double delta, double a) {
  static constexpr double c[7] = {-0.613, 6.3280e-2, -1.6336e-3, 3.3644e-5, -3.4265e-7, 1.6893e-9, -3.0334e-12};
  return distanceTerm(r, delta) + polynomial(c, a);
}

double venusMagnitudeV(double r, double delta, double a) {
  static constexpr double low[5] = {-4.384, -1.044e-3, 3.687e-4, -2.814e-6, 8.938e-9};
  static constexpr double high[3] = {236.05828, -2.81914, 8.39034e-3};
  return distanceTerm(r, delta) + (a < 163.7 ? polynomial(low, a) : polynomial(high, a));
}

double jupiterMagnitudeV(double r, double delta, double a) {
  static constexpr double low[3] = {-9.395, -3.7e-4, 6.16e-4};
  static constexpr double high[6] = {1.0, -1.507, -0.363, -0.062, 2.809, -1.876};
  if (a <= 12.0) return distanceTerm(r, delta) + polynomial(low, a);
  return distanceTerm(r, delta) - 9.428 - 2.5 * std::log10(polynomial(high, a / 180.0));
}

double saturnRingTiltDeg(double sunLat, double observerLat) {
  const double product = sunLat * observerLat;
  return product > 0.0 ? std::sqrt(product) : 0.0;
}

double saturnMagnitudeV(double r, double delta, double a, double sunLat, double observerLat) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double b = saturnRingTiltDeg(sunLat, observerLat);
  if (a <= 6.5 && b <= 27.0) {
    const double s = std::sin(b * kDeg);
    return distanceTerm(r, delta) - 8.914 - 1.825 * s + 0.026 * a - 0.378 * s * std::exp(-2.25 * a);
  }
  return saturnGlobeMagnitudeV(r, delta, a);
}

double saturnGlobeMagnitudeV(double r, double delta, double a) {
  static constexpr double low[3] = {-8.95, -3.7e-4, 6.16e-4};
  static constexpr double high[5] = {-8.94, 2.446e-4, 2.672e-4, -1.506e-6, 4.767e-9};
  return distanceTerm(r, delta) + (a <= 6.5 ? polynomial(low, a) : polynomial(high, a));
}

double marsRotationCorrection(double cm) { return stirling(kMarsRotation, cm); }
double marsOrbitCorrection(double ls) { return stirling(kMarsOrbit, ls); }

double marsMagnitudeV(double r, double delta, double a, const MarsAspect& m) {
  static constexpr double low[3] = {-1.601, 2.267e-2, -1.302e-4};
  static constexpr double high[3] = {-0.367, -0.02573, 3.445e-4};
  double cm = 0.5 * (m.subObserverLonDeg + m.subSolarLonDeg);
  if (std::abs(m.subObserverLonDeg - m.subSolarLonDeg) > 180.0) cm += 180.0;
  return distanceTerm(r, delta) + (a <= 50.0 ? polynomial(low, a) : polynomial(high, a)) +
         marsRotationCorrection(cm) + marsOrbitCorrection(m.heliocentricEclipticLonDeg - 85.0);
}

}  // namespace umbra::sky
