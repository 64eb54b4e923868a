#include "CraterField.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::terrain {
namespace {

/// splitmix64: small, fast, and the same everywhere.
class Random {
public:
  explicit Random(std::uint64_t seed) : state(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return (next() >> 11) * 0x1.0p-53; }  ///< [0, 1)

private:
  std::uint64_t state;
};

/// Height of one crater of radius R [texels] at distance r [texels] from its centre [m per D].
double craterProfile(double r, double R) {
  const double x = r / R;
  constexpr double depth = 0.2, rim = 0.04;
  if (x < 1.0) return rim - depth + depth * x * x;  // paraboloid bowl, floor 0.16 D below the plain
  return rim / (x * x * x);                         // ejecta, continuous at the rim
}

} // namespace

HeightField makeCraterField(const CraterFieldOptions& o) {
  if (o.size < 2 || o.size > 8192) throw std::invalid_argument("crater field: size must be 2..8192");
  if (!(o.spacingM > 0.0)) throw std::invalid_argument("crater field: spacing must be > 0 m");
  HeightField f;
  f.width = f.height = o.size;
  f.spacingM = o.spacingM;
  f.bodyRadiusM = o.bodyRadiusM;
  f.heightsM.assign(static_cast<std::size_t>(o.size) * o.size, 0.0);
  Random rng(o.seed);

  // A rolling plain: a few broad sinusoids with random phases (amplitude 1% of a wavelength).
  for (int k = 0; k < 6; ++k) {
    const double wavelength = o.size * (0.3 + 0.7 * rng.uniform());
    const double angle = 2.0 * 3.14159265358979323846 * rng.uniform();
    const double phase = 2.0 * 3.14159265358979323846 * rng.uniform();
    const double amp = 0.01 * wavelength * o.spacingM / (k + 1);
    const double kx = std::cos(angle) * 2.0 * 3.14159265358979323846 / wavelength;
    const double ky = std::sin(angle) * 2.0 * 3.14159265358979323846 / wavelength;
    for (int j = 0; j < o.size; ++j)
      for (int i = 0; i < o.size; ++i) f.heightsM[static_cast<std::size_t>(j) * o.size + i] += amp * std::sin(kx * i + ky * j + phase);
  }

  // Size bins of a factor of two, largest first; each holds `density` of the field's area.
  const double area = double(o.size) * o.size;
  const double dMax = std::max(o.smallestDiameterTexels, o.largestDiameterFraction * o.size);
  for (double dHi = dMax; dHi >= o.smallestDiameterTexels * 1.0001; dHi *= 0.5) {
    const double dLo = std::max(0.5 * dHi, o.smallestDiameterTexels);
    const double dMid = 0.5 * (dLo + dHi);
    const int count = static_cast<int>(std::ceil(o.density * area / (0.785398 * dMid * dMid)));
    for (int c = 0; c < count; ++c) {
      // D^-2 cumulative law within the bin: inverse transform of D^-3 density.
      const double v = rng.uniform();
      const double D = 1.0 / std::sqrt((1.0 - v) / (dLo * dLo) + v / (dHi * dHi));
      const double cx = rng.uniform() * (o.size - 1), cy = rng.uniform() * (o.size - 1);
      const double R = 0.5 * D, reach = 3.0 * R, dM = D * o.spacingM;
      const int i0 = std::max(0, int(std::floor(cx - reach))), i1 = std::min(o.size - 1, int(std::ceil(cx + reach)));
      const int j0 = std::max(0, int(std::floor(cy - reach))), j1 = std::min(o.size - 1, int(std::ceil(cy + reach)));
      const double edge = craterProfile(reach, R);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const double r = std::hypot(i - cx, j - cy);
          if (r >= reach) continue;
          // Superposed; minus the value at the reach so that the ejecta ends at 0.
          f.heightsM[static_cast<std::size_t>(j) * o.size + i] += (craterProfile(r, R) - edge) * dM;
        }
    }
  }
  return f;
}

} // namespace umbra::terrain
