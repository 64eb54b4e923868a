#include "StarLight.hpp"

#include <algorithm>
#include <cmath>

namespace umbra::sky {

double irradianceRelativeToSun(double vMag) { return std::pow(10.0, -0.4 * (vMag - kSunVMag)); }

double ballesterosTemperatureK(double bMinusV) {
  const double bv = std::clamp(bMinusV, -0.4, 2.0);
  return 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
}

}  // namespace umbra::sky
