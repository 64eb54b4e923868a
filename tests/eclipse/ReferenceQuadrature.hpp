#pragma once
// An independent reference for the visible fraction of the limb-darkened Sun: integrate
// over the angle theta around the Sun's centre, with the radial integral in closed form
// (the library integrates over the radius instead, numerically). Composite Simpson in a
// variable that clusters nodes at the square-root end points.
#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::test {

inline double radialFlux(double rho, double u) {  // int_0^rho L(r) r dr, L with mean 1
  rho = std::clamp(rho, 0.0, 1.0);
  const double s = 1.0 - rho * rho;
  return ((1.0 - u) * rho * rho / 2.0 + u * (1.0 - s * std::sqrt(s)) / 3.0) / (1.0 - u / 3.0);
}

template <class F>
inline double clusteredSimpson(double a, double b, int n, F f) {
  // theta = a + (b - a) (1 - cos(pi t)) / 2, t in [0, 1]
  constexpr double pi = 3.14159265358979323846;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    const double theta = a + (b - a) * (1.0 - std::cos(pi * t)) / 2.0;
    const double jac = (b - a) * pi * std::sin(pi * t) / 2.0;
    sum += w * f(theta) * jac;
  }
  return sum / (3.0 * n);
}

inline double radialFluxOutside(double rho, double u) {  // int_rho^1 L(r) r dr
  rho = std::clamp(rho, 0.0, 1.0);
  const double s = (1.0 - rho) * (1.0 + rho);
  return ((1.0 - u) * s / 2.0 + u * s * std::sqrt(s) / 3.0) / (1.0 - u / 3.0);
}

struct ReferenceFractions {
  double visible;  ///< integrated directly, so accurate relative to itself when tiny
  double hidden;   ///< likewise
};

/// Visible and hidden fractions of the unit solar disc behind an occluder disc of radius
/// R whose centre is d away (both in solar radii), linear limb darkening u. Each is
/// integrated on its own, so that the smaller keeps its relative accuracy.
inline ReferenceFractions referenceFractions(double R, double d, double u, int n = 200000) {
  constexpr double pi = 3.14159265358979323846;
  if (d >= 1.0 + R) return {1.0, 0.0};
  // The ray from the Sun's centre at angle theta (0 = towards the occluder) is inside
  // the occluder between lo and hi.
  auto interval = [&](double theta, double& lo, double& hi) {
    const double disc = R * R - d * d * std::sin(theta) * std::sin(theta);
    if (disc <= 0.0) return false;
    lo = d * std::cos(theta) - std::sqrt(disc);
    hi = d * std::cos(theta) + std::sqrt(disc);
    return hi > 0.0;
  };
  auto hidden = [&](double theta) {
    double lo, hi;
    if (!interval(theta, lo, hi)) return 0.0;
    return radialFlux(hi, u) - radialFlux(std::max(lo, 0.0), u);
  };
  auto visible = [&](double theta) {
    double lo, hi;
    if (!interval(theta, lo, hi)) return 0.5;
    return radialFlux(std::max(lo, 0.0), u) + radialFluxOutside(hi, u);
  };
  const double thetaMax = d > R ? std::asin(R / d) : pi;
  // kink where a boundary of the hidden interval crosses the solar limb
  const double c1 = (1.0 + d * d - R * R) / (2.0 * d);
  std::vector<double> cuts{0.0};
  if (c1 > -1.0 && c1 < 1.0 && std::acos(c1) < thetaMax) cuts.push_back(std::acos(c1));
  cuts.push_back(thetaMax);
  double h = 0.0, v = (pi - thetaMax) * 0.5;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    h += clusteredSimpson(cuts[k], cuts[k + 1], n, hidden);
    v += clusteredSimpson(cuts[k], cuts[k + 1], n, visible);
  }
  return {2.0 * v / pi, 2.0 * h / pi};  // both half planes; the disc's flux is pi
}

/// The reference value, from whichever side is smaller.
inline double referenceVisibleFraction(double R, double d, double u) {
  const ReferenceFractions f = referenceFractions(R, d, u);
  return f.visible < 0.5 ? f.visible : 1.0 - f.hidden;
}

/// Textbook lens area of two circles (radii 1 and R, centres d apart), partial overlap.
inline double textbookLensArea(double R, double d) {
  const double r = 1.0;
  return r * r * std::acos((d * d + r * r - R * R) / (2 * d * r)) +
         R * R * std::acos((d * d + R * R - r * r) / (2 * d * R)) -
         0.5 * std::sqrt((-d + r + R) * (d + r - R) * (d - r + R) * (d + r + R));
}

} // namespace umbra::test
