#include "Corona.hpp"

#include <algorithm>
#include <cmath>

namespace umbra::sky {
namespace {
// Baumbach's coefficients and exponents (Corona.hpp), times 1e-6.
constexpr double kScale = 1e-6;
constexpr double kF = 0.0532, kFExponent = 2.5;
constexpr double kK1 = 1.425, kK1Exponent = 7.0;
constexpr double kK2 = 2.565, kK2Exponent = 17.0;
}  // namespace

double fCoronaRelativeRadiance(double rho) {
  if (!(rho >= 1.0)) return 0.0;
  return kScale * kF * std::pow(rho, -kFExponent);
}

double coronaRelativeRadiance(double rho) {
  if (!(rho >= 1.0)) return 0.0;
  return fCoronaRelativeRadiance(rho) + kScale * (kK1 * std::pow(rho, -kK1Exponent) + kK2 * std::pow(rho, -kK2Exponent));
}

double coronaFluxFractionOutside(double rho0) {
  const double r = std::max(rho0, 1.0);
  // 2 int_r^inf c rho^(1 - n) drho = 2 c r^(2 - n) / (n - 2) for each term c rho^-n.
  const auto term = [&](double c, double n) { return 2.0 * c * std::pow(r, 2.0 - n) / (n - 2.0); };
  return kScale * (term(kF, kFExponent) + term(kK1, kK1Exponent) + term(kK2, kK2Exponent));
}

}  // namespace umbra::sky
