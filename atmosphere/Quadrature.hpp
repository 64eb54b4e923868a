#pragma once
// Quadrature rules shared by the precomputations.
#include <vector>

namespace umbra::atmosphere {

/// The n-point Gauss-Legendre rule on [-1, 1]: nodes x (descending) and weights w, the roots
/// of the Legendre polynomial P_n by Newton's method from Tricomi's estimate,
/// w = 2 / ((1 - x^2) P_n'(x)^2). Exact for polynomials of degree 2n - 1.
struct GaussLegendreRule {
  std::vector<double> x, w;
  explicit GaussLegendreRule(int n);
};

} // namespace umbra::atmosphere
