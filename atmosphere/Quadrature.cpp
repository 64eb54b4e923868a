#include "Quadrature.hpp"

#include <cmath>

namespace umbra::atmosphere {

GaussLegendreRule::GaussLegendreRule(int n) : x(n), w(n) {
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double t = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = t;  // P_0, P_1; then the recurrence up to P_n
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-16) break;
    }
    x[i] = t, w[i] = 2.0 / ((1.0 - t * t) * dp * dp);
  }
}

} // namespace umbra::atmosphere
