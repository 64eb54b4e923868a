// The corona's radial profile (sky/Corona.hpp): Baumbach's formula at 1.1, 1.5, 2 and 4
// solar radii (worked by hand), its F part, and its flux against a quadrature of the profile.
#include "Corona.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace umbra::sky {
namespace {

TEST(Corona, BaumbachsProfileAtItsPublishedTerms) {
  // 1e-6 (0.0532 rho^-2.5 + 1.425 rho^-7 + 2.565 rho^-17), term by term:
  //   1.1: 0.0532 / 1.269059 + 1.425 / 1.948717 + 2.565 / 5.054470 = 0.041921 + 0.731250 + 0.507472
  //   1.5: 0.0532 / 2.755676 + 1.425 / 17.085938 + 2.565 / 985.261253 = 0.019306 + 0.083402 + 0.002603
  //   2:   0.0532 / 5.656854 + 1.425 / 128 + 2.565 / 131072 = 0.009405 + 0.011133 + 0.0000196
  //   4:   0.0532 / 32 + 1.425 / 16384 + 2.565 / 4^17 = 0.0016625 + 0.0000870 + 1.5e-10
  EXPECT_NEAR(coronaRelativeRadiance(1.1), 1.280643e-6, 2e-12);
  EXPECT_NEAR(coronaRelativeRadiance(1.5), 0.105311e-6, 2e-12);
  EXPECT_NEAR(coronaRelativeRadiance(2.0), 0.020557e-6, 2e-12);
  EXPECT_NEAR(coronaRelativeRadiance(4.0), 0.0017495e-6, 2e-13);
  // Beyond 2.08 radii the dust (F) corona outshines the electrons' (K).
  EXPECT_LT(fCoronaRelativeRadiance(2.0), 0.5 * coronaRelativeRadiance(2.0));
  EXPECT_GT(fCoronaRelativeRadiance(4.0), 0.9 * coronaRelativeRadiance(4.0));
  EXPECT_EQ(coronaRelativeRadiance(0.99), 0.0);
  EXPECT_EQ(coronaRelativeRadiance(std::numeric_limits<double>::quiet_NaN()), 0.0);
}

TEST(Corona, ItsFluxIsTheProfileIntegratedOverRings) {
  for (double rho0 : {1.0, 1.03, 1.5, 3.0}) {
    // Rings out to 1e4 radii, in log rho (the F corona's tail falls as rho^-0.5).
    const auto ring = [](double logRho) {
      const double rho = std::exp(logRho);
      return 2.0 * coronaRelativeRadiance(rho) * rho * rho;
    };
    double error = 0.0;
    const double numeric = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        ring, std::log(rho0), std::log(1e4), 15, 1e-13, &error);
    EXPECT_NEAR(coronaFluxFractionOutside(rho0) - coronaFluxFractionOutside(1e4), numeric, 1e-10 * numeric) << rho0;
  }
  // About a millionth of the Sun from the limb out (magnitude -11.9 against the Sun's
  // -26.74: as bright as the full Moon to within a magnitude).
  EXPECT_NEAR(coronaFluxFractionOutside(1.0), 1.1248e-6, 1e-12);
}

}  // namespace
}  // namespace umbra::sky
