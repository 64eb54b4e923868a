// The Gauss-Legendre rule (atmosphere/Quadrature.hpp): exact for polynomials of degree
// 2n - 1 on [-1, 1] (closed form: int x^k = 2 / (k + 1) for even k, 0 for odd), not for
// degree 2n (checked up to n = 8: past it the error of x^2n is below rounding), nodes inside (-1, 1) in descending order, and the known 2-point rule.
#include "Quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace umbra::atmosphere {
namespace {

double integrate(const GaussLegendreRule& q, int k) {
  double s = 0.0;
  for (std::size_t i = 0; i < q.x.size(); ++i) s += q.w[i] * std::pow(q.x[i], k);
  return s;
}

TEST(GaussLegendreRule, ExactToDegreeTwoNMinusOne) {
  for (int n : {1, 2, 3, 8, 12, 24, 32}) {
    const GaussLegendreRule q(n);
    ASSERT_EQ(q.x.size(), static_cast<std::size_t>(n));
    for (int k = 0; k <= 2 * n - 1; ++k)
      EXPECT_NEAR(integrate(q, k), k % 2 ? 0.0 : 2.0 / (k + 1), 1e-13) << "n " << n << " x^" << k;
    if (n <= 8) { EXPECT_GT(std::abs(integrate(q, 2 * n) - 2.0 / (2 * n + 1)), 1e-6) << n; }  // degree 2n: not exact
    for (int i = 0; i < n; ++i) {
      EXPECT_GT(q.w[i], 0.0);
      EXPECT_LT(std::abs(q.x[i]), 1.0);
      if (i > 0) { EXPECT_LT(q.x[i], q.x[i - 1]); }
    }
  }
  const GaussLegendreRule two(2);
  EXPECT_NEAR(two.x[0], 1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(two.w[0], 1.0, 1e-15);
}

} // namespace
} // namespace umbra::atmosphere
